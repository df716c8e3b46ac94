#include "mesh3d/mesh_predictor.h"

namespace m4mesh {

MeshPredictor::MeshPredictor(std::span<const Triangle> faces, uint32_t vertex_count) : first_(vertex_count + 1, 0) {
  for (const Triangle& t : faces)
    for (NodeIndex v : t.v) ++first_[v + 1];
  for (uint32_t v = 0; v < vertex_count; ++v) first_[v + 1] += first_[v];
  // Each vertex's listings, their z holding the face until the faces' z are known.
  corners_.resize(first_.back());
  {
    std::vector<uint32_t> fill(first_.begin(), first_.end() - 1);
    for (uint32_t f = 0; f < faces.size(); ++f)
      for (NodeIndex v : faces[f].v) {
        const int corner = faces[f].corner_of(v);
        corners_[fill[v]++] = {faces[f].v[(corner + 1) % 3], faces[f].v[(corner + 2) % 3], f};
      }
  }
  // Vertex by vertex: the first face of each directed edge from it, then the
  // z of each face corner whose y it is; each face is visited at its corners only.
  std::vector<uint32_t> opposite(3 * faces.size(), kNoNode);  // per face corner 3 f + c
  std::vector<uint32_t> seen_from(vertex_count, kNoNode), third_of(vertex_count);
  for (uint32_t from = 0; from < vertex_count; ++from) {
    for (uint32_t i = first_[from]; i < first_[from + 1]; ++i) {
      const Triangle& t = faces[corners_[i].z];
      for (int k = 0; k < 3; ++k) {
        const NodeIndex to = t.v[(k + 1) % 3];
        if (t.v[k] == from && seen_from[to] != from) {
          seen_from[to] = from;
          third_of[to] = t.third(from, to);
        }
      }
    }
    for (uint32_t i = first_[from]; i < first_[from + 1]; ++i) {
      const uint32_t f = corners_[i].z;
      const Triangle& t = faces[f];
      for (int c = 0; c < 3; ++c) {
        const NodeIndex x = t.v[(c + 1) % 3];  // corner c is v, c + 2 is y = from
        if (t.v[(c + 2) % 3] == from) opposite[3 * f + c] = seen_from[x] == from ? third_of[x] : kNoNode;
      }
    }
  }
  for (uint32_t v = 0; v < vertex_count; ++v)
    for (uint32_t i = first_[v]; i < first_[v + 1]; ++i) {
      const uint32_t f = corners_[i].z;
      corners_[i].z = opposite[3 * f + faces[f].corner_of(v)];
    }
}

}  // namespace m4mesh
