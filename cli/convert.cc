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

int run_convert(const std::string& input, const std::string& output, double fps) {
  refuse_overwriting(input, output);
  const SequenceOutput form = sequence_output(output, false);
  const MeshSequence sequence = load_frames(input);
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
