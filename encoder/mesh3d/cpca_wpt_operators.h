// cpca-wpt's refinement operators (docs/codec_cpca_wpt.md): a cluster's
// start or one of its components quantized at a noise step, the error it
// removes, and its refinement unit.
#pragma once

#include <Eigen/Dense>
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "encoder/mesh3d/cpca_wpt_analysis.h"
#include "mesh3d/cpca_wpt.h"
#include "syntax/io.h"

namespace m4mesh::cpca_wpt {

// A cluster's translation per frame and axis (3N values, grid units): the
// mean over its vertices of their motion about the mean shape.
using Translation = Eigen::VectorXd;

// One refinement unit as coded, with its weight's terms: a cluster's start
// (translation) or one of its components (basis, coefficients).
struct Operator {
  uint32_t cluster = 0;
  uint32_t kind = kCpcaComponent;
  uint32_t shift = kCpcaShiftBias;
  uint32_t reference = 0;   // unit_kind 5: the component continued, in the cluster's list of the previous segment
  bool trajectory = false;  // a component of the members' trajectories (unit_kind 3, or 5 continuing one)
  std::array<int64_t, 3> before{};  // a start's or continued component's base of its first differences (cpca_carried)
  int basis_exponent = 0, coefficient_exponent = 0;  // the values are the real ones × 2^(exponent / 2)
  std::vector<int32_t> basis, coefficients, translation;
  double gain = 0;    // the squared error it removes (grid units², the decoder's reconstruction)
  uint64_t bytes = 0;  // its unit, start code and header included, or its share of a group's
};

// Adds what the operator decodes to (with `undo`: subtracts it, exactly).
void apply(CpcaAnimation& animation, const Operator& op, bool undo = false);

// The operator of a component at the noise step Δ = 2^(noise / 2) grid
// units: the coefficients sigma · w in steps of Δ and the basis in steps of
// about Δ / sigma, so that both add noise of Δ's order to the animation
// (each as fine as their ranges, 2^15 and 2^23, allow). The two steps are
// powers of √2 whose product is a power of 2: their product ×
// 2^−(shift − 16) is in steps of 2^−F grid units.
// `basis_finer` half steps make the basis finer than that rule.
Operator quantize(const Component& c, uint32_t cluster, int noise, int fraction_bits, int basis_finer);

// A cluster's start at the noise step Δ: the translation t is the
// coefficient of the basis (1, …, 1) of norm √M, so it takes steps of about
// Δ / √M (as fine as its range, 2^29, allows, and no finer than 2^−F grid
// units: the shift never rounds, so that a start can be undone exactly).
Operator quantize_start(const Translation& t, uint32_t cluster, size_t members, int noise, int fraction_bits);

// A continued component (unit_kind 5) at the noise step: `basis` as the
// previous segment coded it (the real one × 2^(basis_exponent / 2)), the
// coefficients `weighted` (the real ones, for that real basis) in steps of
// about Δ / ‖basis‖ (as fine as their range allows).
Operator quantize_continued(std::span<const int32_t> basis, int basis_exponent, const Eigen::VectorXd& weighted, uint32_t cluster,
                            uint32_t reference, bool trajectory, int noise, int fraction_bits);

// The squared error a start removes, estimated: M (‖t‖² − ‖t̂ − t‖²).
double estimated_gain(const Translation& t, size_t members, const Operator& op);

// The squared error removed by an operator, estimated without decoding:
// sigma² less the quantization error ‖b̂ŵᵀ − σbwᵀ‖² (from its inner
// products, b unit).
double estimated_gain(const Component& c, const Operator& op);

// A refinement unit's data: one operator's
// (unit_kind 0 … 3 or 5), or a group of several (unit_kind 4). `started`
// holds per cluster whether its start was sent in the segment before; the
// unit's starts set it. `continuable`: per cluster, the components the
// previous segment sent.
void write_refinements(syntax::WriteIO& io, std::span<Operator* const> operators, const CpcaMeshPrediction& mesh, std::vector<uint8_t>& started,
                       std::span<const uint32_t> continuable);

}  // namespace m4mesh::cpca_wpt
