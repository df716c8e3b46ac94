// The suites as files: every case's stream and the manifest that judges
// it (conformance/manifest.h), written deterministically.
#pragma once

#include <string>
#include <vector>

#include "conformance/manifest.h"
#include "conformance/suite.h"

namespace m4mesh {

// Writes the cases as FOLDER/streams/*.m4m and FOLDER/manifest.json.
Manifest write_suite(const std::string& folder, SuiteKind kind, const std::vector<SuiteCase>& cases);
// Both suites: FOLDER (2D) and FOLDER/mesh3d (3D).
void generate_suites(const std::string& folder);

}  // namespace m4mesh
