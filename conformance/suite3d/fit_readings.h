// The affine fit of docs/codec_cpca_wpt.md ("Prediction by the mean
// shape") as a decoder that takes its binary64 steps in another order
// would compute it, and values whose exact fit is an integer, where such a
// decoder floors to another prediction: the suite's stream that tells each
// reading from the text's.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "common/random.h"

namespace m4mesh::suite3d {

enum class FitReading {
  kText,                    // the text's order (mesh3d/affine_fit.h)
  kSarrusDeterminant,       // det as Sarrus's six products, left to right
  kDeterminantRightFirst,   // det = C00 c0 − (C01 c1 − C02 c2)
  kFused,                   // c0, c1, c2 and det contracted to fused multiply-adds
  kMeanFirstInResidual,     // r = T − S × (B / n)
  kMeanFirstInMatrix,       // C = M − S × (S / n)
  kCofactorSolve,           // g = adj(C) r / det, each row's three products summed left to right
  kMeanMinusSlope,          // c = B / n − (g · S) / n
  kSlopeSumRightFirst,      // g · S = g0 S0 + (g1 S1 + g2 S2)
};
inline constexpr int kFitReadings = 9;

// One lane's prediction floor(c) under `reading`, from the points'
// differences q and their values x.
int64_t fit_as_read(std::span<const std::array<int32_t, 3>> q, std::span<const int32_t> x, FitReading reading);

// Values within ±2^15 for the points q whose exact fit is an integer and
// whose prediction under `reading` differs from the text's; none after
// `tries` draws of `random`.
std::optional<std::vector<int32_t>> values_telling_apart(std::span<const std::array<int32_t, 3>> q, FitReading reading, SplitMix64& random,
                                                         int tries);

}  // namespace m4mesh::suite3d
