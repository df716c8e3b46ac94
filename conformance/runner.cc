#include "conformance/runner.h"

#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/md5.h"
#include "conformance/manifest.h"
#include "decoder/decoder.h"

namespace m4mesh {

namespace {

struct Outcome {
  enum { kPass, kFail, kSkip } status;
  std::string detail;
};

std::string replace_all(std::string text, const std::string& from, const std::string& to) {
  for (size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size())) text.replace(at, from.size(), to);
  return text;
}

std::string quoted(const std::string& path) { return "'" + replace_all(path, "'", "'\\''") + "'"; }

Outcome run_ours(const ManifestEntry& e, const std::vector<uint8_t>& stream) {
  DecoderOptions options;
  options.method = e.method == 1 ? MotionMethod::kMethod1 : MotionMethod::kMethod2;
  try {
    const std::string md5 = decode_to_text(stream, options, {});
    if (!e.valid) return {Outcome::kFail, "decoded, expected " + e.error_kind + " at " + e.error_element};
    if (md5 != e.decoded_md5) return {Outcome::kFail, "decoded MD5 " + md5 + ", expected " + e.decoded_md5};
    return {Outcome::kPass, md5};
  } catch (const Error& error) {
    if (e.valid) return {Outcome::kFail, error.what()};
    if (to_string(error.kind()) != e.error_kind || error.element() != e.error_element || error.plane() != e.error_plane)
      return {Outcome::kFail, std::string(to_string(error.kind())) + ": " + error.what() + "; expected " + e.error_kind +
                                  " at plane " + std::to_string(e.error_plane) + ", " + e.error_element};
    return {Outcome::kPass, std::string(to_string(error.kind())) + ": " + error.what()};
  }
}

Outcome run_external(const ManifestEntry& e, const std::string& stream_path, const std::string& command_template) {
  if (e.method != 2 && command_template.find("{method}") == std::string::npos)
    return {Outcome::kSkip, "needs Method I: put {method} in the decoder command"};
  const std::filesystem::path out = std::filesystem::temp_directory_path() / ("m4mesh-conform-" + e.id + ".txt");
  std::filesystem::remove(out);
  std::string command = replace_all(command_template, "{in}", quoted(stream_path));
  command = replace_all(command, "{out}", quoted(out.string()));
  command = replace_all(command, "{method}", std::to_string(e.method));
  const int status = std::system((command + " > /dev/null 2>&1").c_str());
  const bool ok = status != -1 && WIFEXITED(status) && WEXITSTATUS(status) == 0;
  if (!e.valid) {
    std::filesystem::remove(out);
    return ok ? Outcome{Outcome::kFail, "exit status 0 for a stream that must be rejected (" + e.error_kind + ")"}
              : Outcome{Outcome::kPass, "rejected"};
  }
  if (!ok) return {Outcome::kFail, "the decoder failed (status " + std::to_string(status) + ")"};
  if (!std::filesystem::exists(out)) return {Outcome::kFail, "the decoder wrote no output"};
  const std::vector<uint8_t> text = read_file(out.string());
  std::filesystem::remove(out);
  const std::string md5 = md5_hex(std::string_view(reinterpret_cast<const char*>(text.data()), text.size()));
  if (md5 != e.decoded_md5) return {Outcome::kFail, "decoded MD5 " + md5 + ", expected " + e.decoded_md5};
  return {Outcome::kPass, md5};
}

}  // namespace

ConformResult run_conformance(const ConformOptions& options, std::ostream& out) {
  const std::filesystem::path suite(options.suite);
  const Manifest manifest = read_manifest((suite / "manifest.json").string());
  ConformResult result;
  char line[512];
  std::snprintf(line, sizeof line, "%-36s %-7s %-6s %s\n", "stream", "expect", "result", "detail");
  out << line;
  for (const ManifestEntry& e : manifest.entries) {
    const std::string path = (suite / e.file).string();
    Outcome outcome;
    try {
      const std::vector<uint8_t> stream = read_file(path);
      const std::string md5 = md5_hex(std::string_view(reinterpret_cast<const char*>(stream.data()), stream.size()));
      if (md5 != e.stream_md5)
        outcome = {Outcome::kFail, "the stream file's MD5 is " + md5 + ", the manifest says " + e.stream_md5};
      else
        outcome = options.decoder_command.empty() ? run_ours(e, stream) : run_external(e, path, options.decoder_command);
    } catch (const Error& error) {
      outcome = {Outcome::kFail, error.what()};
    }
    const char* status = outcome.status == Outcome::kPass ? "pass" : outcome.status == Outcome::kFail ? "FAIL" : "skip";
    (outcome.status == Outcome::kPass ? result.passed : outcome.status == Outcome::kFail ? result.failed : result.skipped)++;
    std::snprintf(line, sizeof line, "%-36s %-7s %-6s %.400s\n", e.id.c_str(), e.valid ? "decode" : "reject", status,
                  outcome.detail.c_str());
    out << line;
  }
  out << result.passed << " passed, " << result.failed << " failed";
  if (result.skipped) out << ", " << result.skipped << " skipped";
  out << "\n";
  return result;
}

}  // namespace m4mesh
