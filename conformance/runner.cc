#include "conformance/runner.h"

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <thread>

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/md5.h"
#include "conformance/coverage.h"
#include "conformance/coverage3d.h"
#include "conformance/judge.h"
#include "conformance/manifest.h"

namespace m4mesh {

namespace {

namespace fs = std::filesystem;

struct Outcome {
  enum { kPass, kFail, kSkip } status;
  std::string detail;
};

std::string replace_all(std::string text, const std::string& from, const std::string& to) {
  for (size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size())) text.replace(at, from.size(), to);
  return text;
}

std::string quoted(const std::string& path) { return "'" + replace_all(path, "'", "'\\''") + "'"; }

// A folder of the run's own for the external decoder's outputs, removed at the end.
class TemporaryFolder {
 public:
  TemporaryFolder() {
    std::string pattern = (fs::temp_directory_path() / "m4mesh-conform-XXXXXX").string();
    if (!mkdtemp(pattern.data())) throw Error(ErrorKind::kIo, "", kNoPlane, kNoOffset, "cannot create a temporary folder in " + pattern);
    path_ = pattern;
  }
  ~TemporaryFolder() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

// The decoder's standard error, shortened, for a failed case.
std::string stderr_of(const fs::path& file) {
  if (!fs::exists(file)) return "";
  std::vector<uint8_t> text = read_file(file.string());
  if (text.size() > 300) text.resize(300);
  std::string s(text.begin(), text.end());
  for (char& c : s)
    if (c == '\n') c = ' ';
  return s.empty() ? "" : "; its stderr: " + s;
}

std::string seconds_text(double seconds) {
  std::ostringstream text;
  text << seconds;
  return text.str();
}

// Runs `command` with sh, its standard output to /dev/null and its standard
// error to `err`: its wait status, or none when it ran past `timeout`
// seconds (then its process group is killed).
std::optional<int> run_with_timeout(const std::string& command, const fs::path& err, double timeout) {
  const pid_t child = fork();
  if (child < 0) return -1;
  if (child == 0) {
    setpgid(0, 0);
    // A subshell, so that the command's own redirections win over these.
    const std::string line = "( " + command + " ) > /dev/null 2> " + quoted(err.string());
    execl("/bin/sh", "sh", "-c", line.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  setpgid(child, child);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout);
  auto pause = std::chrono::microseconds(200);
  for (int status = 0;;) {
    if (waitpid(child, &status, WNOHANG) == child) return status;
    if (std::chrono::steady_clock::now() >= deadline) {
      kill(-child, SIGKILL);
      waitpid(child, &status, 0);
      return std::nullopt;
    }
    std::this_thread::sleep_for(pause);
    pause = std::min(2 * pause, std::chrono::microseconds(20000));
  }
}

Outcome run_external(SuiteKind kind, const ManifestEntry& e, const std::string& stream_path, const std::string& command_template,
                     const fs::path& folder, double timeout_seconds) {
  if (kind == SuiteKind::kMesh2d && e.method != 2 && command_template.find("{method}") == std::string::npos)
    return {Outcome::kSkip, "needs Method I: put {method} in the decoder command"};
  // The extension tells a decoder such as m4mesh which output to write.
  const fs::path out = folder / (e.id + (kind == SuiteKind::kMesh3d ? ".f32" : ".txt")), err = folder / (e.id + ".stderr");
  std::string command = replace_all(command_template, "{in}", quoted(stream_path));
  command = replace_all(command, "{out}", quoted(out.string()));
  command = replace_all(command, "{method}", std::to_string(e.method));
  const std::optional<int> finished = run_with_timeout(command, err, timeout_seconds);
  if (!finished) return {Outcome::kFail, "no exit within " + seconds_text(timeout_seconds) + " s: killed" + stderr_of(err)};
  const int status = *finished;
  if (status == -1) return {Outcome::kFail, "the decoder could not be started"};
  // A crash fails any stream: the shell reports a command killed by signal N as 128 + N.
  const int signal = WIFSIGNALED(status) ? WTERMSIG(status) : WEXITSTATUS(status) > 128 && WEXITSTATUS(status) < 160 ? WEXITSTATUS(status) - 128 : 0;
  if (signal != 0) return {Outcome::kFail, "killed by signal " + std::to_string(signal) + stderr_of(err)};
  const int code = WEXITSTATUS(status);
  if (code == 126 || code == 127)
    return {Outcome::kFail, "exit " + std::to_string(code) + (code == 127 ? ": command not found" : ": command not executable") + stderr_of(err)};
  if (!e.valid)
    return code == 0 ? Outcome{Outcome::kFail, "exit status 0 for a stream that must be rejected (" + e.error_kind + ")"}
                     : Outcome{Outcome::kPass, "rejected (exit " + std::to_string(code) + ")"};
  if (code != 0) return {Outcome::kFail, "the decoder failed (exit " + std::to_string(code) + ")" + stderr_of(err)};
  if (!fs::exists(out)) return {Outcome::kFail, "the decoder wrote no output" + stderr_of(err)};
  const std::string md5 = md5_hex(read_file(out.string()));
  if (md5 != e.decoded_md5) return {Outcome::kFail, "decoded MD5 " + md5 + ", expected " + e.decoded_md5};
  return {Outcome::kPass, md5};
}

// Per area: the catalog's items the suite's valid streams reach, and the
// ones they do not.
void print_coverage(const fs::path& suite, const Manifest& manifest, std::ostream& out) {
  std::set<std::string> reached;
  std::map<std::string, std::set<std::string>> catalog;
  if (manifest.kind == SuiteKind::kMesh3d) {
    catalog = coverage_catalog3d();
    for (const ManifestEntry& e : manifest.entries)
      if (e.valid) reached.merge(coverage_items3d(read_file((suite / e.file).string())));
  } else {
    catalog["2d"] = required_value_classes();
    for (const ManifestEntry& e : manifest.entries) reached.insert(e.classes.begin(), e.classes.end());
  }
  size_t total = 0, hit = 0;
  std::ostringstream missing;
  for (const auto& [area, items] : catalog) {
    size_t area_hit = 0;
    for (const std::string& i : items) {
      if (reached.count(i)) ++area_hit;
      else missing << "  not reached: " << i << "\n";
    }
    out << "coverage " << area << ": " << area_hit << " / " << items.size() << " items reached\n";
    total += items.size();
    hit += area_hit;
  }
  std::set<std::string> errors;
  for (const ManifestEntry& e : manifest.entries)
    if (!e.valid) errors.insert(e.error_kind + " " + e.error_element);
  out << missing.str() << "coverage: " << hit << " / " << total << " items reached; " << errors.size()
      << " error kinds by element tested by the streams to reject:\n";
  for (const std::string& e : errors) out << "  " << e << "\n";
}

}  // namespace

ConformResult run_conformance(const ConformOptions& options, std::ostream& out) {
  const fs::path suite(options.suite);
  if (!options.decoder_command.empty() &&
      (options.decoder_command.find("{in}") == std::string::npos || options.decoder_command.find("{out}") == std::string::npos))
    throw usage_error("--decoder " + options.decoder_command + ": the command needs {in} (the stream) and {out} (the file it writes)");
  if (!(options.timeout_seconds > 0)) throw usage_error("--timeout: a number of seconds above 0");
  const Manifest manifest = read_manifest((suite / "manifest.json").string());
  std::optional<TemporaryFolder> folder;
  if (!options.decoder_command.empty()) folder.emplace();
  ConformResult result;
  char line[640];
  std::snprintf(line, sizeof line, "%-36s %-7s %-6s %s\n", "stream", "expect", "result", "detail");
  out << line;
  for (const ManifestEntry& e : manifest.entries) {
    const std::string path = (suite / e.file).string();
    Outcome outcome;
    try {
      const std::vector<uint8_t> stream = read_file(path);
      if (const std::string mismatch = stream_md5_mismatch(e, stream); !mismatch.empty()) {
        outcome = {Outcome::kFail, mismatch};
      } else if (folder) {
        outcome = run_external(manifest.kind, e, path, options.decoder_command, folder->path(), options.timeout_seconds);
      } else {
        const Verdict verdict = judge_stream(manifest.kind, e, stream);
        outcome = {verdict.pass ? Outcome::kPass : Outcome::kFail, verdict.detail};
      }
    } catch (const std::exception& error) {
      outcome = {Outcome::kFail, error.what()};
    }
    const char* status = outcome.status == Outcome::kPass ? "pass" : outcome.status == Outcome::kFail ? "FAIL" : "skip";
    (outcome.status == Outcome::kPass ? result.passed : outcome.status == Outcome::kFail ? result.failed : result.skipped)++;
    std::snprintf(line, sizeof line, "%-36s %-7s %-6s %.500s\n", e.id.c_str(), e.valid ? "decode" : "reject", status, outcome.detail.c_str());
    out << line;
  }
  out << result.passed << " passed, " << result.failed << " failed";
  if (result.skipped) out << ", " << result.skipped << " skipped";
  out << "\n";
  if (options.coverage) print_coverage(suite, manifest, out);
  return result;
}

}  // namespace m4mesh
