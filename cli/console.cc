#include "cli/console.h"

#include <unistd.h>

#include <cstdarg>
#include <cstdio>
#include <filesystem>

#include "common/error.h"

namespace m4mesh::console {

namespace {

Level g_level = Level::kNormal;
bool g_overwrite = false;
std::string g_input;

void vsay(const char* format, va_list args) {
  std::vfprintf(stderr, format, args);
  std::fputc('\n', stderr);
}

}  // namespace

void set_level(Level level) { g_level = level; }
void set_overwrite(bool overwrite) { g_overwrite = overwrite; }
bool overwrite() { return g_overwrite; }
void set_input(const std::string& path) { g_input = path == "-" ? "standard input" : path; }
const std::string& input() { return g_input; }
bool quiet() { return g_level == Level::kQuiet; }

void say(const char* format, ...) {
  if (g_level == Level::kQuiet) return;
  va_list args;
  va_start(args, format);
  vsay(format, args);
  va_end(args);
}

void detail(const char* format, ...) {
  if (g_level != Level::kVerbose) return;
  va_list args;
  va_start(args, format);
  vsay(format, args);
  va_end(args);
}

Progress::Progress(std::string what, size_t total)
    : Progress(std::move(what), total, stderr, isatty(fileno(stderr)) != 0, std::chrono::seconds(1)) {}

Progress::Progress(std::string what, size_t total, std::FILE* out, bool interactive, std::chrono::milliseconds after,
                   std::chrono::milliseconds log_every)
    : what_(std::move(what)),
      total_(total),
      out_(out),
      interactive_(interactive),
      after_(after),
      log_every_(log_every),
      start_(std::chrono::steady_clock::now()),
      logged_(start_) {}

Progress::~Progress() { finish(); }

void Progress::finish() {
  if (shown_) std::fprintf(out_, "\r%*s\r", static_cast<int>(what_.size() + 32), "");
  shown_ = false;
}

void Progress::update(size_t done, size_t total) {
  total_ = total;
  update(done);
}

void Progress::update(size_t done) {
  if (g_level == Level::kQuiet) return;
  if (!interactive_) {
    if (g_level != Level::kVerbose) return;
    const auto now = std::chrono::steady_clock::now();
    if (now - logged_ < log_every_) return;
    logged_ = now;
    std::fprintf(out_, "%s %zu/%zu\n", what_.c_str(), done, total_);
    std::fflush(out_);
    return;
  }
  if (!shown_ && std::chrono::steady_clock::now() - start_ < after_) return;
  shown_ = true;
  std::fprintf(out_, "\r%s %zu/%zu", what_.c_str(), done, total_);
  std::fflush(out_);
}

std::string counted(uint64_t count, const char* one, const char* many) { return std::to_string(count) + " " + (count == 1 ? one : many); }

void check_output(const std::string& path) {
  namespace fs = std::filesystem;
  if (path == "-" || g_overwrite) return;
  std::error_code error;
  const fs::file_status status = fs::status(path, error);
  const bool taken = fs::is_regular_file(status) || (fs::is_directory(status) && !fs::is_empty(path, error));
  if (taken) throw usage_error(path + ": exists; -y replaces it");
}

}  // namespace m4mesh::console
