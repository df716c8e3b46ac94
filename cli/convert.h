// m4mesh convert: a frame sequence from any input form to any output form.
#pragma once

#include <string>

namespace m4mesh {

// `fps`: a glTF animation's frames per second.
int run_convert(const std::string& input, const std::string& output, double fps);

}  // namespace m4mesh
