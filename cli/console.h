// What the command line tells a person, by the conventions of codec tools
// (ffmpeg, x264, draco_encoder): data on standard output; summaries, notes,
// warnings and progress on standard error; -q keeps only errors, -v adds
// detail; an existing output is replaced only with -y.
#pragma once

#include <chrono>
#include <cstdint>
#include <cstddef>
#include <cstdio>
#include <string>

namespace m4mesh::console {

enum class Level { kQuiet, kNormal, kVerbose };
void set_level(Level level);
void set_overwrite(bool overwrite);
bool quiet();

// A summary, note or warning line on standard error (none with -q).
[[gnu::format(printf, 1, 2)]] void say(const char* format, ...);
// Detail, with -v only.
[[gnu::format(printf, 1, 2)]] void detail(const char* format, ...);

// A job's progress on standard error, without -q: on a terminal one line
// that rewrites itself once the job has run for a second; elsewhere (a
// file or a pipe) nothing, but with -v a line of its own every ten
// seconds.
class Progress {
 public:
  Progress(std::string what, size_t total);
  // The same on `out`: a line that rewrites itself when `interactive`, once
  // `after` has passed; else a line of its own every `log_every`.
  Progress(std::string what, size_t total, std::FILE* out, bool interactive, std::chrono::milliseconds after,
           std::chrono::milliseconds log_every = std::chrono::seconds(10));
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;
  void update(size_t done);
  // With a total the job learnt on the way.
  void update(size_t done, size_t total);
  // Clears the line, so that what comes next starts on a clean one.
  void finish();

 private:
  std::string what_;
  size_t total_;
  std::FILE* out_;
  bool interactive_;
  std::chrono::milliseconds after_, log_every_;
  std::chrono::steady_clock::time_point start_, logged_;
  bool shown_ = false;
};

// Refuses an output that exists as a file or as a folder that is not
// empty, unless -y; "-", character devices and FIFOs are written in place.
void check_output(const std::string& path);
// Whether -y was given.
bool overwrite();

// "1 frame", "2 frames": a count with its noun, singular for one.
std::string counted(uint64_t count, const char* one, const char* many);

// The input a command is reading, named by its errors ("-": standard input).
void set_input(const std::string& path);
const std::string& input();

}  // namespace m4mesh::console
