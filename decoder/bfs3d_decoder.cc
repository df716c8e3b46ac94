// bfs3d (codec_id 1) decoding: breadth-first motion prediction (docs/container3d.md).
#include "bitstream/bit_reader.h"
#include "decoder/codec3d.h"
#include "mesh3d/traversal3d.h"
#include "syntax/bfs3d.h"
#include "syntax/residual_coder.h"

namespace m4mesh {

namespace {

// One axis's residuals, in coding order, from its own bin and raw streams.
// The axis's state stays local so that the compiler keeps it in registers.
void decode_axis(std::span<const uint8_t> bins, std::span<const uint8_t> raw_bytes, std::span<int32_t> residuals) {
  ArithmeticDecoder coder(bins);
  BitReader raw(raw_bytes.data(), raw_bytes.size());
  ResidualCoder<1> model;
  for (int32_t& r : residuals)
    if (!model.decode(coder, raw, 0, r)) frame_data_error(ErrorKind::kInvalidCode, "motion_residual", "a residual longer than 32 bits");
  if (coder.overrun() != 0 || raw.overrun()) frame_data_error(ErrorKind::kTruncated, "motion_residual", "the frame's data ends early");
}

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
    for (std::vector<int32_t>& r : residuals_) r.resize(vertex_count);
  }

  void decode_frame(std::span<const uint8_t> data, std::vector<IntPoint3>& positions) override {
    BitReader reader(data.data(), data.size());
    syntax::ReadIO io(reader);
    Bfs3dFrameLengths lengths;
    syntax::describe(io, lengths);
    const uint64_t streams = lengths.streams_bytes();
    if (streams != data.size() - kBfs3dLengthsBytes)
      io.fail(streams > data.size() - kBfs3dLengthsBytes ? ErrorKind::kOutOfRange : ErrorKind::kStructure, "raw_bytes_z",
              "the streams' lengths add up to " + std::to_string(streams) + " bytes, the frame holds " +
                  std::to_string(data.size() - kBfs3dLengthsBytes));
    data = data.subspan(kBfs3dLengthsBytes);
    for (int axis = 0; axis < 3; ++axis) {
      const std::span<const uint8_t> bins = data.first(lengths.arithmetic_bytes[axis]);
      data = data.subspan(bins.size());
      const std::span<const uint8_t> raw = data.first(lengths.raw_bytes[axis]);
      data = data.subspan(raw.size());
      decode_axis(bins, raw, residuals_[axis]);
    }
    const bool parallelogram = header_.prediction == kPredictParallelogram;
    for (size_t k = 0; k < order_.node.size(); ++k) {
      const NodeIndex n = order_.node[k];
      const std::array<int64_t, 3> w = predict_motion(order_, k, motion_, parallelogram);
      for (int axis = 0; axis < 3; ++axis) {
        const int64_t q = positions[n][axis] + w[axis] + residuals_[axis][k];
        if (q > kMaxQuantized || q < -kMaxQuantized)
          frame_data_error(ErrorKind::kOutOfRange, "motion_residual", "vertex " + std::to_string(n) + " leaves ±2^26 grid steps");
        motion_[n][axis] = static_cast<int32_t>(q - positions[n][axis]);
        positions[n][axis] = static_cast<int32_t>(q);
      }
    }
  }

 private:
  Bfs3dHeader header_;
  Grid grid_;
  MotionOrder3d order_;
  std::vector<std::array<int32_t, 3>> motion_;  // |motion| ≤ 2^27: both ends lie within ±2^26
  std::array<std::vector<int32_t>, 3> residuals_;
};

}  // namespace

std::unique_ptr<CodecDecoder3d> read_bfs3d_header(syntax::ReadIO& io) {
  Bfs3dHeader header;
  syntax::describe(io, header);
  return std::make_unique<Bfs3dDecoder>(header);
}

}  // namespace m4mesh
