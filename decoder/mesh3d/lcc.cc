// The cloth codec in local cylindrical coordinates (codec_id 3) decoding
// (docs/codec_lcc.md): the reference mesh from the base mesh, then every
// frame from its symbols, vertex after vertex along the coding order, in
// binary64 with IEEE operations only.
#include <algorithm>
#include <atomic>
#include <optional>

#include "codecs3d/codec_decoder.h"
#include "common/parallel.h"
#include "mesh3d/lcc.h"
#include "mesh3d/quantization.h"
#include "syntax/mesh3d/entropy_io.h"
#include "syntax/mesh3d/lcc.h"

namespace m4mesh {

namespace {

// Frames of at least this many steps place their vertices on one thread
// while their symbols are decoded on another, kLccStepChunk steps at a
// time, where the process may run on two cores.
constexpr size_t kPipelinedSteps = 4096;
constexpr uint32_t kSymbolsFailed = UINT32_MAX;

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
                                     8 * static_cast<uint64_t>(data.raw.data() - payload), io.plane()};
    if (header_.mode == kLccStreamMode) coder_.emplace();
    const bool predicted = !coded.anchor();
    const LccIndices& prediction = predictor_->predict(coded);
    LccIndices indices{std::vector<int32_t>(residuals_.direct.size()), std::vector<int32_t>(residuals_.steps.size())};
    if (trace_) {
      syntax::EntropyReadIO<true> symbols(data.bins, data.raw, place, trace_);
      read_symbols(symbols, predicted, nullptr);
      place_vertices(io, prediction, indices, nullptr);
    } else if (!pipelined_) {
      syntax::EntropyReadIO<false> symbols(data.bins, data.raw, place);
      read_symbols(symbols, predicted, nullptr);
      place_vertices(io, prediction, indices, nullptr);
    } else {
      // A large frame places its vertices while its symbols are being
      // decoded; an error of the symbols is reported before one of the
      // values, as one after the other would.
      std::atomic<uint32_t> decoded{0};
      parallel_for(2, 0, [&](size_t task) {
        if (task == 0) {
          syntax::EntropyReadIO<false> symbols(data.bins, data.raw, place);
          read_symbols(symbols, predicted, &decoded);
        } else {
          place_vertices(io, prediction, indices, &decoded);
        }
      });
    }
    positions_.swap(next_);
    predictor_->keep(coded, std::move(indices));
  }

  void start(BaseMesh base) {
    faces_ = std::move(base.faces);
    std::vector<IntPoint3> reference_grid = std::move(base.positions);
    positions_.resize(reference_grid.size());
    next_.resize(reference_grid.size());
    for (size_t i = 0; i < positions_.size(); ++i) positions_[i] = lcc_grid_position(header_, reference_grid[i]);
    model_.emplace(faces_, positions_, static_cast<int>(header_.theta_bits), static_cast<int>(header_.rh_bits), header_.rh_range_value());
    predictor_.emplace(header_, model_->order(), reference_grid);
    frame_order_.emplace(header_.reference == kLccReferenceIsFrame0 ? 1 : 0, object_.frame_count, header_.gop);
    residuals_.direct.resize(3 * model_->order().direct.size());
    residuals_.steps.resize(3 * model_->order().steps.size());
    coder_.emplace();
    pipelined_ = model_->order().steps.size() >= kPipelinedSteps && available_cores() >= 2;
  }

  // The frame's symbols, in chunks of steps; `decoded` (when set) says
  // how far they are: 1 + the steps decoded once the direct vertices are,
  // kSymbolsFailed when their decoding failed.
  template <class IO>
  void read_symbols(IO& io, bool predicted, std::atomic<uint32_t>* decoded) {
    const auto publish = [&](uint32_t value) {
      if (!decoded) return;
      decoded->store(value, std::memory_order_release);
      decoded->notify_one();
    };
    const std::span<int32_t> steps = residuals_.steps;
    try {
      syntax::describe_symbols(io, *coder_, predicted, residuals_.direct, {}, model_->theta_limit(), model_->rh_limit());
      publish(1);
      for (size_t k = 0; k < steps.size() / 3; k += kLccStepChunk) {
        const size_t end = std::min(k + kLccStepChunk, steps.size() / 3);
        syntax::describe_symbols(io, *coder_, predicted, {}, steps.subspan(3 * k, 3 * (end - k)), model_->theta_limit(), model_->rh_limit());
        publish(static_cast<uint32_t>(1 + end));
      }
      io.finish("theta");
    } catch (...) {
      publish(kSymbolsFailed);
      throw;
    }
  }

  // The frame's indices (prediction plus residuals) and positions: the
  // directly coded vertices from their grid indices, then every step in
  // order, each as soon as `decoded` says its symbols are there.
  void place_vertices(const syntax::ReadIO& io, const LccIndices& prediction, LccIndices& indices, const std::atomic<uint32_t>* decoded) {
    const auto wait_for = [&](size_t needed) {
      if (!decoded) return true;
      uint32_t now = decoded->load(std::memory_order_acquire);
      while (now < needed) {
        decoded->wait(now, std::memory_order_acquire);
        now = decoded->load(std::memory_order_acquire);
      }
      return now != kSymbolsFailed;
    };
    if (!wait_for(1)) return;
    const std::vector<NodeIndex>& direct = model_->order().direct;
    for (size_t i = 0; i < indices.direct.size(); ++i) {
      const int64_t q = int64_t{prediction.direct[i]} + residuals_.direct[i];
      if (q > kMaxQuantized || q < -kMaxQuantized)
        fail_reconstruction(io, ErrorKind::kOutOfRange, "direct_position", "vertex " + std::to_string(direct[i / 3]) + " leaves ±2^26 grid steps");
      indices.direct[i] = static_cast<int32_t>(q);
    }
    for (size_t i = 0; i < direct.size(); ++i)
      next_[direct[i]] = lcc_grid_position(header_, {indices.direct[3 * i], indices.direct[3 * i + 1], indices.direct[3 * i + 2]});
    const int32_t theta_limit = model_->theta_limit(), rh_limit = model_->rh_limit();
    const size_t step_count = model_->order().steps.size();
    for (size_t first = 0; first < step_count; first += kLccStepChunk) {
      const size_t end = std::min(first + kLccStepChunk, step_count);
      if (!wait_for(1 + end)) return;
      for (size_t k = first; k < end; ++k) {
        int32_t* step = &indices.steps[3 * k];
        step[0] = lcc_wrapped_angle(int64_t{prediction.steps[3 * k]} + residuals_.steps[3 * k], theta_limit);
        for (size_t j = 1; j < 3; ++j) {
          step[j] = prediction.steps[3 * k + j] + residuals_.steps[3 * k + j];
          if (step[j] < -rh_limit || step[j] > rh_limit)
            fail_reconstruction(io, ErrorKind::kOutOfRange, j == 1 ? "rho" : "zeta",
                                "step " + std::to_string(k) + ": prediction and residual leave ±2^rh_bits");
        }
      }
      model_->place_chunk(first / kLccStepChunk, indices.steps, next_);
    }
  }

  ObjectHeader object_;
  LccHeader header_;
  std::vector<Triangle> faces_;
  std::optional<LccModel> model_;
  std::optional<LccPredictor> predictor_;
  std::optional<LccFrameOrder> frame_order_;
  std::vector<Vec3> positions_, next_;  // the last frame decoded, the one being decoded
  LccIndices residuals_;
  std::optional<syntax::ResidualCoder<syntax::kLccChannels>> coder_;
  bool pipelined_ = false;
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
