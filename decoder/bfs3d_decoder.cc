// bfs3d (codec_id 1) decoding: breadth-first motion prediction (docs/container3d.md).
#include "bitstream/bit_reader.h"
#include "decoder/codec3d.h"
#include "mesh3d/traversal3d.h"
#include "syntax/bfs3d.h"
#include "syntax/residual_coder.h"

namespace m4mesh {

namespace {

class Bfs3dDecoder final : public CodecDecoder3d {
 public:
  explicit Bfs3dDecoder(const Bfs3dHeader& header) : header_(header) {
    for (int axis = 0; axis < 3; ++axis) {
      grid_.origin[axis] = header.origin_value(axis);
      grid_.step[axis] = header.step_value(axis);
    }
  }

  const Grid& grid() const override { return grid_; }

  void start(std::span<const Triangle> faces, uint32_t vertex_count) override {
    order_ = bfs3d_order(faces, vertex_count);
    motion_.assign(vertex_count + size_t{1}, {0, 0, 0});
  }

  void decode_frame(std::span<const uint8_t> data, std::vector<IntPoint3>& positions) override {
    if (data.size() < 3 * kArithmeticLengthBytes) frame_data_error(ErrorKind::kTruncated, "arithmetic_bytes", "the frame's data ends early");
    std::array<uint32_t, 3> lengths;
    for (int axis = 0; axis < 3; ++axis) {
      const uint8_t* p = data.data() + axis * kArithmeticLengthBytes;
      lengths[axis] = uint32_t{p[0]} << 24 | uint32_t{p[1]} << 16 | uint32_t{p[2]} << 8 | p[3];
    }
    data = data.subspan(3 * kArithmeticLengthBytes);
    std::array<ArithmeticDecoder, 3> bins{ArithmeticDecoder({}), ArithmeticDecoder({}), ArithmeticDecoder({})};
    for (int axis = 0; axis < 3; ++axis) {
      if (lengths[axis] > data.size()) frame_data_error(ErrorKind::kOutOfRange, "arithmetic_bytes", "longer than the frame's data");
      bins[axis] = ArithmeticDecoder(data.first(lengths[axis]));
      data = data.subspan(lengths[axis]);
    }
    BitReader raw(data.data(), data.size());
    ResidualCoder<3> model;
    const bool parallelogram = header_.prediction == kPredictParallelogram;
    for (size_t k = 0; k < order_.node.size(); ++k) {
      const NodeIndex n = order_.node[k];
      const auto &a = motion_[order_.pred_a[k]], &b = motion_[order_.pred_b[k]], &c = motion_[order_.pred_c[k]];
      const bool use_parallelogram = parallelogram && order_.pred_c[k] != order_.zero_slot;
      for (int axis = 0; axis < 3; ++axis) {
        int32_t r;
        if (!model.decode(bins[axis], raw, axis, r)) frame_data_error(ErrorKind::kInvalidCode, "motion_residual", "a residual longer than 32 bits");
        const int64_t w = predict_motion(a[axis], b[axis], c[axis], use_parallelogram);
        const int64_t v = w + r;
        const int64_t q = positions[n][axis] + v;
        if (q > kMaxQuantized || q < -kMaxQuantized)
          frame_data_error(ErrorKind::kOutOfRange, "motion_residual", "vertex " + std::to_string(n) + " leaves ±2^26 grid steps");
        motion_[n][axis] = v;
        positions[n][axis] = static_cast<int32_t>(q);
      }
    }
    if (bins[0].overrun() + bins[1].overrun() + bins[2].overrun() != 0 || raw.overrun())
      frame_data_error(ErrorKind::kTruncated, "motion_residual", "the frame's data ends early");
  }

 private:
  Bfs3dHeader header_;
  Grid grid_;
  MotionOrder3d order_;
  std::vector<std::array<int64_t, 3>> motion_;
};

}  // namespace

std::unique_ptr<CodecDecoder3d> read_bfs3d_header(syntax::ReadIO& io) {
  Bfs3dHeader header;
  syntax::describe(io, header);
  return std::make_unique<Bfs3dDecoder>(header);
}

}  // namespace m4mesh
