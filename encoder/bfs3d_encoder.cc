// bfs3d (codec_id 1) encoding: every frame on the grid, its motion predicted
// breadth first and coded losslessly (docs/container3d.md).
#include <bit>

#include "encoder/codec3d.h"
#include "mesh3d/traversal3d.h"
#include "syntax/bfs3d.h"
#include "syntax/residual_coder.h"

namespace m4mesh {

namespace {

class Bfs3dEncoder final : public CodecEncoder3d {
 public:
  Bfs3dEncoder(const MeshSequence& s, const Encode3dOptions& options)
      : grid_(Grid::over(s.frames[0], options.bits)), order_(bfs3d_order(s.faces, s.vertex_count)), motion_(s.vertex_count + size_t{1}) {
    header_.bits = static_cast<uint32_t>(options.bits);
    header_.prediction = options.parallelogram ? kPredictParallelogram : kPredictAverage;
    for (int axis = 0; axis < 3; ++axis) {
      header_.origin[axis] = std::bit_cast<uint32_t>(grid_.origin[axis]);
      header_.step[axis] = std::bit_cast<uint32_t>(grid_.step[axis]);
    }
  }

  const Grid& grid() const override { return grid_; }
  void write_header(syntax::WriteIO& io) override { syntax::describe(io, header_); }

  // The six lengths (syntax/bfs3d.h), then per axis its bins and raw bits.
  std::vector<uint8_t> encode_frame(std::span<const Vec3> frame, size_t frame_index, std::vector<IntPoint3>& positions,
                                    Encode3dResult&) override {
    quantize_frame(grid_, frame, frame_index, current_);
    std::array<ArithmeticEncoder, 3> coders;
    std::array<BitWriter, 3> raws;
    ResidualCoder<3> model;
    const bool parallelogram = header_.prediction == kPredictParallelogram;
    for (size_t k = 0; k < order_.node.size(); ++k) {
      const NodeIndex n = order_.node[k];
      const std::array<int64_t, 3> w = predict_motion(order_, k, motion_, parallelogram);
      for (int axis = 0; axis < 3; ++axis) {
        const int32_t v = current_[n][axis] - positions[n][axis];
        model.encode(coders[axis], raws[axis], axis, static_cast<int32_t>(v - w[axis]));
        motion_[n][axis] = v;
      }
    }
    positions.swap(current_);
    std::array<std::vector<uint8_t>, 6> streams;
    Bfs3dFrameLengths lengths;
    for (int axis = 0; axis < 3; ++axis) {
      streams[2 * axis] = coders[axis].finish();
      raws[axis].write(0, static_cast<int>((8 - raws[axis].position() % 8) % 8));
      streams[2 * axis + 1] = raws[axis].take_bytes();
      lengths.arithmetic_bytes[axis] = static_cast<uint32_t>(streams[2 * axis].size());
      lengths.raw_bytes[axis] = static_cast<uint32_t>(streams[2 * axis + 1].size());
    }
    BitWriter head;
    syntax::WriteIO io(head);
    syntax::describe(io, lengths);
    std::vector<uint8_t> data = head.take_bytes();
    for (const std::vector<uint8_t>& stream : streams) data.insert(data.end(), stream.begin(), stream.end());
    return data;
  }

 private:
  Grid grid_;
  Bfs3dHeader header_;
  MotionOrder3d order_;
  std::vector<std::array<int32_t, 3>> motion_;  // both ends lie within ±2^26 grid steps
  std::vector<IntPoint3> current_;
};

}  // namespace

std::unique_ptr<CodecEncoder3d> make_bfs3d_encoder(const MeshSequence& sequence, const Encode3dOptions& options) {
  return std::make_unique<Bfs3dEncoder>(sequence, options);
}

}  // namespace m4mesh
