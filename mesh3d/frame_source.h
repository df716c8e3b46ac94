// The frames an encoder reads: one at a time, in any order and as often as
// a codec needs, so that a sequence of any length is coded in memory that
// depends on the mesh and the codec's segment, not on the frame count. A
// source is a file read frame by frame, a sequence in memory, some frames
// of another source, another source with its vertices renumbered, or
// frames made on the fly (benchmarks).
#pragma once

#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <vector>

#include "mesh/topology.h"
#include "mesh3d/sequence.h"

namespace m4mesh {

// What one pass over every frame finds: the box of every position, and the
// largest diagonal of one frame's box (PSNR's dmax).
struct SequenceScan {
  Box3 box;
  double largest_frame_diagonal = 0;
};

class FrameSource {
 public:
  virtual ~FrameSource() = default;

  virtual uint32_t vertex_count() const = 0;
  virtual std::span<const Triangle> faces() const = 0;
  virtual uint32_t frame_count() const = 0;
  // Frame `index` (below frame_count) into `out` (vertex_count positions).
  // Safe to call from several threads at once.
  virtual void read(uint32_t index, std::span<Vec3> out) const = 0;
  // Frame `index` without a copy when the source holds it in memory, else empty.
  virtual std::span<const Vec3> view(uint32_t /*index*/) const { return {}; }

  // The pass over every frame, made once on first use (thread-safe): an
  // input error for a sequence that cannot be coded (no frame, fewer than
  // 3 vertices or no face, beyond the container's limits, a face naming a
  // vertex that does not exist, a position that is not finite, naming the
  // frame and vertex).
  virtual const SequenceScan& scan() const;

 private:
  mutable std::once_flag scanned_;
  mutable SequenceScan scan_;
};

// A frame of a source: the source's own memory, or a copy in a buffer of
// the reader's (valid until the next get()).
class FrameReader {
 public:
  explicit FrameReader(const FrameSource& source) : source_(source) {}
  std::span<const Vec3> get(uint32_t index);

 private:
  const FrameSource& source_;
  std::vector<Vec3> buffer_;
};

// A sequence in memory, borrowed (it must outlive the source) or owned.
class SequenceSource final : public FrameSource {
 public:
  explicit SequenceSource(const MeshSequence& sequence) : sequence_(sequence) {}
  explicit SequenceSource(MeshSequence&& sequence) : owned_(std::move(sequence)), sequence_(*owned_) {}

  uint32_t vertex_count() const override { return sequence_.vertex_count; }
  std::span<const Triangle> faces() const override { return sequence_.faces; }
  uint32_t frame_count() const override { return static_cast<uint32_t>(sequence_.frames.size()); }
  void read(uint32_t index, std::span<Vec3> out) const override;
  std::span<const Vec3> view(uint32_t index) const override;
  const MeshSequence& sequence() const { return sequence_; }

 private:
  std::optional<MeshSequence> owned_;
  const MeshSequence& sequence_;
};

// Frames of another source (which must outlive it), in the order listed.
class ClipSource final : public FrameSource {
 public:
  ClipSource(const FrameSource& source, std::vector<uint32_t> frames) : source_(source), frames_(std::move(frames)) {}

  uint32_t vertex_count() const override { return source_.vertex_count(); }
  std::span<const Triangle> faces() const override { return source_.faces(); }
  uint32_t frame_count() const override { return static_cast<uint32_t>(frames_.size()); }
  void read(uint32_t index, std::span<Vec3> out) const override { source_.read(frames_.at(index), out); }
  std::span<const Vec3> view(uint32_t index) const override { return source_.view(frames_.at(index)); }
  // The source's frame at `index`.
  uint32_t source_frame(uint32_t index) const { return frames_.at(index); }

 private:
  const FrameSource& source_;
  std::vector<uint32_t> frames_;
};

// Another source (which must outlive it) with other faces and, unless
// `input_of` is empty, its vertices renumbered: vertex v is the source's
// input_of[v]. `faces` are in the new numbers.
class RenumberedSource final : public FrameSource {
 public:
  RenumberedSource(const FrameSource& source, std::vector<uint32_t> input_of, std::vector<Triangle> faces)
      : source_(source), input_of_(std::move(input_of)), faces_(std::move(faces)) {}

  uint32_t vertex_count() const override { return source_.vertex_count(); }
  std::span<const Triangle> faces() const override { return faces_; }
  uint32_t frame_count() const override { return source_.frame_count(); }
  void read(uint32_t index, std::span<Vec3> out) const override;
  std::span<const Vec3> view(uint32_t index) const override { return input_of_.empty() ? source_.view(index) : std::span<const Vec3>(); }
  // The source's: the same positions.
  const SequenceScan& scan() const override { return source_.scan(); }

 private:
  const FrameSource& source_;
  std::vector<uint32_t> input_of_;
  std::vector<Triangle> faces_;
};

// Every frame in memory (tests, tools that need the whole sequence).
MeshSequence read_all_frames(const FrameSource& source);

// Sequences of at most this many vertex-frames are read into memory at
// once (24 bytes each); longer ones frame by frame from their files.
inline constexpr uint64_t kInMemoryVertexFrames = uint64_t{1} << 22;

// The frames of a sequence file or folder (every form load_sequence
// reads), in memory up to `in_memory` vertex-frames, else read from the
// files as the encoder asks for them (a .m4seq or .pc2 file at the
// frame's offset, a frame file parsed again; standard input is always
// read whole).
std::unique_ptr<FrameSource> open_sequence(const std::string& path, bool report_progress = false,
                                           uint64_t in_memory = kInMemoryVertexFrames);

}  // namespace m4mesh
