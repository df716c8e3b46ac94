// m4mesh convert: a frame sequence from any input form to any output form.
#pragma once

#include <string>

#include "cli/gltf.h"

namespace m4mesh {

// `fps`: a glTF output's frames per second; `frames`: A:B, the input's
// frames A … B only (from 0; A: or :B), or empty for all; `selection`: the
// mesh, animation and sampling rate of a glTF input.
int run_convert(const std::string& input, const std::string& output, double fps, const std::string& frames, const GltfSelection& selection);

}  // namespace m4mesh
