// The conformance suite of the 3D container (conformance/mesh3d/): streams
// of each implemented 3D codec with the MD5 of their decoded frames, and
// streams a decoder must reject. The manifest and the runner are the 2D
// suite's (conformance/manifest.h, conformance/runner.h).
#pragma once

#include <cstdint>
#include <vector>

#include "conformance/suite.h"

namespace m4mesh {

// The cases in groups: Affine-Octree, bfs3d, rejected. With `traced`, each
// stream to decode keeps the trace its encoder printed.
std::vector<SuiteCase> build_suite3d(bool traced = false);

// The decoded output whose MD5 the manifest holds: every frame's canonical
// bytes (binary32 x, y, z per vertex, little-endian), frame after frame.
std::vector<uint8_t> decoded_frames3d(const std::vector<uint8_t>& stream);

}  // namespace m4mesh
