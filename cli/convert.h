// m4mesh convert: a frame sequence from any input form to any output form.
#pragma once

#include <string>

namespace m4mesh {

// `fps`: a glTF animation's frames per second; `frames`: A:B, the input's
// frames A … B only (from 0; A: or :B), or empty for all.
int run_convert(const std::string& input, const std::string& output, double fps, const std::string& frames);

}  // namespace m4mesh
