// The constrained Delaunay triangulation of §6.2: all nodes, the boundary
// polygon (nodes 0 … B−1, counterclockwise) as constraints, triangles
// outside the polygon removed. Exact integer predicates; cocircular nodes
// are resolved by symbolic perturbation by node index, so the result is
// unique and independent of the insertion order.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "common/error.h"
#include "mesh/geometry.h"
#include "mesh/topology.h"

namespace m4mesh {

struct CdtOptions {
  // Node insertion order: biased randomized insertion (BRIO) rounds, each
  // sorted along a Hilbert curve, shuffled with this seed. The triangles
  // never depend on it.
  uint64_t insertion_seed = 0x6d346d657368;  // "m4mesh"
  bool shuffle = true;
};

// A §6.1 violation and the node it is placed at (docs/decisions.md, 3):
// the later node of a pair, kNoNode for the boundary as a whole.
struct GeometryViolation {
  std::string message;
  NodeIndex node = kNoNode;
};

// A kGeometry error that remembers its node.
class GeometryError : public Error {
 public:
  explicit GeometryError(const GeometryViolation& v);
  NodeIndex node() const { return node_; }

 private:
  NodeIndex node_;
};

// Checks §6.1 (throws GeometryError): coordinates 0 … 1023, node 0 the
// top-left node, no duplicates, a simple counterclockwise boundary.
// Interior nodes strictly inside are checked by constrained_delaunay().
void validate_delaunay_nodes(std::span<const Point> nodes, uint32_t boundary_count);
// Every such violation, up to max_reports of them (empty when valid).
std::vector<GeometryViolation> delaunay_node_violations(std::span<const Point> nodes, uint32_t boundary_count, size_t max_reports);

// Validates, then triangulates (GeometryError when a node lies on a
// boundary edge or outside the boundary). Triangles are clockwise (orient > 0).
MeshTopology constrained_delaunay(std::span<const Point> nodes, uint32_t boundary_count,
                                           const CdtOptions& options = {});

// Whether the edge (a, c) shared by clockwise triangles (a, b, c) and (a, c, d)
// is replaced by (b, d): d strictly inside the circle through a, b, c, or on
// it with the smallest of the four indices at b or d (§6.2).
bool delaunay_flip(const Point& pa, const Point& pb, const Point& pc, const Point& pd, NodeIndex a, NodeIndex b,
                   NodeIndex c, NodeIndex d);

}  // namespace m4mesh
