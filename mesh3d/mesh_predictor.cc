#include "mesh3d/mesh_predictor.h"

namespace m4mesh {

MeshPredictor::MeshPredictor(std::span<const Triangle> faces, uint32_t vertex_count) : first_(vertex_count + 1, 0) {
  for (const Triangle& t : faces)
    for (NodeIndex v : t.v) ++first_[v + 1];
  for (uint32_t v = 0; v < vertex_count; ++v) first_[v + 1] += first_[v];
  // Each vertex's listings; until the parallelograms are known, z holds the face corner 3 f + c of v's first corner.
  corners_.resize(first_.back());
  {
    std::vector<uint32_t> fill(first_.begin(), first_.end() - 1);
    for (uint32_t f = 0; f < faces.size(); ++f)
      for (NodeIndex v : faces[f].v) {
        const int c = faces[f].corner_of(v);
        corners_[fill[v]++] = {faces[f].v[(c + 1) % 3], faces[f].v[(c + 2) % 3], 3 * f + c};
      }
  }
  // Vertex by vertex: the first face of each directed edge from it, then the
  // z of each face corner whose y it is; each face is visited at its corners
  // only. A face that holds `from` once is read from its listing alone.
  std::vector<uint32_t> opposite(3 * faces.size(), kNoNode);  // per face corner
  std::vector<uint32_t> seen_from(vertex_count, kNoNode), third_of(vertex_count);
  for (uint32_t from = 0; from < vertex_count; ++from) {
    for (uint32_t i = first_[from]; i < first_[from + 1]; ++i) {
      const Corner& listing = corners_[i];
      if (listing.x != from && listing.y != from) {
        if (seen_from[listing.x] != from) seen_from[listing.x] = from, third_of[listing.x] = listing.y;
        continue;
      }
      const Triangle& t = faces[listing.z / 3];
      for (int k = 0; k < 3; ++k) {
        const NodeIndex to = t.v[(k + 1) % 3];
        if (t.v[k] == from && seen_from[to] != from) {
          seen_from[to] = from;
          third_of[to] = t.third(from, to);
        }
      }
    }
    for (uint32_t i = first_[from]; i < first_[from + 1]; ++i) {
      const Corner& listing = corners_[i];
      const uint32_t f = listing.z / 3;
      if (listing.x != from && listing.y != from) {
        // The corner after from's is listing.x's, whose x is listing.y.
        opposite[3 * f + (listing.z % 3 + 1) % 3] = seen_from[listing.y] == from ? third_of[listing.y] : kNoNode;
        continue;
      }
      const Triangle& t = faces[f];
      for (int c = 0; c < 3; ++c) {
        const NodeIndex x = t.v[(c + 1) % 3];  // corner c is v, c + 2 is y = from
        if (t.v[(c + 2) % 3] == from) opposite[3 * f + c] = seen_from[x] == from ? third_of[x] : kNoNode;
      }
    }
  }
  for (Corner& listing : corners_) listing.z = opposite[listing.z];
}

}  // namespace m4mesh
