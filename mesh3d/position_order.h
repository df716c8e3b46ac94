// The order in which values on the vertices are predicted (docs/base_mesh.md,
// "Position order"): the vertex best predicted by the ones before it comes
// next, rather than the next in coding order.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "mesh3d/mesh_predictor.h"

namespace m4mesh {

class PositionOrder {
 public:
  PositionOrder(const MeshPredictor& predictor, uint32_t vertex_count);

  // The candidates (given in the order that breaks ties) ordered so that
  // each has the most parallelograms over the candidates before it, then
  // the most known corners, then comes first among the candidates given.
  // Vertices that are not candidates are never known. O(F log F) over the
  // candidates' faces, whatever the degrees.
  std::vector<uint32_t> of(std::span<const uint32_t> candidates);

 private:
  const MeshPredictor& predictor_;
  std::vector<uint32_t> local_;  // per vertex: its index among the candidates, kNotCandidate between calls
  // One call's working arrays, kept for the next (see of()).
  std::vector<uint32_t> owner_, corners_, first_use_, uses_, fill_, grown_;
  std::vector<uint8_t> unknown_, state_;
  std::vector<uint64_t> support_;
};

}  // namespace m4mesh
