#include "cli/convert.h"

#include <algorithm>

#include "cli/console.h"
#include "cli/sequence_files.h"
#include "cli/sequence_writer.h"
#include "common/error.h"

namespace m4mesh {

using console::say;

int run_convert(const std::string& input, const std::string& output, double fps, const std::string& frames, const GltfSelection& selection) {
  refuse_overwriting(input, output, OutputForm::kFileOrFolder);
  const SequenceOutput form = sequence_output(output, false);
  const auto [first, last] = frame_range(frames);
  const std::unique_ptr<FrameSource> source = open_frames(input, selection);
  const uint32_t count = source->frame_count();
  if (first >= count || (last != UINT32_MAX && last >= count))
    throw usage_error("--frames " + frames + ": " + input + " has " + std::to_string(count) + " frames, 0 … " + std::to_string(count - 1));
  const uint32_t end = std::min<uint32_t>(count - 1, last) + 1;
  const std::unique_ptr<SequenceWriter> writer = sequence_writer(form, output, {source->vertex_count(), source->faces(), end - first, fps});
  FrameReader reader(*source);
  for (uint32_t f = first; f < end; ++f) writer->frame(f - first, reader.get(f));
  writer->commit();
  say("%s: %s of %s", output.c_str(), console::counted(end - first, "frame", "frames").c_str(),
      console::counted(source->vertex_count(), "vertex", "vertices").c_str());
  return 0;
}

}  // namespace m4mesh
