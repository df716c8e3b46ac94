// The cloth codec in local cylindrical coordinates (codec_id 3) encoding
// (docs/codec_lcc.md): the reference mesh as the base mesh, then every
// frame in the closed loop of §4.3 of the paper: each vertex is quantized
// in the frame of the already reconstructed triangle it is reached from,
// and reconstructed exactly as the decoder does.
#include <algorithm>
#include <climits>
#include <cmath>
#include <numbers>

#include "codecs3d/codec_encoder.h"
#include "common/bit_cast.h"
#include "common/error.h"
#include "encoder/mesh3d/codec_options.h"
#include "encoder/mesh3d/quality_target.h"
#include "mesh3d/lcc.h"
#include "mesh3d/metrics.h"
#include "mesh3d/quantization.h"
#include "syntax/mesh3d/entropy_io.h"
#include "syntax/mesh3d/lcc.h"

namespace m4mesh {

namespace {


int32_t rounded(double value, int32_t lo, int32_t hi) {
  const double r = std::nearbyint(value);
  return r < lo ? lo : r > hi ? hi : static_cast<int32_t>(r);
}

// Brings a frame into the cache in address order before the coding order
// reads it out of order (the hardware prefetcher then streams it).
void prefetch(std::span<const Vec3> frame) {
  const char* bytes = reinterpret_cast<const char*>(frame.data());
  for (size_t offset = 0; offset < frame.size_bytes(); offset += 64) __builtin_prefetch(bytes + offset);
}

// The closed loop over one frame: indices and reconstruction.
class LccLoop {
 public:
  LccLoop(const LccModel& model, const LccHeader& header) : model_(model), header_(header) {}

  // Quantizes `frame` into `indices`, vertex after vertex in the frame of
  // the reconstructed triangle it is reached from, and reconstructs it
  // into `positions`.
  void code(std::span<const Vec3> frame, size_t frame_index, const Grid& grid_of_frame, LccIndices& indices,
            std::vector<Vec3>& positions) const {
    const LccOrder& order = model_.order();
    prefetch(frame);
    indices.direct.resize(3 * order.direct.size());
    indices.steps.resize(3 * order.steps.size());
    for (size_t i = 0; i < order.direct.size(); ++i) {
      const NodeIndex v = order.direct[i];
      IntPoint3 q;
      if (!grid_of_frame.quantize(frame[v], q))
        throw Error(ErrorKind::kInput, "", kNoPlane, kNoOffset,
                    "frame " + std::to_string(frame_index) + ", vertex " + std::to_string(v) +
                        " lies beyond the quantization grid's ±2^26 steps");
      for (int axis = 0; axis < 3; ++axis) indices.direct[3 * i + static_cast<size_t>(axis)] = q[axis];
      positions[v] = lcc_grid_position(header_, q);
    }
    const int32_t theta_limit = model_.theta_limit(), rh_limit = model_.rh_limit();
    const double L = model_.edge_length();
    for (size_t k = 0; k < order.steps.size(); ++k) {
      const LccStep& step = order.steps[k];
      const LccFrame local = lcc_frame(positions[step.a], positions[step.b], positions[step.c]);
      const Cylindrical c = to_cylindrical(local, frame[step.d]);
      const int32_t t = lcc_wrapped_angle(static_cast<int64_t>(std::nearbyint(c.theta * theta_limit / std::numbers::pi)), theta_limit);
      const int32_t rho = rounded((c.radius / L - model_.reference_radius(k)) / model_.rh_step(), -rh_limit, rh_limit);
      const int32_t zeta = rounded((c.height / L - model_.reference_height(k)) / model_.rh_step(), -rh_limit, rh_limit);
      indices.steps[3 * k] = t;
      indices.steps[3 * k + 1] = rho;
      indices.steps[3 * k + 2] = zeta;
      positions[step.d] = model_.place_in(local, k, t, rho, zeta);
    }
  }

