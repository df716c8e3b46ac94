#include "mesh3d/mesh_predictor.h"

namespace m4mesh {

MeshPredictor::MeshPredictor(std::span<const Triangle> faces, uint32_t vertex_count) : faces_(faces), first_(vertex_count + 1, 0) {
  for (const Triangle& t : faces)
    for (NodeIndex v : t.v) ++first_[v + 1];
  for (uint32_t v = 0; v < vertex_count; ++v) first_[v + 1] += first_[v];
  around_.resize(first_.back());
  std::vector<uint32_t> fill(first_.begin(), first_.end() - 1);
  edges_.reserve(3 * faces.size());
  for (uint32_t f = 0; f < faces.size(); ++f)
    for (int i = 0; i < 3; ++i) {
      const NodeIndex from = faces[f].v[i], to = faces[f].v[(i + 1) % 3];
      around_[fill[from]++] = f;
      if (edges_.find(from, to) == DirectedEdgeIndex::kNone) edges_.insert(from, to, f);
    }
}

}  // namespace m4mesh
