// The parallelogram prediction over a mesh (docs/base_mesh.md,
// "Positions"), shared by the base mesh's positions and the codecs that
// predict other values on the vertices (cpca-wpt's bases).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "mesh/topology.h"
#include "syntax/mesh3d/base_mesh.h"

namespace m4mesh {

// Floor division, for predictions of either sign.
inline int64_t floor_div(int64_t sum, int64_t n) {
  const int64_t q = sum / n;
  return (sum % n != 0 && sum < 0) ? q - 1 : q;
}

// The parallelogram prediction of docs/base_mesh.md ("Positions") for any
// values that live on the vertices (positions, a component's basis) and
// any set of vertices already known; the faces in any numbering, in their
// decoded order (which sets each directed edge's first face).
class MeshPredictor {
 public:
  MeshPredictor(std::span<const Triangle> faces, uint32_t vertex_count);

  // The prediction p of vertex v from the known vertices' values (D per
  // vertex; never v's own): the mean (floor) of the parallelograms x + y − z of the
  // faces (v, x, y) whose x, y and opposite z (the third vertex of the
  // first face with the directed edge y → x) are known, channel
  // kParallelogramChannel; else the mean of the known corners of the faces
  // around v, each counted once per face, channel kNeighbourChannel; −1
  // (p untouched) when no corner is known.
  template <size_t D, class Known, class Value>
  int predict(uint32_t v, Known known, Value value, std::array<int64_t, D>& p) const {
    std::array<int64_t, D> sum{};
    int64_t n = 0;
    for_each_parallelogram(v, known, [&](uint32_t x, uint32_t y, uint32_t z) {
      if (!known(z)) return;
      const auto& vx = value(x);
      const auto& vy = value(y);
      const auto& vz = value(z);
      for (size_t a = 0; a < D; ++a) sum[a] += int64_t{vx[a]} + vy[a] - vz[a];
      ++n;
    });
    if (n > 0) {
      for (size_t a = 0; a < D; ++a) p[a] = floor_div(sum[a], n);
      return syntax::kParallelogramChannel;
    }
    return neighbour_mean(v, known, value, p) ? syntax::kNeighbourChannel : -1;
  }

  // Calls visit(x, y, z) for every parallelogram x + y − z that may predict
  // v: each face (v, x, y) around v whose neighbour across x–y (the first
  // face with the directed edge y → x) has the third vertex z; only those
  // whose x and y pass the filter (which spares looking z up).
  template <class Filter, class Visit>
  void for_each_parallelogram(uint32_t v, Filter filter, Visit visit) const {
    for (uint32_t i = first_[v]; i < first_[v + 1]; ++i) {
      const Corner& c = corners_[i];
      if (filter(c.x) && filter(c.y) && c.z != kNoNode) visit(c.x, c.y, c.z);
    }
  }

  // Face corners: how many parallelograms there can be.
  size_t corners() const { return corners_.size(); }

  // The mean (floor) of the known corners of the faces around v, each
  // counted once per face; false (p untouched) when none is known.
  template <size_t D, class Known, class Value>
  bool neighbour_mean(uint32_t v, Known known, Value value, std::array<int64_t, D>& p) const {
    std::array<int64_t, D> sum{};
    int64_t n = 0;
    for_each_known_corner(v, known, [&](uint32_t u) {
      const auto& vu = value(u);
      for (size_t a = 0; a < D; ++a) sum[a] += vu[a];
      ++n;
    });
    if (n == 0) return false;
    for (size_t a = 0; a < D; ++a) p[a] = floor_div(sum[a], n);
    return true;
  }

  // Calls visit(u) for every known corner u ≠ v of every face around v,
  // once per face (a face listed once per corner of v).
  template <class Known, class Visit>
  void for_each_known_corner(uint32_t v, Known known, Visit visit) const {
    for (uint32_t i = first_[v]; i < first_[v + 1]; ++i) {
      const Corner& c = corners_[i];
      if (c.x != v && known(c.x)) visit(c.x);
      if (c.y != v && known(c.y)) visit(c.y);
    }
  }

 private:
  // A face around v seen from v's first corner in it: the corners x, y after
  // it and the parallelogram's z, the third vertex of the first face with
  // the directed edge y → x (kNoNode without one).
  struct Corner {
    uint32_t x, y, z;
  };
  // The faces around each vertex v, in face order, once per corner of v: corners_[first_[v]] … corners_[first_[v + 1] − 1].
  std::vector<uint32_t> first_;
  std::vector<Corner> corners_;
};

}  // namespace m4mesh
