// The conformance manifest (conformance/manifest.json): one entry per stream.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace m4mesh {

struct ManifestEntry {
  std::string id;
  std::string file;  // relative to the suite folder
  std::string purpose;
  std::vector<std::string> clauses;
  std::string stream_md5;
  int method = 2;
  bool valid = true;
  // Valid streams.
  std::string decoded_md5;  // MD5 of the §9 text
  int64_t planes = 0;
  std::vector<std::string> classes;   // value classes (conformance/coverage.h)
  std::vector<std::string> warnings;  // what `m4mesh check` warns about
  // Negative streams.
  std::string error_kind;
  std::string error_element;
  int64_t error_plane = -1;
};

struct Manifest {
  std::vector<ManifestEntry> entries;
};

Manifest read_manifest(const std::string& path);
std::string manifest_json(const Manifest& manifest);

// Builds every stream of the suite, writes it and manifest.json under `folder`.
Manifest generate_suite(const std::string& folder);

}  // namespace m4mesh
