// m4mesh convert: a frame sequence from any input form to any output form.
#pragma once

#include <string>

namespace m4mesh {

int run_convert(const std::string& input, const std::string& output);

}  // namespace m4mesh