 private:
  const LccModel& model_;
  const LccHeader& header_;
};

// The residuals of a frame's indices against their prediction (θ wrapped).
void residuals_of(const LccIndices& indices, const LccIndices& prediction, int32_t theta_limit, LccIndices& residuals) {
  residuals.direct.resize(indices.direct.size());
  for (size_t i = 0; i < indices.direct.size(); ++i) residuals.direct[i] = indices.direct[i] - prediction.direct[i];
  residuals.steps.resize(indices.steps.size());
  for (size_t i = 0; i < indices.steps.size(); i += 3) {
    residuals.steps[i] = lcc_wrapped_angle(int64_t{indices.steps[i]} - prediction.steps[i], theta_limit);
    residuals.steps[i + 1] = indices.steps[i + 1] - prediction.steps[i + 1];
    residuals.steps[i + 2] = indices.steps[i + 2] - prediction.steps[i + 2];
  }
}

std::vector<Float3> as_floats(std::span<const Vec3> positions) {
  std::vector<Float3> out(positions.size());
  for (size_t i = 0; i < positions.size(); ++i)
    out[i] = {static_cast<float>(positions[i].x), static_cast<float>(positions[i].y), static_cast<float>(positions[i].z)};
  return out;
}

class LccEncoder final : public CodecEncoder3d {
 public:
  LccEncoder(const FrameSource& s, const CodecSettings& settings)
      : grid_(Grid::covering(s, settings.integer("bits"))), target_kg_(settings.number("target-kg")), base_mesh_(settings.base_mesh()) {
    header_.bits = static_cast<uint32_t>(settings.integer("bits"));
    for (int axis = 0; axis < 3; ++axis) {
      header_.origin[axis] = bit_cast<uint32_t>(grid_.origin[axis]);
      header_.step[axis] = bit_cast<uint32_t>(grid_.step[axis]);
    }
    header_.mode = settings.text("mode") == "download" ? kLccDownloadMode : kLccStreamMode;
    if (settings.text("mode") != "stream" && settings.text("mode") != "download") throw usage_error("--mode is stream or download (lcc)");
    // The reference: frame 0, or a rest shape with the same connectivity.
    std::vector<Vec3> reference(s.vertex_count());
    s.read(0, reference);
    if (!settings.text("reference").empty()) {
      const MeshSequence rest = load_sequence(settings.text("reference"));
      if (rest.vertex_count != s.vertex_count() || !same_faces(rest.faces, s.faces()))
        throw usage_error(settings.text("reference") + ": the reference must have the sequence's vertices and faces (lcc)");
      reference = rest.frames[0];
      header_.reference = kLccReferenceIsRestShape;
    }
    reference_grid_.resize(reference.size());
    for (size_t i = 0; i < reference.size(); ++i)
      if (!grid_.quantize(reference[i], reference_grid_[i]))
        throw Error(ErrorKind::kInput, "", kNoPlane, kNoOffset, "reference vertex " + std::to_string(i) + " lies too far outside the grid");
    reference_.resize(reference.size());
    for (size_t i = 0; i < reference.size(); ++i) reference_[i] = lcc_grid_position(header_, reference_grid_[i]);
    header_.rh_range = bit_cast<uint32_t>(measured_range(s));
    const int theta_bits = settings.integer("theta-bits");
    header_.theta_bits = static_cast<uint32_t>(theta_bits);
    header_.rh_bits = static_cast<uint32_t>(settings.integer("rh-bits") ? settings.integer("rh-bits") : recommended_rh_bits(theta_bits));
    header_.gop = settings.flag("temporal") ? static_cast<uint32_t>(settings.integer("gop")) : 0;
    if (target_kg_ > 0) {
      // A long sequence's bits are chosen on a sample of its frames.
      if (uint64_t{s.vertex_count()} * s.frame_count() > kWholeSearchVertexFrames)
        choose_bits(ClipSource(s, sample_frames(s.vertex_count(), s.frame_count())));
      else
        choose_bits(s);
    }
  }

  void write_header(syntax::WriteIO& io) override { syntax::describe(io, header_); }

  void encode(const FrameSource& s, UnitSink& sink) override {
    sink.unit(UnitType::kBaseMesh, 0, [&](syntax::WriteIO& io) { write_base_mesh(io, s.faces(), reference_grid_, base_mesh_); });
    const LccModel model = model_of(s);
    if (header_.reference == kLccReferenceIsFrame0) sink.decoded(0, as_floats(reference_));
    size_t done = 0;
    closed_loop(s, model, [&](const LccCodedFrame& coded, syntax::ResidualCoder<syntax::kLccChannels>& coder, LccIndices& residuals,
                              const std::vector<Vec3>& positions) {
      sink.unit(UnitType::kFrame, coded.frame, [&](syntax::WriteIO& io) {
        const syntax::SectionPlace place{"bins", "raw", 0, 0, io.plane()};
        if (io.trace()) {
          syntax::EntropyWriteIO<true> symbols(place, io.trace());
          write_frame(io, symbols, coder, model, !coded.anchor(), residuals);
        } else {
          syntax::EntropyWriteIO<false> symbols(place);
          write_frame(io, symbols, coder, model, !coded.anchor(), residuals);
        }
      });
      sink.decoded(coded.frame, as_floats(positions));
      sink.progress(++done, s.frame_count());
    });
  }

