// Sequence outputs written frame by frame, as a decoder hands the frames
// out: memory holds a frame, not the sequence (but for a glTF animation,
// whose buffer holds every frame, and a .m4seq or .pc2 whose frame count
// is not known in advance). The output appears only on commit(); a writer
// destroyed before it leaves nothing behind (standard output excepted).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>

#include "cli/sequence_files.h"
#include "common/point3.h"
#include "mesh3d/sequence.h"
#include "mesh/topology.h"

namespace m4mesh {

class SequenceWriter {
 public:
  virtual ~SequenceWriter() = default;
  // The next frame, in display order; `index` is its number in the output
  // (a folder of OBJ frames names its files by it). Binary outputs hold
  // binary32 positions, text ones the positions given.
  virtual void frame(uint32_t index, std::span<const Vec3> positions) = 0;
  virtual void commit() = 0;
};

struct SequenceShape {
  uint32_t vertex_count = 0;
  std::span<const Triangle> faces;
  std::optional<uint32_t> frame_count;  // none: known at commit()
  double fps = 25;
};

std::unique_ptr<SequenceWriter> sequence_writer(SequenceOutput form, const std::string& output, const SequenceShape& shape);

}  // namespace m4mesh
