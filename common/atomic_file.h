// Output files that appear only when complete: data goes to a temporary
// file beside the target, which is renamed over it on commit(). A symlink
// is followed (its target is replaced, the link stays); a character
// device or a FIFO is written in place, and "-" is standard output, both
// streaming (they cannot be taken back on a failure).
#pragma once

#include <cstdio>
#include <string>
#include <string_view>
#include <vector>

namespace m4mesh {

class AtomicFile {
 public:
  explicit AtomicFile(std::string path);
  ~AtomicFile();  // removes the temporary file unless committed
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  void write(std::string_view data);
  // Drops what was written (an I/O error on standard output or a FIFO,
  // which cannot take it back).
  void restart();
  void commit();

 private:
  std::string path_;
  std::string temp_path_;  // empty when written in place
  std::FILE* file_ = nullptr;
};

// A whole file; "-" is standard input (read once, then the same bytes again).
std::vector<uint8_t> read_file(const std::string& path);
void write_file_atomically(const std::string& path, std::string_view data);

}  // namespace m4mesh
