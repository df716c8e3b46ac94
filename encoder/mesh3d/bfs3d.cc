// bfs3d (codec_id 1) encoding: every frame on the grid, its motion predicted
// breadth first and coded losslessly (docs/codec_bfs3d.md).

#include "common/bit_cast.h"
#include "encoder/mesh3d/codec_options.h"
#include "encoder/mesh3d/grid_frame_encoder.h"
#include "mesh3d/bfs3d.h"
#include "syntax/mesh3d/bfs3d.h"
#include "syntax/mesh3d/entropy_io.h"

namespace m4mesh {

namespace {

// One axis's residuals into its sections; the symbols' trace is printed
// after the fields that precede the sections.
template <bool kTraced>
void encode_axis(std::span<int32_t> residuals, const syntax::SectionPlace& place, Trace* trace, std::vector<uint8_t>& bins,
                 std::vector<uint8_t>& raw, std::string& trace_text) {
  syntax::EntropyWriteIO<kTraced> io(place, trace);
  syntax::describe_axis(io, residuals);
  bins = io.finish_bins();
  raw = io.finish_raw();
  trace_text = io.trace_text();
}

class Bfs3dEncoder final : public GridFrameEncoder {
 public:
  Bfs3dEncoder(const FrameSource& s, const CodecSettings& settings)
      : GridFrameEncoder(Grid::covering(s, settings.integer("bits")), settings.integer("intra-period"), settings.base_mesh()),
        order_(bfs3d_order(s.faces(), s.vertex_count())),
        motion_(s.vertex_count() + size_t{1}) {
    header_.bits = static_cast<uint32_t>(settings.integer("bits"));
    header_.prediction = settings.flag("parallelogram") ? kPredictParallelogram : kPredictAverage;
    for (int axis = 0; axis < 3; ++axis) {
      header_.origin[axis] = bit_cast<uint32_t>(grid_.origin[axis]);
      header_.step[axis] = bit_cast<uint32_t>(grid_.step[axis]);
      residuals_[axis].resize(s.vertex_count());
    }
  }

  void write_header(syntax::WriteIO& io) override { syntax::describe(io, header_); }

 private:
  void encode_frame(syntax::WriteIO& io, std::span<const Vec3> frame, size_t frame_index, std::vector<IntPoint3>& positions) override {
    quantize_frame(grid_, frame, frame_index, current_);
    const bool parallelogram = header_.prediction == kPredictParallelogram;
    for (size_t k = 0; k < order_.node.size(); ++k) {
      const NodeIndex n = order_.node[k];
      const std::array<int64_t, 3> predicted = predict_motion(order_, k, motion_, parallelogram);
      for (int axis = 0; axis < 3; ++axis) {
        const int32_t v = current_[n][axis] - positions[n][axis];
        residuals_[axis][k] = static_cast<int32_t>(v - predicted[axis]);
        motion_[n][axis] = v;
      }
    }
    positions.swap(current_);
    Bfs3dFrame data;
    std::array<std::vector<uint8_t>, 3> bins, raw;
    std::array<std::string, 3> traces;
    for (int axis = 0; axis < 3; ++axis) {
      const syntax::SectionPlace place{syntax::kAxisBins[axis], syntax::kAxisRaw[axis], 0, 0, io.plane()};
      if (io.trace())
        encode_axis<true>(residuals_[axis], place, io.trace(), bins[axis], raw[axis], traces[axis]);
      else
        encode_axis<false>(residuals_[axis], place, nullptr, bins[axis], raw[axis], traces[axis]);
      data.arithmetic_bytes[axis] = static_cast<uint32_t>(bins[axis].size());
      data.raw_bytes[axis] = static_cast<uint32_t>(raw[axis].size());
      data.bins[axis] = bins[axis];
      data.raw[axis] = raw[axis];
    }
    syntax::describe(io, data);
    if (io.trace())
      for (const std::string& text : traces) io.trace()->stream() << text;
  }

  Bfs3dHeader header_;
  MotionOrder3d order_;
  std::vector<std::array<int32_t, 3>> motion_;  // both ends lie within ±2^26 grid steps
  std::array<std::vector<int32_t>, 3> residuals_;
  std::vector<IntPoint3> current_;
};

}  // namespace

std::vector<CodecOption> bfs3d_options() {
  return {bits_option("quantization bits per coordinate"),
          {"parallelogram", "bfs3d: parallelogram prediction instead of the base-edge average", OptionKind::kFlag, "", 0, 1},
          intra_period_option()};
}

std::unique_ptr<CodecEncoder3d> make_bfs3d_encoder(const FrameSource& sequence, const CodecSettings& settings) {
  return std::make_unique<Bfs3dEncoder>(sequence, settings);
}

}  // namespace m4mesh
