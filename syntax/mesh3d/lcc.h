// The cloth codec in local cylindrical coordinates (codec_id 3) syntax
// (docs/codec_lcc.md): the codec header, and a frame unit's data, a bin
// section and a raw section holding the directly coded vertices' grid
// residuals and every other vertex's quantized (θ, ρ, ζ).
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <span>

#include "common/bit_cast.h"
#include "syntax/io.h"
#include "syntax/mesh3d/grid.h"
#include "syntax/mesh3d/residual.h"

namespace m4mesh {

inline constexpr uint32_t kLccReferenceIsFrame0 = 0;
inline constexpr uint32_t kLccReferenceIsRestShape = 1;
inline constexpr uint32_t kLccStreamMode = 0;
inline constexpr uint32_t kLccDownloadMode = 1;
inline constexpr uint32_t kLccMaxGop = 64;

struct LccHeader {
  uint32_t bits = 12;  // the grid of the base mesh and of the directly coded vertices
  std::array<uint32_t, 3> origin{};  // binary32 bit patterns
  std::array<uint32_t, 3> step{};
  uint32_t reference = kLccReferenceIsFrame0;
  uint32_t mode = kLccStreamMode;
  uint32_t theta_bits = 6;  // b_θ: θ in steps of π / 2^b_θ
  uint32_t rh_bits = 3;     // b_rh: ρ and ζ in steps of σ / 2^b_rh
  uint32_t rh_range = 0;    // σ, binary32: |ρ|, |ζ| ≤ σ
  uint32_t gop = 0;         // temporal prediction: anchors every gop frames (0: none)

  float origin_value(int axis) const { return bit_cast<float>(origin[axis]); }
  float step_value(int axis) const { return bit_cast<float>(step[axis]); }
  float rh_range_value() const { return bit_cast<float>(rh_range); }
};

// A frame unit's data: the bin section's length, the bins, the raw bits.
struct LccFrameData {
  uint32_t arithmetic_bytes = 0;
  std::span<const uint8_t> bins;
  std::span<const uint8_t> raw;
};

namespace syntax {

// Channels of the residual coder: the direct vertices' x, y, z, then θ, ρ,
// ζ; anchors use 0 … 5, frames predicted between anchors 6 … 11.
inline constexpr int kLccDirectChannel = 0;
inline constexpr int kLccThetaChannel = 3;
inline constexpr int kLccRadiusChannel = 4;
inline constexpr int kLccHeightChannel = 5;
inline constexpr int kLccPredictedChannels = 6;
inline constexpr int kLccChannels = 12;
inline constexpr ResidualNames kLccDirect = M4MESH_RESIDUAL_NAMES("direct", "direct_position");
inline constexpr ResidualNames kLccTheta = M4MESH_RESIDUAL_NAMES("theta", "theta");
inline constexpr ResidualNames kLccRadius = M4MESH_RESIDUAL_NAMES("rho", "rho");
inline constexpr ResidualNames kLccHeight = M4MESH_RESIDUAL_NAMES("zeta", "zeta");

template <class IO>
void describe(IO& io, LccHeader& h) {
  io.field_in("quantization_bits", 8, h.bits, 4, 24);
  describe_grid(io, h.origin, h.step);
  io.field_in("reference_mode", 8, h.reference, kLccReferenceIsFrame0, kLccReferenceIsRestShape);
  io.field_in("coding_mode", 8, h.mode, kLccStreamMode, kLccDownloadMode);
  io.field_in("theta_bits", 8, h.theta_bits, 2, 15);
  io.field_in("rh_bits", 8, h.rh_bits, 1, 20);
  binary32(io, "rh_range", h.rh_range);
  io.require(std::isfinite(h.rh_range_value()) && h.rh_range_value() > 0, ErrorKind::kOutOfRange, "rh_range",
             "not a positive finite binary32");
  io.field_in("temporal_gop", 8, h.gop, 0, kLccMaxGop);
  io.require(h.gop != 1, ErrorKind::kOutOfRange, "temporal_gop", "1: no temporal prediction is 0");
}

template <class IO>
void describe(IO& io, LccFrameData& f) {
  io.field("arithmetic_bytes", 32, f.arithmetic_bytes);
  io.require_length("arithmetic_bytes", f.arithmetic_bytes);
  io.section("bins", f.arithmetic_bytes, f.bins);
  io.tail_section("raw", f.raw);
}

// A frame's symbols, residuals against the frame's prediction
// (mesh3d/lcc.h): per directly coded vertex, its x, y, z grid residual;
// per step, θ, ρ and ζ (θ in [−theta_limit, theta_limit), ρ and ζ in
// [−rh_limit, rh_limit] for an anchor and twice that for a predicted
// frame). The coder carries the contexts (reset per frame in stream mode,
// carried across frames in download mode).
template <class IO>
void describe_symbols(IO& io, ResidualCoder<kLccChannels>& coder, bool predicted, std::span<int32_t> direct, std::span<int32_t> steps,
                      int32_t theta_limit, int32_t rh_limit) {
  const int base = predicted ? kLccPredictedChannels : 0;
  const int32_t rh_residual = predicted ? 2 * rh_limit : rh_limit;
  for (size_t i = 0; i < direct.size(); ++i) coder.describe(io, base + kLccDirectChannel + static_cast<int>(i % 3), direct[i], kLccDirect);
  for (size_t i = 0; i < steps.size(); i += 3) {
    coder.describe(io, base + kLccThetaChannel, steps[i], kLccTheta);
    if (steps[i] < -theta_limit || steps[i] >= theta_limit) io.fail(ErrorKind::kOutOfRange, "theta", "an angle index beyond ±2^theta_bits");
    coder.describe(io, base + kLccRadiusChannel, steps[i + 1], kLccRadius);
    if (steps[i + 1] < -rh_residual || steps[i + 1] > rh_residual) io.fail(ErrorKind::kOutOfRange, "rho", "a radius residual beyond its range");
    coder.describe(io, base + kLccHeightChannel, steps[i + 2], kLccHeight);
    if (steps[i + 2] < -rh_residual || steps[i + 2] > rh_residual) io.fail(ErrorKind::kOutOfRange, "zeta", "a height residual beyond its range");
  }
}

}  // namespace syntax

}  // namespace m4mesh
