// The cloth codec in local cylindrical coordinates (codec_id 3) decoding
// (docs/codec_lcc.md): the reference mesh from the base mesh, then every
// frame from its symbols, vertex after vertex along the coding order, in
// binary64 with IEEE operations only.
#include <optional>

#include "codecs3d/codec_decoder.h"
#include "mesh3d/lcc.h"
#include "mesh3d/quantization.h"
#include "syntax/mesh3d/entropy_io.h"
#include "syntax/mesh3d/lcc.h"

namespace m4mesh {

namespace {

class LccDecoder final : public CodecDecoder3d {
 public:
  LccDecoder(const ObjectHeader& object, const LccHeader& header) : object_(object), header_(header) {}

  void decode_unit(const UnitHeader& unit, syntax::ReadIO& io, std::vector<uint32_t>& decoded) override {
    if (unit.type() == UnitType::kBaseMesh) {
      if (model_) io.fail(ErrorKind::kStructure, "unit_type", "a second base mesh unit: the reference is sent once");
      start(read_base_mesh(io, object_, trace_));
      if (header_.reference == kLccReferenceIsFrame0) decoded.push_back(0);
      return;
    }
    if (!model_) io.fail(ErrorKind::kStructure, "unit_type", "a frame unit before the reference mesh was decoded");
    if (frame_order_->done()) io.fail(ErrorKind::kStructure, "frame_index", "a frame unit after the last frame");
    // The unit is the next frame even when it fails, and the frame then
    // keeps its prediction, so that a check carries on.
    const LccCodedFrame coded = frame_order_->next();
    decoded.push_back(coded.frame);
    io.set_plane(coded.frame);
    try {
      decode_frame(unit, io, coded);
    } catch (const Error&) {
      predictor_->keep(coded, predictor_->predict(coded));
      throw;
    }
  }

  const std::vector<Triangle>& faces() const override { return faces_; }
  void frame(uint32_t, std::span<Float3> positions) const override {
    for (size_t i = 0; i < positions.size(); ++i)
      positions[i] = {static_cast<float>(positions_[i].x), static_cast<float>(positions_[i].y), static_cast<float>(positions_[i].z)};
  }

 private:
  void decode_frame(const UnitHeader& unit, syntax::ReadIO& io, const LccCodedFrame& coded) {
    if (unit.frame_index != coded.frame)
      io.fail(ErrorKind::kStructure, "frame_index",
              "frame " + std::to_string(unit.frame_index) + " where frame " + std::to_string(coded.frame) + " was expected");
    LccFrameData data;
    syntax::describe(io, data);
    const uint8_t* payload = io.reader().data();
    const syntax::SectionPlace place{"bins", "raw", 8 * static_cast<uint64_t>(data.bins.data() - payload),
                                     8 * static_cast<uint64_t>(data.raw.data() - payload), io.plane(),
                                     object_.version};
    if (header_.mode == kLccStreamMode) coder_.emplace();
    if (trace_) {
      syntax::EntropyReadIO<true> symbols(data.bins, data.raw, place, trace_);
      read_symbols(symbols, !coded.anchor());
    } else {
      syntax::EntropyReadIO<false> symbols(data.bins, data.raw, place);
      read_symbols(symbols, !coded.anchor());
    }
    reconstruct(io, coded);
  }

  void start(BaseMesh base) {
    faces_ = std::move(base.faces);
    std::vector<IntPoint3> reference_grid = std::move(base.positions);
    positions_.resize(reference_grid.size());
    for (size_t i = 0; i < positions_.size(); ++i) positions_[i] = lcc_grid_position(header_, reference_grid[i]);
    model_.emplace(faces_, positions_, static_cast<int>(header_.theta_bits), static_cast<int>(header_.rh_bits), header_.rh_range_value());
    predictor_.emplace(header_, model_->order(), reference_grid);
    frame_order_.emplace(header_.reference == kLccReferenceIsFrame0 ? 1 : 0, object_.frame_count, header_.gop);
    residuals_.direct.resize(3 * model_->order().direct.size());
    residuals_.steps.resize(3 * model_->order().steps.size());
    coder_.emplace();
  }

  template <class IO>
  void read_symbols(IO& io, bool predicted) {
    syntax::describe_symbols(io, *coder_, predicted, residuals_.direct, residuals_.steps, model_->theta_limit(), model_->rh_limit());
    io.finish("theta");
  }

  // The frame's indices (prediction plus residuals), then its directly
  // coded vertices from their grid indices and every step in order.
  void reconstruct(syntax::ReadIO& io, const LccCodedFrame& coded) {
    const LccIndices& prediction = predictor_->predict(coded);
    LccIndices indices;
    indices.direct.resize(residuals_.direct.size());
    for (size_t i = 0; i < indices.direct.size(); ++i) {
      const int64_t q = int64_t{prediction.direct[i]} + residuals_.direct[i];
      if (q > kMaxQuantized || q < -kMaxQuantized)
        fail_reconstruction(io, ErrorKind::kOutOfRange, "direct_position", "vertex " + std::to_string(model_->order().direct[i / 3]) + " leaves ±2^26 grid steps");
      indices.direct[i] = static_cast<int32_t>(q);
    }
    const int32_t theta_limit = model_->theta_limit(), rh_limit = model_->rh_limit();
    indices.steps.resize(residuals_.steps.size());
    for (size_t i = 0; i < indices.steps.size(); i += 3) {
      indices.steps[i] = lcc_wrapped_angle(int64_t{prediction.steps[i]} + residuals_.steps[i], theta_limit);
      for (size_t j = i + 1; j < i + 3; ++j) {
        indices.steps[j] = prediction.steps[j] + residuals_.steps[j];
        if (indices.steps[j] < -rh_limit || indices.steps[j] > rh_limit)
          fail_reconstruction(io, ErrorKind::kOutOfRange, j == i + 1 ? "rho" : "zeta",
                  "step " + std::to_string(i / 3) + ": prediction and residual leave ±2^rh_bits");
      }
    }
    const std::vector<NodeIndex>& direct = model_->order().direct;
    for (size_t i = 0; i < direct.size(); ++i)
      positions_[direct[i]] = lcc_grid_position(header_, {indices.direct[3 * i], indices.direct[3 * i + 1], indices.direct[3 * i + 2]});
    for (size_t k = 0; k < model_->order().steps.size(); ++k)
      positions_[model_->order().steps[k].d] =
          model_->place(k, positions_, indices.steps[3 * k], indices.steps[3 * k + 1], indices.steps[3 * k + 2]);
    predictor_->keep(coded, std::move(indices));
  }

  ObjectHeader object_;
  LccHeader header_;
  std::vector<Triangle> faces_;
  std::optional<LccModel> model_;
  std::optional<LccPredictor> predictor_;
  std::optional<LccFrameOrder> frame_order_;
  std::vector<Vec3> positions_;
  LccIndices residuals_;
  std::optional<syntax::ResidualCoder<syntax::kLccChannels>> coder_;
};

}  // namespace

std::unique_ptr<CodecDecoder3d> make_lcc_decoder(const ObjectHeader& object, syntax::ReadIO& io) {
  LccHeader header;
  syntax::describe(io, header);
  io.require(header.gop == 0 || object.frame_count > 0, ErrorKind::kStructure, "temporal_gop",
             "temporal prediction needs the object header's frame_count");
  return std::make_unique<LccDecoder>(object, header);
}

}  // namespace m4mesh
