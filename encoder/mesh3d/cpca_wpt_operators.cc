#include "encoder/mesh3d/cpca_wpt_operators.h"

#include <algorithm>
#include <cmath>

#include "common/error.h"
#include "mesh3d/quantization.h"
#include "syntax/mesh3d/cpca_wpt.h"
#include "syntax/mesh3d/entropy_io.h"

namespace m4mesh::cpca_wpt {

namespace {

// Exponent e such that |largest| · 2^e < 2^bits.
int exponent_for(double largest, int bits) { return largest > 0 ? bits - 1 - std::ilogb(largest) : bits; }

// Floor division by 2.
int half_of(int value) { return value >= 0 ? value / 2 : -((1 - value) / 2); }

std::vector<int32_t> scaled(const Eigen::VectorXd& values, int half_exponent) {
  const double scale = power_of_sqrt2(half_exponent);
  std::vector<int32_t> out(static_cast<size_t>(values.size()));
  for (Eigen::Index i = 0; i < values.size(); ++i) out[static_cast<size_t>(i)] = static_cast<int32_t>(std::nearbyint(values(i) * scale));
  return out;
}

template <class SymbolIO>
void write_refinements(syntax::WriteIO& io, SymbolIO& symbols, std::span<Operator* const> operators, const CpcaMeshPrediction& mesh,
                       std::vector<uint8_t>& started, std::span<const uint32_t> continuable) {
  CpcaRefinement r;
  for (const Operator* op : operators) r.group.push_back({op->cluster, op->kind, op->shift, op->reference});
  auto start = [&](const CpcaRefinementHeader& h, bool) {
    if (h.kind == kCpcaStart) started[h.cluster] = 1;
  };
  if (r.group.size() > 1) {
    syntax::CpcaGroupContexts contexts;
    syntax::describe_group_list(
        symbols, contexts, std::span(r.group), static_cast<uint32_t>(started.size()), [&](uint32_t cluster) { return started[cluster] != 0; },
        [&](uint32_t cluster) { return continuable[cluster]; }, start);
  } else {
    for (const CpcaRefinementHeader& h : r.group) start(h, false);
  }
  syntax::CpcaCoders coders;
  for (size_t i = 0; i < operators.size(); ++i)
    describe_refinement(symbols, coders, mesh, r.group[i], operators[i]->trajectory, operators[i]->before, operators[i]->translation,
                        operators[i]->basis, operators[i]->coefficients);
  if (r.group.size() == 1) {
    r.cluster = r.group[0].cluster;
    r.kind = r.group[0].kind;
    r.shift = r.group[0].shift;
    r.reference = r.group[0].reference;
    r.group.clear();
  } else {
    r.cluster = 0;
    r.kind = kCpcaGroup;
    r.shift = 0;
  }
  symbols.finish(io, r);
}

}  // namespace

void apply(CpcaAnimation& animation, const Operator& op, bool undo) {
  if (op.kind == kCpcaStart)
    animation.translate(op.cluster, op.translation, op.shift, undo);
  else
    animation.refine(op.cluster, op.basis, op.coefficients, op.shift, op.trajectory, undo);
}

Operator quantize(const Component& c, uint32_t cluster, int noise, int fraction_bits, int basis_finer) {
  const Eigen::VectorXd weighted = c.sigma * c.coefficients;
  const int basis_exponent = std::min(2 * std::ilogb(c.sigma) - noise + basis_finer, 2 * exponent_for(c.basis.cwiseAbs().maxCoeff(), 15));
  const int wanted = std::min(-noise, 2 * exponent_for(weighted.cwiseAbs().maxCoeff(), 23));
  const int shift = std::clamp(half_of(basis_exponent + wanted) - fraction_bits, -static_cast<int>(kCpcaShiftBias),
                               static_cast<int>(kCpcaMaxShift - kCpcaShiftBias));
  const int coefficient_exponent = 2 * (shift + fraction_bits) - basis_exponent;
  Operator op;
  op.cluster = cluster;
  op.shift = static_cast<uint32_t>(shift + static_cast<int>(kCpcaShiftBias));
  op.basis_exponent = basis_exponent;
  op.coefficient_exponent = coefficient_exponent;
  op.basis = scaled(c.basis, basis_exponent);
  op.coefficients = scaled(weighted, coefficient_exponent);
  for (int32_t v : op.coefficients)
    if (v > kCpcaMaxCoefficient || v < -kCpcaMaxCoefficient)
      throw Error(ErrorKind::kInput, "", kNoPlane, kNoOffset, "a motion too large for the fixed point of cpca-wpt: use fewer --bits");
  return op;
}

Operator quantize_start(const Translation& t, uint32_t cluster, size_t members, int noise, int fraction_bits) {
  const int wanted = std::min(half_of(2 * std::ilogb(std::sqrt(static_cast<double>(members))) - noise), exponent_for(t.cwiseAbs().maxCoeff(), 29));
  const int shift = std::clamp(wanted - fraction_bits, -static_cast<int>(kCpcaShiftBias), 0);
  Operator op;
  op.cluster = cluster;
  op.kind = kCpcaStart;
  op.shift = static_cast<uint32_t>(shift + static_cast<int>(kCpcaShiftBias));
  op.coefficient_exponent = 2 * (shift + fraction_bits);
  op.translation = scaled(t, op.coefficient_exponent);
  for (int32_t v : op.translation)
    if (v > kCpcaMaxTranslation || v < -kCpcaMaxTranslation)
      throw Error(ErrorKind::kInput, "", kNoPlane, kNoOffset, "a motion too large for the fixed point of cpca-wpt: use fewer --bits");
  return op;
}

Operator quantize_continued(std::span<const int32_t> basis, int basis_exponent, const Eigen::VectorXd& weighted, uint32_t cluster,
                            uint32_t reference, bool trajectory, int noise, int fraction_bits) {
  double norm = 0;
  for (int32_t b : basis) norm += static_cast<double>(b) * static_cast<double>(b);
  norm = std::sqrt(norm) / power_of_sqrt2(basis_exponent);
  // The coefficients of the unit basis are weighted × norm, in steps of Δ.
  const int wanted = std::min(-noise + static_cast<int>(std::lround(2 * std::log2(std::max(norm, 0x1p-30)))),
                              2 * exponent_for(weighted.cwiseAbs().maxCoeff(), 23));
  const int shift = std::clamp(half_of(basis_exponent + wanted) - fraction_bits, -static_cast<int>(kCpcaShiftBias),
                               static_cast<int>(kCpcaMaxShift - kCpcaShiftBias));
  Operator op;
  op.cluster = cluster;
  op.kind = kCpcaContinued;
  op.reference = reference;
  op.trajectory = trajectory;
  op.shift = static_cast<uint32_t>(shift + static_cast<int>(kCpcaShiftBias));
  op.basis_exponent = basis_exponent;
  op.coefficient_exponent = 2 * (shift + fraction_bits) - basis_exponent;
  op.basis.assign(basis.begin(), basis.end());
  op.coefficients = scaled(weighted, op.coefficient_exponent);
  for (int32_t v : op.coefficients)
    if (v > kCpcaMaxCoefficient || v < -kCpcaMaxCoefficient)
      throw Error(ErrorKind::kInput, "", kNoPlane, kNoOffset, "a motion too large for the fixed point of cpca-wpt: use fewer --bits");
  return op;
}

double estimated_gain(const Translation& t, size_t members, const Operator& op) {
  double removed = 0;
  for (Eigen::Index j = 0; j < t.size(); ++j) {
    const double q = op.translation[static_cast<size_t>(j)] / power_of_sqrt2(op.coefficient_exponent);
    removed += t(j) * t(j) - (q - t(j)) * (q - t(j));
  }
  return static_cast<double>(members) * removed;
}

double estimated_gain(const Component& c, const Operator& op) {
  double bb = 0, bq = 0, ww = 0, wq = 0;
  for (Eigen::Index j = 0; j < c.basis.size(); ++j) {
    const double b = op.basis[static_cast<size_t>(j)] / power_of_sqrt2(op.basis_exponent);
    bb += b * b;
    bq += b * c.basis(j);
  }
  for (Eigen::Index n = 0; n < c.coefficients.size(); ++n) {
    const double w = op.coefficients[static_cast<size_t>(n)] / power_of_sqrt2(op.coefficient_exponent);
    ww += w * w;
    wq += w * c.sigma * c.coefficients(n);
  }
  const double noise = bb * ww - 2 * bq * wq + c.sigma * c.sigma;
  return c.sigma * c.sigma - noise;
}

void write_refinements(syntax::WriteIO& io, std::span<Operator* const> operators, const CpcaMeshPrediction& mesh, std::vector<uint8_t>& started,
                       std::span<const uint32_t> continuable) {
  const syntax::SectionPlace place{"bins", "raw", 0, 0, io.plane()};
  if (io.trace()) {
    syntax::EntropyWriteIO<true> symbols(place, io.trace());
    write_refinements(io, symbols, operators, mesh, started, continuable);
  } else {
    syntax::EntropyWriteIO<false> symbols(place);
    write_refinements(io, symbols, operators, mesh, started, continuable);
  }
}

}  // namespace m4mesh::cpca_wpt
