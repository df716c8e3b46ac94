// The judgement of m4mesh's own decoder on one stream of a suite, as
// `m4mesh conform` gives it and the web page shows it (web/bindings.cc).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "conformance/manifest.h"

namespace m4mesh {

struct Verdict {
  bool pass = false;
  std::string detail;  // the MD5 or the error; what differs from the manifest
};

// The stream file's MD5 against the manifest's; empty when they agree.
std::string stream_md5_mismatch(const ManifestEntry& entry, const std::vector<uint8_t>& stream);

// The stream as the manifest has it, then decoded to the manifest's MD5,
// or rejected with its error: kind, element, plane (3D: frame) and bit.
Verdict judge_stream(SuiteKind kind, const ManifestEntry& entry, const std::vector<uint8_t>& stream);

}  // namespace m4mesh