  std::vector<CodecStatistic> statistics() const override {
    std::vector<CodecStatistic> figures{
        {"theta bits", header_.theta_bits}, {"rh bits", header_.rh_bits}, {"rh range", header_.rh_range_value()}, {"temporal gop", header_.gop}};
    if (target_kg_ > 0) figures.push_back({"KG error of the closed loop", reached_kg_});
    return figures;
  }

 private:
  template <class SymbolIO>
  static void write_frame(syntax::WriteIO& io, SymbolIO& symbols, syntax::ResidualCoder<syntax::kLccChannels>& coder, const LccModel& model,
                          bool predicted, LccIndices& residuals) {
    syntax::describe_symbols(symbols, coder, predicted, residuals.direct, residuals.steps, model.theta_limit(), model.rh_limit());
    LccFrameData data;
    symbols.finish(io, data);
  }

  // σ: the largest |ρ| and |ζ| of the originals (each vertex in the frame
  // of its original triangle), with 5 % to spare, as a binary32. The
  // height is along b → c and the radius follows from |d − O|² − height²,
  // without the rest of the frame.
  float measured_range(const FrameSource& s) const {
    const LccModel model(s.faces(), reference_, 2, 1, 1);
    double largest = 0;
    FrameReader reader(s);
    for (uint32_t f = 0; f < s.frame_count(); ++f) {
      const std::span<const Vec3> frame = reader.get(f);
      prefetch(frame);
      for (size_t k = 0; k < model.order().steps.size(); ++k) {
        const LccStep& step = model.order().steps[k];
        const Vec3 &b = frame[step.b], &c = frame[step.c], &p = frame[step.d];
        const Vec3 axis{c.x - b.x, c.y - b.y, c.z - b.z}, d{p.x - (b.x + c.x) * 0.5, p.y - (b.y + c.y) * 0.5, p.z - (b.z + c.z) * 0.5};
        const double axis_length = std::sqrt(axis.x * axis.x + axis.y * axis.y + axis.z * axis.z);
        const double height = axis_length > 0 ? (d.x * axis.x + d.y * axis.y + d.z * axis.z) / axis_length : d.x;
        const double radius = std::sqrt(std::max(0.0, d.x * d.x + d.y * d.y + d.z * d.z - height * height));
        largest = std::max({largest, std::fabs(radius / model.edge_length() - model.reference_radius(k)),
                            std::fabs(height / model.edge_length() - model.reference_height(k))});
      }
    }
    const float range = static_cast<float>(std::max(1.05 * largest, 0x1p-20));
    return std::isfinite(range) ? range : 0x1p20f;
  }

  // Eq. 1 of the paper: b_rh = b_θ − ⌊0.5 − log2 σ⌋, within 1 … 20.
  int recommended_rh_bits(int theta_bits) const {
    const int bits = theta_bits - static_cast<int>(std::floor(0.5 - std::log2(header_.rh_range_value())));
    return std::clamp(bits, 1, 20);
  }

  // The bits that reach the target with the smallest frame data: per b_θ
  // (ascending) the smallest b_rh up to two above Eq. 1's that reaches it,
  // measured on the closed loop and its coded symbols; the ascent stops
  // once two b_θ in a row coded larger than the best.
  void choose_bits(const FrameSource& s) {
    uint64_t best_bytes = UINT64_MAX;
    uint32_t best_theta = 0, best_rh = 0;
    int worse = 0;
    for (int theta_bits = 2; theta_bits <= 15 && worse < 2; ++theta_bits) {
      for (int rh_bits = 1; rh_bits <= std::min(20, recommended_rh_bits(theta_bits) + 2); ++rh_bits) {
        header_.theta_bits = static_cast<uint32_t>(theta_bits);
        header_.rh_bits = static_cast<uint32_t>(rh_bits);
        const Trial trial = run_trial(s);
        if (trial.kg > target_kg_) continue;
        if (trial.bytes < best_bytes) {
          best_bytes = trial.bytes;
          best_theta = header_.theta_bits;
          best_rh = header_.rh_bits;
          reached_kg_ = trial.kg;
          worse = 0;
        } else {
          ++worse;
        }
        break;
      }
    }
    if (best_bytes == UINT64_MAX)
      throw usage_error("--target-kg " + std::to_string(target_kg_) + " is out of reach even at 15 angle bits (lcc)");
    header_.theta_bits = best_theta;
    header_.rh_bits = best_rh;
  }

