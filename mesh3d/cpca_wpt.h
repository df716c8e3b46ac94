// The normative process of the clustered-PCA codec (codec_id 4,
// ../shared/seeds/002), shared by its encoder and decoder: the clusters
// from the cluster map, and the decoded animation in fixed point, which
// every refinement operator refines in place (Eq. 5 of the report,
// Φᵢ₊₁ = Φᵢ + Bᵢ Sᵢᵢ Vᵢᵀ) with integer arithmetic only.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "common/point3.h"
#include "mesh/topology.h"
#include "syntax/mesh3d/cpca_wpt.h"

namespace m4mesh {

// Each cluster's vertices in index order.
std::vector<std::vector<NodeIndex>> cpca_members(std::span<const uint32_t> cluster_of, uint32_t cluster_count);

// The number of components of a cluster of `members` vertices over
// `frames` frames: the rank bound min(3 · members, frames).
inline uint64_t cpca_component_limit(size_t members, uint32_t frames) { return std::min<uint64_t>(3 * uint64_t{members}, frames); }

// The animation as decoded so far: per frame, vertex and axis a 64-bit
// integer in steps of 2^−F grid units, starting at the mean shape's grid
// index × 2^F (arithmetic modulo 2^64), and its positions in binary32.
class CpcaAnimation {
 public:
  CpcaAnimation(const CpcaHeader& header, std::span<const IntPoint3> mean_shape, uint32_t frames);

  uint32_t frames() const { return frames_; }
  size_t vertex_count() const { return vertex_count_; }

  // Adds round(translation[3n + a] × 2^−(shift − 16)) to frame n, axis a
  // of every member, and updates those positions (a cluster's start).
  void translate(std::span<const NodeIndex> members, std::span<const int32_t> translation, uint32_t shift);
  // Adds round(basis[3i + a] × coefficients[n] × 2^−(shift − 16)) to
  // frame n, vertex members[i], axis a, and updates those positions.
  void refine(std::span<const NodeIndex> members, std::span<const int32_t> basis, std::span<const int32_t> coefficients, uint32_t shift);

  std::span<const Float3> frame(uint32_t f) const { return {positions_.data() + size_t{f} * vertex_count_, vertex_count_}; }

 private:
  Float3 position_of(size_t element) const;

  size_t vertex_count_;
  uint32_t frames_;
  std::array<double, 3> origin_, unit_;  // unit: the grid step × 2^−F
  std::vector<uint64_t> fixed_;          // frame-major, then vertex, then axis
  std::vector<Float3> positions_;
};

}  // namespace m4mesh
