// The conformance suite of the 3D container (conformance/mesh3d/): streams
// of each implemented 3D codec with the MD5 of their decoded frames, and
// streams a decoder must reject; the generator, the manifest and the runner.
#pragma once

#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

#include "common/error.h"
#include "conformance/runner.h"

namespace m4mesh {

struct Suite3dCase {
  std::string id;
  std::string purpose;
  std::vector<std::string> clauses;  // sections of docs/container3d.md and docs/codec_affine_octree.md
  std::vector<uint8_t> stream;
  bool valid = true;
  // Negative streams: what a decoder must report (the frame is the "plane").
  ErrorKind error_kind = ErrorKind::kTruncated;
  std::string error_element;
  int64_t error_frame = kNoPlane;
};

std::vector<Suite3dCase> build_suite3d();

// Writes FOLDER/streams/*.m4m and FOLDER/manifest.json.
void write_suite3d(const std::string& folder);

// The decoded output whose MD5 the manifest holds: every frame's canonical
// bytes (binary32 x, y, z per vertex, little-endian), frame after frame.
std::vector<uint8_t> decoded_frames3d(const std::vector<uint8_t>& stream);

// Whether FOLDER/manifest.json is a 3D suite's.
bool is_suite3d(const std::string& folder);

// As run_conformance, for a 3D suite; an external decoder command gets
// {in} and {out}, and writes the decoded output above to {out}.
ConformResult run_conformance3d(const ConformOptions& options, std::ostream& out);

}  // namespace m4mesh
