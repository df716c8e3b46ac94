// The conformance manifest (manifest.json of a suite folder), one schema
// for the 2D suite (conformance/) and the 3D suite (conformance/mesh3d/):
// the suite's kind, then one entry per stream.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace m4mesh {

enum class SuiteKind { kMesh2d, kMesh3d };

struct ManifestEntry {
  std::string id;
  std::string file;  // relative to the suite folder
  std::string purpose;
  std::vector<std::string> clauses;
  std::string stream_md5;
  int method = 2;  // 2D: the motion vector prediction the stream needs
  bool valid = true;
  // Valid streams.
  std::string decoded_md5;  // MD5 of the decoded output (decoded_output_md5)
  int64_t planes = 0;       // planes (2D) or frames (3D) decoded
  std::vector<std::string> classes;   // 2D: value classes (conformance/coverage.h)
  std::vector<std::string> warnings;  // what `m4mesh check` warns about
  // Negative streams.
  std::string error_kind;
  std::string error_element;
  int64_t error_plane = -1;  // 3D: the frame
  int64_t error_offset = -1;  // the bit the error is placed at (-1: a rule about the whole stream)
};

struct Manifest {
  SuiteKind kind = SuiteKind::kMesh2d;
  std::vector<ManifestEntry> entries;
};

Manifest read_manifest(const std::string& path);
// A manifest's text; `name` for the errors.
Manifest parse_manifest(std::string_view text, const std::string& name);
std::string manifest_json(const Manifest& manifest);

// The MD5 of a stream's decoded output: the §9 text (2D), or every frame's
// binary32 bytes (3D); an Error when the stream does not decode.
std::string decoded_output_md5(SuiteKind kind, const std::vector<uint8_t>& stream, int method);

}  // namespace m4mesh
