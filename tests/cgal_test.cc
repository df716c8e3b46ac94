// Cross-check against CGAL's constrained Delaunay triangulation on random
// inputs in general position (no four nodes of a Delaunay quad on one
// circle, where the §6.2 rule and CGAL's own may differ).
#include <gtest/gtest.h>

#include <cstdio>
#include <map>

#include "mesh/cdt.h"
#include "tests/cgal_reference.h"
#include "tests/test_util.h"

namespace m4mesh {
namespace {

// Whether some interior edge's quad is cocircular.
bool has_cocircular_quad(const std::vector<Point>& nodes, const std::vector<Triangle>& triangles) {
  std::map<std::pair<NodeIndex, NodeIndex>, NodeIndex> third;
  for (const Triangle& t : triangles)
    for (int j = 0; j < 3; ++j) third[{t.v[j], t.v[(j + 1) % 3]}] = t.v[(j + 2) % 3];
  for (const auto& [edge, b] : third) {
    const auto other = third.find({edge.second, edge.first});
    if (other != third.end() && incircle(nodes[edge.second], nodes[b], nodes[edge.first], nodes[other->second]) == 0)
      return true;
  }
  return false;
}

TEST(Cgal, IdenticalTrianglesOnRandomInputs) {
  int compared = 0;
  for (uint64_t seed = 1; seed <= 100; ++seed) {
    const uint32_t boundary = 3 + static_cast<uint32_t>(seed * 13 % 200);
    const std::vector<Point> nodes =
        test::random_polygon_with_interior(seed, boundary, static_cast<uint32_t>(seed * 97 % 1500));
    const std::vector<Triangle> ours = canonical_triangles(constrained_delaunay(nodes, boundary).triangles, nodes);
    if (has_cocircular_quad(nodes, ours)) continue;
    EXPECT_EQ(ours, canonical_triangles(reference::cgal_cdt(nodes, boundary), nodes)) << "seed " << seed;
    ++compared;
  }
  std::printf("compared %d inputs in general position\n", compared);
  EXPECT_GE(compared, 50);
}

}  // namespace
}  // namespace m4mesh
