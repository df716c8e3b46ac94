// m4mesh conform and generate-suite: the conformance suites through any
// decoder, and the suites written anew.
#pragma once

#include <string>

#include "conformance/runner.h"

namespace m4mesh {

int run_conform(ConformOptions options);
int run_generate_suite(const std::string& folder);

}  // namespace m4mesh
