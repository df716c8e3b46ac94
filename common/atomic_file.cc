#include "common/atomic_file.h"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>

#include "common/error.h"

namespace m4mesh {

static Error io_error(const std::string& path, const std::string& what) {
  return Error(ErrorKind::kIo, "", kNoPlane, kNoOffset,
               path + ": " + what + ": " + std::strerror(errno));
}

AtomicFile::AtomicFile(std::string path) : path_(std::move(path)) {
  namespace fs = std::filesystem;
  if (path_ == "-") {
    file_ = stdout;
    return;
  }
  // A symlink (or a chain of them, even dangling) is followed to the file it names.
  std::error_code ignored;
  fs::path target = path_;
  for (int hops = 0; hops < 40 && fs::is_symlink(target, ignored); ++hops) {
    const fs::path next = fs::read_symlink(target, ignored);
    target = next.is_absolute() ? next : target.parent_path() / next;
  }
  path_ = target.string();
  const fs::file_status status = fs::status(path_, ignored);
  if (fs::is_character_file(status) || fs::is_fifo(status)) {
    file_ = std::fopen(path_.c_str(), "wb");
    if (file_ == nullptr) throw io_error(path_, "cannot open");
    return;
  }
  if (fs::is_directory(status)) throw Error(ErrorKind::kIo, "", kNoPlane, kNoOffset, path_ + ": a folder, not a file");
  temp_path_ = path_ + ".tmp." + std::to_string(::getpid());
  file_ = std::fopen(temp_path_.c_str(), "wb");
  if (file_ == nullptr) throw io_error(path_, "cannot create");
}

AtomicFile::~AtomicFile() {
  if (file_ == nullptr || file_ == stdout) return;
  std::fclose(file_);
  if (!temp_path_.empty()) std::remove(temp_path_.c_str());
}

void AtomicFile::write(std::string_view data) {
  if (std::fwrite(data.data(), 1, data.size(), file_) != data.size())
    throw io_error(path_, "cannot write");
}

void AtomicFile::restart() {
  if (temp_path_.empty()) throw Error(ErrorKind::kIo, "", kNoPlane, kNoOffset, path_ + ": what was written cannot be taken back");
  file_ = std::freopen(temp_path_.c_str(), "wb", file_);
  if (file_ == nullptr) throw io_error(path_, "cannot create");
}

void AtomicFile::commit() {
  std::FILE* file = file_;
  file_ = nullptr;
  if (file == stdout) {
    if (std::fflush(stdout) != 0) throw io_error("standard output", "cannot write");
    return;
  }
  if (std::fclose(file) != 0) {
    if (!temp_path_.empty()) std::remove(temp_path_.c_str());
    throw io_error(path_, "cannot close");
  }
  if (temp_path_.empty()) return;
  if (std::rename(temp_path_.c_str(), path_.c_str()) != 0) {
    std::remove(temp_path_.c_str());
    throw io_error(path_, "cannot rename into place");
  }
}

std::vector<uint8_t> read_file(const std::string& path) {
  if (path == "-") {
    // Read once and kept: a command may look at its input before it reads it.
    static std::optional<std::vector<uint8_t>> standard_input;
    if (!standard_input) {
      std::vector<uint8_t> bytes;
      uint8_t buffer[65536];
      for (size_t n; (n = std::fread(buffer, 1, sizeof buffer, stdin)) > 0;) bytes.insert(bytes.end(), buffer, buffer + n);
      if (std::ferror(stdin)) throw io_error("standard input", "cannot read");
      standard_input = std::move(bytes);
    }
    return *standard_input;
  }
  std::error_code ignored;
  if (std::filesystem::is_directory(path, ignored)) throw io_error(path, "a folder, not a file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw io_error(path, "cannot open");
  std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw io_error(path, "cannot read");
  return bytes;
}

void write_file_atomically(const std::string& path, std::string_view data) {
  AtomicFile file(path);
  file.write(data);
  file.commit();
}

}  // namespace m4mesh