  struct Trial {
    double kg = 0;
    uint64_t bytes = 0;  // every frame's bins and raw bits
  };

  // The closed loop over the whole sequence at the header's bits: the KG
  // error of its reconstruction and the size of its coded symbols.
  Trial run_trial(const FrameSource& s) const {
    const LccModel model = model_of(s);
    QualityMeter meter(s);
    if (header_.reference == kLccReferenceIsFrame0) meter.add(0, as_floats(reference_));
    Trial trial;
    closed_loop(s, model, [&](const LccCodedFrame& coded, syntax::ResidualCoder<syntax::kLccChannels>& coder, LccIndices& residuals,
                              const std::vector<Vec3>& positions) {
      syntax::EntropyWriteIO<false> symbols(syntax::SectionPlace{});
      syntax::describe_symbols(symbols, coder, !coded.anchor(), residuals.direct, residuals.steps, model.theta_limit(), model.rh_limit());
      trial.bytes += symbols.finish_bins().size() + symbols.finish_raw().size();
      meter.add(coded.frame, as_floats(positions));
    });
    trial.kg = meter.kg();
    return trial;
  }

  LccModel model_of(const FrameSource& s) const {
    return LccModel(s.faces(), reference_, static_cast<int>(header_.theta_bits), static_cast<int>(header_.rh_bits), header_.rh_range_value());
  }

  // The closed loop over the coded frames at the header's bits, in coding
  // order: each frame's residuals (the coder reset first in stream mode)
  // and reconstruction go to frame_coded(coded, coder, residuals, positions).
  template <class FrameCoded>
  void closed_loop(const FrameSource& s, const LccModel& model, FrameCoded&& frame_coded) const {
    const LccLoop loop(model, header_);
    LccPredictor predictor(header_, model.order(), reference_grid_);
    LccFrameOrder order(header_.reference == kLccReferenceIsFrame0 ? 1 : 0, s.frame_count(), header_.gop);
    std::vector<Vec3> positions = reference_;
    FrameReader reader(s);
    syntax::ResidualCoder<syntax::kLccChannels> coder;
    LccIndices indices, residuals;
    while (!order.done()) {
      const LccCodedFrame coded = order.next();
      loop.code(reader.get(coded.frame), coded.frame, grid_, indices, positions);
      residuals_of(indices, predictor.predict(coded), model.theta_limit(), residuals);
      predictor.keep(coded, indices);
      if (header_.mode == kLccStreamMode) coder = {};
      frame_coded(coded, coder, residuals, positions);
    }
  }

  Grid grid_;
  LccHeader header_;
  double target_kg_;
  BaseMeshCoding base_mesh_;
  double reached_kg_ = 0;
  std::vector<IntPoint3> reference_grid_;
  std::vector<Vec3> reference_;
};

}  // namespace

std::vector<CodecOption> lcc_options() {
  return {bits_option("quantization bits of the reference mesh and the directly coded vertices"),
          {"theta-bits", "lcc: b_θ, angle steps of π / 2^b_θ", OptionKind::kInteger, "6", 2, 15},
          {"rh-bits", "lcc: b_rh, radius and height steps of σ / 2^b_rh (0: Eq. 1 of the paper)", OptionKind::kInteger, "0", 0, 20},
          {"mode", "lcc: stream (every frame decodable alone) or download (contexts carried across frames)", OptionKind::kText, "stream", 0, 0},
          {"reference", "lcc: a rest shape (OBJ) with the sequence's connectivity, sent as the base mesh (default: frame 0)",
           OptionKind::kText, "", 0, 0},
          {"temporal", "lcc: temporal prediction between anchor frames (the hierarchy of the paper's [23]; frames coded out of order)",
           OptionKind::kFlag, "", 0, 0},
          {"gop", "lcc --temporal: an anchor frame every this many frames", OptionKind::kInteger, "4", 2, kLccMaxGop},
          {"target-kg", "lcc: the fewest angle bits whose KG error is at most this (0: off; overrides --theta-bits and --rh-bits)",
           OptionKind::kNumber, "0", 0, 100}};
}

std::unique_ptr<CodecEncoder3d> make_lcc_encoder(const FrameSource& sequence, const CodecSettings& settings) {
  return std::make_unique<LccEncoder>(sequence, settings);
}

}  // namespace m4mesh
