// The cloth codec in local cylindrical coordinates (codec_id 3) encoding
// (docs/codec_lcc.md): the reference mesh as the base mesh, then every
// frame in the closed loop of §4.3 of the paper: each vertex is quantized
// in the frame of the already reconstructed triangle it is reached from,
// and reconstructed exactly as the decoder does.
#include <algorithm>
#include <bit>
#include <climits>
#include <cmath>
#include <numbers>

#include "codecs3d/codec_encoder.h"
#include "codecs3d/options.h"
#include "common/error.h"
#include "mesh3d/lcc.h"
#include "mesh3d/metrics.h"
#include "mesh3d/quantization.h"
#include "syntax/mesh3d/entropy_io.h"
#include "syntax/mesh3d/lcc.h"

namespace m4mesh {

namespace {

Error usage_error(const std::string& message) { return Error(ErrorKind::kUsage, "", kNoPlane, kNoOffset, message); }

int32_t rounded(double value, int32_t lo, int32_t hi) {
  const double r = std::nearbyint(value);
  return r < lo ? lo : r > hi ? hi : static_cast<int32_t>(r);
}

// The closed loop over one frame: symbols and reconstruction.
class LccLoop {
 public:
  LccLoop(const LccModel& model, const LccHeader& header) : model_(model), header_(header) {}

  // Codes `frame` against `base` (the grid positions the direct vertices
  // are predicted from), updating `grid` (the direct vertices' new ones)
  // and `positions` (the reconstruction).
  void code(std::span<const Vec3> frame, size_t frame_index, const Grid& grid_of_frame, const std::vector<IntPoint3>& base,
            std::vector<IntPoint3>& grid, std::vector<Vec3>& positions, std::vector<int32_t>& direct, std::vector<int32_t>& steps) const {
    const LccOrder& order = model_.order();
    direct.resize(3 * order.direct.size());
    steps.resize(3 * order.steps.size());
    for (size_t i = 0; i < order.direct.size(); ++i) {
      const NodeIndex v = order.direct[i];
      IntPoint3 q;
      if (!grid_of_frame.quantize(frame[v], q))
        throw Error(ErrorKind::kInput, "", kNoPlane, kNoOffset,
                    "frame " + std::to_string(frame_index) + ", vertex " + std::to_string(v) +
                        " lies too far outside the first frame's box for the quantization grid");
      for (int axis = 0; axis < 3; ++axis) direct[3 * i + static_cast<size_t>(axis)] = q[axis] - base[v][axis];
      grid[v] = q;
      positions[v] = lcc_grid_position(header_, q);
    }
    const int32_t theta_limit = model_.theta_limit(), rh_limit = model_.rh_limit();
    const double L = model_.edge_length();
    for (size_t k = 0; k < order.steps.size(); ++k) {
      const LccStep& step = order.steps[k];
      const LccFrame local = lcc_frame(positions[step.a], positions[step.b], positions[step.c]);
      const Cylindrical c = to_cylindrical(local, frame[step.d]);
      int32_t t = static_cast<int32_t>(std::nearbyint(c.theta * theta_limit / std::numbers::pi));
      if (t >= theta_limit) t -= 2 * theta_limit;
      const int32_t rho = rounded((c.radius / L - model_.reference_radius(k)) / model_.rh_step(), -rh_limit, rh_limit);
      const int32_t zeta = rounded((c.height / L - model_.reference_height(k)) / model_.rh_step(), -rh_limit, rh_limit);
      steps[3 * k] = t;
      steps[3 * k + 1] = rho;
      steps[3 * k + 2] = zeta;
      positions[step.d] = model_.place_in(local, k, t, rho, zeta);
    }
  }

