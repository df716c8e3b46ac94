#include <algorithm>
#include <filesystem>

#include "cli/convert.h"

#include "cli/console.h"
#include "cli/sequence_files.h"
#include "common/error.h"
#include "mesh3d/sequence.h"

namespace m4mesh {

namespace fs = std::filesystem;

namespace {

using console::say;

}  // namespace

int run_convert(const std::string& input, const std::string& output, double fps, const std::string& frames) {
  refuse_overwriting(input, output);
  const SequenceOutput form = sequence_output(output, false);
  const auto [first, last] = frame_range(frames);
  MeshSequence sequence = load_frames(input);
  const size_t count = sequence.frames.size();
  if (first >= count || (last != UINT32_MAX && last >= count))
    throw usage_error("--frames " + frames + ": " + input + " has " + std::to_string(count) + " frames, 0 … " + std::to_string(count - 1));
  sequence.frames.erase(sequence.frames.begin() + std::min<size_t>(size_t{last} + 1, count), sequence.frames.end());
  sequence.frames.erase(sequence.frames.begin(), sequence.frames.begin() + first);
  if (form == SequenceOutput::kObjFolder) {
    const fs::path staging = staging_folder(output);
    try {
      write_obj_frames(sequence, staging.string());
      install_obj_frames(staging, fs::path(output));
    } catch (...) {
      fs::remove_all(staging);
      throw;
    }
  } else
    write_sequence_file(form, sequence, output, fps);
  say("%s: %zu frames of %u vertices", output.c_str(), sequence.frames.size(), sequence.vertex_count);
  return 0;
}

}  // namespace m4mesh
