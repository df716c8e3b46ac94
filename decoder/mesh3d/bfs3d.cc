// bfs3d (codec_id 1) decoding: breadth-first motion prediction (docs/codec_bfs3d.md).
#include "common/parallel.h"
#include "decoder/mesh3d/grid_frame_decoder.h"
#include "mesh3d/bfs3d.h"
#include "syntax/mesh3d/bfs3d.h"
#include "syntax/mesh3d/entropy_io.h"

namespace m4mesh {

namespace {

// Frames of at least this many vertices decode their three axes on several threads.
constexpr size_t kParallelAxesVertices = 4096;

// One axis's residuals from its own sections. The state stays local so
// that the compiler keeps it in registers.
template <bool kTraced>
void decode_axis(std::span<const uint8_t> bins, std::span<const uint8_t> raw, const syntax::SectionPlace& place, Trace* trace,
                 std::span<int32_t> residuals) {
  syntax::EntropyReadIO<kTraced> io(bins, raw, place, trace);
  syntax::describe_axis(io, residuals);
  io.finish("motion_residual");
}

Grid grid_of(const Bfs3dHeader& header) {
  Grid grid;
  for (int axis = 0; axis < 3; ++axis) {
    grid.origin[axis] = header.origin_value(axis);
    grid.step[axis] = header.step_value(axis);
  }
  return grid;
}

class Bfs3dDecoder final : public GridFrameDecoder {
 public:
  Bfs3dDecoder(const ObjectHeader& object, const Bfs3dHeader& header) : GridFrameDecoder(object, grid_of(header)), header_(header) {}

 private:
  void start(std::span<const Triangle> faces, uint32_t vertex_count) override {
    order_ = bfs3d_order(faces, vertex_count);
    motion_.assign(vertex_count + size_t{1}, {0, 0, 0});
    for (std::vector<int32_t>& r : residuals_) r.resize(vertex_count);
  }

  void decode_frame(syntax::ReadIO& io, std::vector<IntPoint3>& positions) override {
    Bfs3dFrame frame;
    syntax::describe(io, frame);
    const uint8_t* payload = io.reader().data();
    const auto decode = [&](size_t axis) {
      const syntax::SectionPlace place{syntax::kAxisBins[axis], syntax::kAxisRaw[axis],
                                       8 * static_cast<uint64_t>(frame.bins[axis].data() - payload),
                                       8 * static_cast<uint64_t>(frame.raw[axis].data() - payload), io.plane()};
      if (trace_)
        decode_axis<true>(frame.bins[axis], frame.raw[axis], place, trace_, residuals_[axis]);
      else
        decode_axis<false>(frame.bins[axis], frame.raw[axis], place, nullptr, residuals_[axis]);
    };
    // The axes' sections are independent: a large frame decodes them side
    // by side (the first error in axis order is the one reported).
    if (trace_ || order_.node.size() < kParallelAxesVertices)
      for (size_t axis = 0; axis < 3; ++axis) decode(axis);
    else
      parallel_for(3, 0, decode);
    const bool parallelogram = header_.prediction == kPredictParallelogram;
    for (size_t k = 0; k < order_.node.size(); ++k) {
      const NodeIndex n = order_.node[k];
      const std::array<int64_t, 3> predicted = predict_motion(order_, k, motion_, parallelogram);
      for (int axis = 0; axis < 3; ++axis) {
        const int64_t q = positions[n][axis] + predicted[axis] + residuals_[axis][k];
        if (q > kMaxQuantized || q < -kMaxQuantized)
          fail_reconstruction(io, ErrorKind::kOutOfRange, "motion_residual", "vertex " + std::to_string(n) + " leaves ±2^26 grid steps");
        motion_[n][axis] = static_cast<int32_t>(q - positions[n][axis]);
        positions[n][axis] = static_cast<int32_t>(q);
      }
    }
  }

  Bfs3dHeader header_;
  MotionOrder3d order_;
  std::vector<std::array<int32_t, 3>> motion_;  // |motion| ≤ 2^27: both ends lie within ±2^26
  std::array<std::vector<int32_t>, 3> residuals_;
};

}  // namespace

std::unique_ptr<CodecDecoder3d> make_bfs3d_decoder(const ObjectHeader& object, syntax::ReadIO& io) {
  Bfs3dHeader header;
  syntax::describe(io, header);
  return std::make_unique<Bfs3dDecoder>(object, header);
}

}  // namespace m4mesh