 private:
  const LccModel& model_;
  const LccHeader& header_;
};

std::vector<Float3> as_floats(std::span<const Vec3> positions) {
  std::vector<Float3> out(positions.size());
  for (size_t i = 0; i < positions.size(); ++i)
    out[i] = {static_cast<float>(positions[i].x), static_cast<float>(positions[i].y), static_cast<float>(positions[i].z)};
  return out;
}

class LccEncoder final : public CodecEncoder3d {
 public:
  LccEncoder(const MeshSequence& s, const CodecSettings& settings)
      : grid_(Grid::over(s.frames[0], settings.integer("bits"))), target_kg_(settings.number("target-kg")) {
    header_.bits = static_cast<uint32_t>(settings.integer("bits"));
    for (int axis = 0; axis < 3; ++axis) {
      header_.origin[axis] = std::bit_cast<uint32_t>(grid_.origin[axis]);
      header_.step[axis] = std::bit_cast<uint32_t>(grid_.step[axis]);
    }
    header_.mode = settings.text("mode") == "download" ? kLccDownloadMode : kLccStreamMode;
    if (settings.text("mode") != "stream" && settings.text("mode") != "download") throw usage_error("--mode is stream or download (lcc)");
    // The reference: frame 0, or a rest shape with the same connectivity.
    std::vector<Vec3> reference = s.frames[0];
    if (!settings.text("reference").empty()) {
      const MeshSequence rest = load_sequence(settings.text("reference"));
      if (rest.vertex_count != s.vertex_count || rest.faces != s.faces)
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
    header_.rh_range = std::bit_cast<uint32_t>(measured_range(s));
    const int theta_bits = settings.integer("theta-bits");
    header_.theta_bits = static_cast<uint32_t>(theta_bits);
    header_.rh_bits = static_cast<uint32_t>(settings.integer("rh-bits") ? settings.integer("rh-bits") : recommended_rh_bits(theta_bits));
    if (target_kg_ > 0) choose_bits(s);
  }

  void write_header(syntax::WriteIO& io) override { syntax::describe(io, header_); }

  void encode(const MeshSequence& s, UnitSink& sink) override {
    sink.unit(UnitType::kBaseMesh, 0, [&](syntax::WriteIO& io) { write_base_mesh(io, s.faces, reference_grid_); });
    const LccModel model = model_of(s);
    if (header_.reference == kLccReferenceIsFrame0) sink.decoded(0, as_floats(reference_));
    closed_loop(s, model, [&](size_t f, syntax::ResidualCoder<syntax::kLccChannels>& coder, std::vector<int32_t>& direct,
                              std::vector<int32_t>& steps, const std::vector<Vec3>& positions) {
      sink.unit(UnitType::kFrame, static_cast<uint32_t>(f), [&](syntax::WriteIO& io) {
        const syntax::SectionPlace place{"bins", "raw", 0, 0, io.plane()};
        if (io.trace()) {
          syntax::EntropyWriteIO<true> symbols(place, io.trace());
          write_frame(io, symbols, coder, model, direct, steps);
        } else {
          syntax::EntropyWriteIO<false> symbols(place);
          write_frame(io, symbols, coder, model, direct, steps);
        }
      });
      sink.decoded(static_cast<uint32_t>(f), as_floats(positions));
      sink.progress(f + 1, s.frames.size());
    });
  }

  std::vector<CodecStatistic> statistics() const override {
    std::vector<CodecStatistic> figures{{"theta bits", header_.theta_bits}, {"rh bits", header_.rh_bits}, {"rh range", header_.rh_range_value()}};
    if (target_kg_ > 0) figures.push_back({"KG error of the closed loop", reached_kg_});
    return figures;
  }

 private:
  template <class SymbolIO>
  static void write_frame(syntax::WriteIO& io, SymbolIO& symbols, syntax::ResidualCoder<syntax::kLccChannels>& coder, const LccModel& model,
                          std::vector<int32_t>& direct, std::vector<int32_t>& steps) {
    syntax::describe_symbols(symbols, coder, direct, steps, model.theta_limit(), model.rh_limit());
    const std::vector<uint8_t> bins = symbols.finish_bins(), raw = symbols.finish_raw();
    LccFrameData data{static_cast<uint32_t>(bins.size()), bins, raw};
    syntax::describe(io, data);
    if (io.trace()) io.trace()->stream() << symbols.trace_text();
  }

  // σ: the largest |ρ| and |ζ| of the originals (each vertex in the frame
  // of its original triangle), with 5 % to spare, as a binary32.
  float measured_range(const MeshSequence& s) const {
    const LccModel model(s.faces, reference_, 2, 1, 1);
    double largest = 0;
    for (const std::vector<Vec3>& frame : s.frames)
      for (size_t k = 0; k < model.order().steps.size(); ++k) {
        const LccStep& step = model.order().steps[k];
        const Cylindrical c = radius_and_height(lcc_frame(frame[step.a], frame[step.b], frame[step.c]), frame[step.d]);
        largest = std::max({largest, std::fabs(c.radius / model.edge_length() - model.reference_radius(k)),
                            std::fabs(c.height / model.edge_length() - model.reference_height(k))});
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
  void choose_bits(const MeshSequence& s) {
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
  Trial run_trial(const MeshSequence& s) const {
    const LccModel model = model_of(s);
    MeshSequence decoded;
    decoded.vertex_count = s.vertex_count;
    decoded.faces = s.faces;
    auto add = [&](const std::vector<Vec3>& positions) {
      std::vector<Vec3> frame;
      for (const Float3& p : as_floats(positions)) frame.push_back({p[0], p[1], p[2]});
      decoded.frames.push_back(std::move(frame));
    };
    if (header_.reference == kLccReferenceIsFrame0) add(reference_);
    Trial trial;
    closed_loop(s, model, [&](size_t, syntax::ResidualCoder<syntax::kLccChannels>& coder, std::vector<int32_t>& direct,
                              std::vector<int32_t>& steps, const std::vector<Vec3>& positions) {
      syntax::EntropyWriteIO<false> symbols(syntax::SectionPlace{});
      syntax::describe_symbols(symbols, coder, direct, steps, model.theta_limit(), model.rh_limit());
      trial.bytes += symbols.finish_bins().size() + symbols.finish_raw().size();
      add(positions);
    });
    trial.kg = kg_error(s, decoded);
    return trial;
  }

  LccModel model_of(const MeshSequence& s) const {
    return LccModel(s.faces, reference_, static_cast<int>(header_.theta_bits), static_cast<int>(header_.rh_bits), header_.rh_range_value());
  }

  // The closed loop over the coded frames at the header's bits: each frame's
  // symbols (the coder reset first in stream mode) and reconstruction go to
  // frame_coded(f, coder, direct, steps, positions).
  template <class FrameCoded>
  void closed_loop(const MeshSequence& s, const LccModel& model, FrameCoded&& frame_coded) const {
    const LccLoop loop(model, header_);
    std::vector<Vec3> positions = reference_;
    std::vector<IntPoint3> grid = reference_grid_;
    syntax::ResidualCoder<syntax::kLccChannels> coder;
    std::vector<int32_t> direct, steps;
    // Download mode predicts from the previous frame: the grid that code() updates (it reads each vertex before writing it).
    const std::vector<IntPoint3>& base = header_.mode == kLccStreamMode ? reference_grid_ : grid;
    for (size_t f = header_.reference == kLccReferenceIsFrame0 ? 1 : 0; f < s.frames.size(); ++f) {
      loop.code(s.frames[f], f, grid_, base, grid, positions, direct, steps);
      if (header_.mode == kLccStreamMode) coder = {};
      frame_coded(f, coder, direct, steps, positions);
    }
  }

  Grid grid_;
  LccHeader header_;
  double target_kg_;
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
          {"target-kg", "lcc: the fewest angle bits whose KG error is at most this (0: off; overrides --theta-bits and --rh-bits)",
           OptionKind::kNumber, "0", 0, 100}};
}

std::unique_ptr<CodecEncoder3d> make_lcc_encoder(const MeshSequence& sequence, const CodecSettings& settings) {
  return std::make_unique<LccEncoder>(sequence, settings);
}

}  // namespace m4mesh
