// The conformance suite of the 3D container (conformance/mesh3d/): streams
// of each implemented 3D codec with the MD5 of their decoded frames, and
// streams a decoder must reject. The manifest and the runner are the 2D
// suite's (conformance/manifest.h, conformance/runner.h).
#pragma once

#include <cstdint>
#include <vector>

#include "conformance/suite.h"

namespace m4mesh {

// The cases codec by codec (conformance/suite3d/), then the streams to
// reject, in the manifest's order. With `traced`, each stream to decode
// keeps the trace its encoder printed.
std::vector<SuiteCase> build_suite3d(bool traced = false);

}  // namespace m4mesh
