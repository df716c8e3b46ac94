// The constrained Delaunay triangulation of §6.2.
#include <gtest/gtest.h>

#include <map>
#include <set>

#include "common/error.h"
#include "conformance/suite.h"
#include "mesh/cdt.h"
#include "tests/test_util.h"

namespace m4mesh {
namespace {

std::vector<Triangle> cdt(const std::vector<Point>& nodes, uint32_t boundary, CdtOptions options = {}) {
  return canonical_triangles(constrained_delaunay(nodes, boundary, options).triangles, nodes);
}

// The properties that make the triangulation the unique CDT: exact cover of
// the polygon, Euler's formula, and every non-boundary edge locally
// Delaunay under the perturbed predicate.
void expect_valid_cdt(const std::vector<Point>& nodes, uint32_t boundary, const std::vector<Triangle>& triangles) {
  const int64_t n = static_cast<int64_t>(nodes.size());
  ASSERT_EQ(static_cast<int64_t>(triangles.size()), 2 * n - boundary - 2);
  int64_t polygon_area = 0;
  for (uint32_t i = 0; i < boundary; ++i) {
    const Point &p = nodes[i], &q = nodes[(i + 1) % boundary];
    polygon_area += int64_t{p.x} * q.y - int64_t{q.x} * p.y;
  }
  int64_t triangle_area = 0;
  std::map<std::pair<NodeIndex, NodeIndex>, NodeIndex> opposite;  // directed edge → third node
  for (const Triangle& t : triangles) {
    const int64_t area = orient(nodes[t.v[0]], nodes[t.v[1]], nodes[t.v[2]]);
    ASSERT_GT(area, 0) << "degenerate or counterclockwise triangle";
    triangle_area += area;
    for (int j = 0; j < 3; ++j) ASSERT_TRUE(opposite.emplace(std::pair{t.v[j], t.v[(j + 1) % 3]}, t.v[(j + 2) % 3]).second);
  }
  EXPECT_EQ(triangle_area, -polygon_area);
  std::set<std::pair<NodeIndex, NodeIndex>> boundary_edges;
  for (uint32_t i = 0; i < boundary; ++i) boundary_edges.insert({(i + 1) % boundary, i});
  size_t edges = 0;
  for (const auto& [edge, b] : opposite) {
    const auto reverse = opposite.find({edge.second, edge.first});
    if (reverse == opposite.end()) {
      EXPECT_TRUE(boundary_edges.count(edge)) << "open edge " << edge.first << "-" << edge.second;
      ++edges;
      continue;
    }
    if (edge.first > edge.second) continue;
    ++edges;
    // Triangles (a, b, c) and (a, c, d) around the edge (a, c) = (edge.second, edge.first).
    const NodeIndex a = edge.second, c = edge.first, d = reverse->second;
    EXPECT_FALSE(delaunay_flip(nodes[a], nodes[b], nodes[c], nodes[d], a, b, c, d))
        << "edge " << a << "-" << c << " is not locally Delaunay";
  }
  EXPECT_EQ(static_cast<int64_t>(edges), 3 * n - boundary - 3);
}

TEST(DelaunayFlip, CocircularQuadKeepsTheDiagonalAtTheSmallestIndex) {
  const Point a{0, 0}, b{10, 0}, c{10, 10}, d{0, 10};  // clockwise as displayed, one circle
  EXPECT_FALSE(delaunay_flip(a, b, c, d, 0, 1, 2, 3));  // 0 is on (a, c)
  EXPECT_TRUE(delaunay_flip(a, b, c, d, 1, 0, 2, 3));   // 0 is at b: flip to (b, d)
  EXPECT_TRUE(delaunay_flip(a, b, c, d, 2, 3, 1, 0));   // 0 is at d
  EXPECT_FALSE(delaunay_flip(a, b, c, d, 3, 2, 0, 1));  // 0 is at c
  EXPECT_TRUE(delaunay_flip(a, b, c, Point{5, 11}, 0, 1, 2, 3));   // strictly inside
  EXPECT_FALSE(delaunay_flip(a, b, c, Point{-1, 12}, 9, 1, 8, 0));  // strictly outside
}

TEST(Cdt, ThreeNodes) {
  const std::vector<Point> nodes{{0, 0}, {0, 10}, {10, 0}};
  EXPECT_EQ(cdt(nodes, 3), (std::vector<Triangle>{{{0, 2, 1}}}));
}

TEST(Cdt, SquareWithCentre) {
  const std::vector<Point> nodes{{0, 0}, {0, 10}, {10, 10}, {10, 0}, {5, 5}};
  EXPECT_EQ(cdt(nodes, 4), (std::vector<Triangle>{{{0, 3, 4}}, {{0, 4, 1}}, {{1, 4, 2}}, {{2, 4, 3}}}));
}

// A square: the diagonal through node 0, the smallest index (§6.2).
TEST(Cdt, SquareUsesTheFanRule) {
  const std::vector<Point> nodes{{0, 0}, {0, 10}, {10, 10}, {10, 0}};
  EXPECT_EQ(cdt(nodes, 4), (std::vector<Triangle>{{{0, 2, 1}}, {{0, 3, 2}}}));
}

// Twelve nodes on one circle: a fan from node 0.
TEST(Cdt, PointsOnOneCircleFormAFanFromTheSmallestIndex) {
  const std::vector<Point> ring{{495, 500}, {496, 503}, {497, 504}, {500, 505}, {503, 504}, {504, 503},
                                {505, 500}, {504, 497}, {503, 496}, {500, 495}, {497, 496}, {496, 497}};
  // Rotate so the top-left node comes first, keeping the counterclockwise order.
  std::vector<Point> nodes = ring;
  std::rotate(nodes.begin(), std::min_element(nodes.begin(), nodes.end(), more_top_left), nodes.end());
  const std::vector<Triangle> triangles = cdt(nodes, 12);
  ASSERT_EQ(triangles.size(), 10u);
  for (const Triangle& t : triangles) EXPECT_EQ(t.v[0], 0u);
  expect_valid_cdt(nodes, 12, triangles);
}

// A grid coded as a Delaunay mesh: every cell is cocircular, and its
// diagonal goes through the smallest of its four indices.
TEST(Cdt, RegularGridFollowsTheFanRuleInEveryCell) {
  const int n = 9;
  std::vector<Point> nodes;
  // Boundary counterclockwise from (0, 0): down the left, along the bottom, up the right, back along the top.
  for (int i = 0; i < n - 1; ++i) nodes.push_back({0, i * 10});
  for (int i = 0; i < n - 1; ++i) nodes.push_back({i * 10, (n - 1) * 10});
  for (int i = n - 1; i > 0; --i) nodes.push_back({(n - 1) * 10, i * 10});
  for (int i = n - 1; i > 0; --i) nodes.push_back({i * 10, 0});
  const uint32_t boundary = static_cast<uint32_t>(nodes.size());
  test::Random random(4);
  std::vector<Point> interior;
  for (int y = 1; y < n - 1; ++y)
    for (int x = 1; x < n - 1; ++x) interior.push_back({x * 10, y * 10});
  for (size_t i = interior.size(); i > 1; --i) std::swap(interior[i - 1], interior[random.next() % i]);
  nodes.insert(nodes.end(), interior.begin(), interior.end());
  const std::vector<Triangle> triangles = cdt(nodes, boundary);
  expect_valid_cdt(nodes, boundary, triangles);

  std::map<std::pair<int, int>, NodeIndex> at;
  for (NodeIndex i = 0; i < nodes.size(); ++i) at[{nodes[i].x, nodes[i].y}] = i;
  std::set<std::pair<NodeIndex, NodeIndex>> edges;
  for (const Triangle& t : triangles)
    for (int j = 0; j < 3; ++j) edges.insert(std::minmax(t.v[j], t.v[(j + 1) % 3]));
  for (int y = 0; y + 1 < n; ++y) {
    for (int x = 0; x + 1 < n; ++x) {
      const NodeIndex tl = at[{x * 10, y * 10}], tr = at[{x * 10 + 10, y * 10}], bl = at[{x * 10, y * 10 + 10}],
                      br = at[{x * 10 + 10, y * 10 + 10}];
      const NodeIndex smallest = std::min({tl, tr, bl, br});
      const bool main_diagonal = edges.count(std::minmax(tl, br)) > 0;
      EXPECT_NE(main_diagonal, edges.count(std::minmax(tr, bl)) > 0);
      EXPECT_EQ(main_diagonal, smallest == tl || smallest == br) << "cell " << x << "," << y;
    }
  }
}

TEST(Cdt, CollinearBoundaryRunsWithInteriorNodes) {
  std::vector<Point> nodes;
  for (int i = 0; i < 50; ++i) nodes.push_back({0, i * 20});
  for (int i = 0; i < 50; ++i) nodes.push_back({i * 20, 1000});
  for (int i = 50; i > 0; --i) nodes.push_back({1000, i * 20});
  for (int i = 50; i > 0; --i) nodes.push_back({i * 20, 0});
  const uint32_t boundary = static_cast<uint32_t>(nodes.size());
  test::Random random(5);
  std::set<std::pair<int, int>> used;
  while (nodes.size() < boundary + 400) {
    const Point p{random.uniform(1, 999), random.uniform(1, 999)};
    if (used.insert({p.x, p.y}).second) nodes.push_back(p);
  }
  expect_valid_cdt(nodes, boundary, cdt(nodes, boundary));
}

TEST(Cdt, NonConvexAndSpiralBoundaries) {
  const std::vector<Point> comb = comb_boundary();
  expect_valid_cdt(comb, static_cast<uint32_t>(comb.size()), cdt(comb, static_cast<uint32_t>(comb.size())));

  const std::vector<Point> spiral = spiral_boundary();
  const uint32_t b = static_cast<uint32_t>(spiral.size());
  validate_delaunay_nodes(spiral, b);
  expect_valid_cdt(spiral, b, cdt(spiral, b));
}

TEST(Cdt, RandomPolygonsHaveEveryProperty) {
  for (uint64_t seed = 1; seed <= 30; ++seed) {
    const uint32_t boundary = 3 + static_cast<uint32_t>(seed * 7 % 60);
    const std::vector<Point> nodes = test::random_polygon_with_interior(seed, boundary, static_cast<uint32_t>(seed * 37));
    expect_valid_cdt(nodes, boundary, cdt(nodes, boundary));
  }
}

TEST(Cdt, InsertionOrderDoesNotMatter) {
  const std::vector<Point> nodes = test::random_polygon_with_interior(99, 40, 3000);
  const std::vector<Triangle> reference = cdt(nodes, 40);
  for (uint64_t seed : {1u, 2u, 3u}) {
    CdtOptions options;
    options.insertion_seed = seed;
    EXPECT_EQ(cdt(nodes, 40, options), reference);
  }
  CdtOptions in_stream_order;
  in_stream_order.shuffle = false;
  EXPECT_EQ(cdt(nodes, 40, in_stream_order), reference);
  // Cocircular-heavy input: a small lattice inside.
  std::vector<Point> lattice{{0, 0}, {0, 300}, {300, 300}, {300, 0}};
  for (int y = 1; y < 30; ++y)
    for (int x = 1; x < 30; ++x) lattice.push_back({x * 10, y * 10});
  const std::vector<Triangle> lattice_reference = cdt(lattice, 4);
  for (uint64_t seed : {5u, 6u, 7u, 8u}) {
    CdtOptions options;
    options.insertion_seed = seed;
    EXPECT_EQ(cdt(lattice, 4, options), lattice_reference);
  }
  EXPECT_EQ(cdt(lattice, 4, in_stream_order), lattice_reference);
}

TEST(Cdt, MaximumSizes) {
  // 65,535 nodes with 1,023 boundary nodes.
  const std::vector<Point> nodes = test::random_polygon_with_interior(7, 1023, 65535 - 1023, 400, 511);
  ASSERT_EQ(nodes.size(), 65535u);
  expect_valid_cdt(nodes, 1023, cdt(nodes, 1023));
}

TEST(Cdt, CoordinatesAtBothEnds) {
  std::vector<Point> nodes{{0, 0}, {0, 1023}, {1023, 1023}, {1023, 0}, {1, 1}, {1022, 1022}, {1, 1022}};
  expect_valid_cdt(nodes, 4, cdt(nodes, 4));
}

void expect_geometry_error(const std::vector<Point>& nodes, uint32_t boundary, const std::string& fragment, NodeIndex node = kNoNode) {
  try {
    constrained_delaunay(nodes, boundary);
    ADD_FAILURE() << "accepted, expected: " << fragment;
  } catch (const GeometryError& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kGeometry);
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    EXPECT_EQ(e.node(), node) << e.what();
  }
}

TEST(Cdt, InvalidGeometryIsReportedWithTheNode) {
  expect_geometry_error({{0, 0}, {10, 0}, {0, 10}}, 3, "clockwise");
  expect_geometry_error({{0, 0}, {0, 10}, {0, 20}}, 3, "zero area");
  expect_geometry_error({{0, 0}, {0, 10}, {10, 10}, {10, 0}, {20, 5}}, 4, "interior node 4 lies outside", 4);
  expect_geometry_error({{0, 0}, {0, 10}, {10, 10}, {10, 0}, {10, 5}}, 4, "interior node 4 is not strictly inside", 4);
  expect_geometry_error({{0, 0}, {0, 10}, {10, 10}, {10, 0}, {5, 5}, {5, 5}}, 4, "nodes 4 and 5 coincide", 5);
  expect_geometry_error({{5, 5}, {0, 10}, {10, 10}, {10, 0}}, 4, "node 0 is not the top-left node (node 3 is)", 3);
  expect_geometry_error({{0, 0}, {0, 20}, {10, 0}, {12, 14}}, 4, "touch");  // crossed edges
  expect_geometry_error({{0, 0}, {0, 10}, {10, 10}, {10, 1024}}, 4, "node 3 lies outside 0…1023", 3);
  expect_geometry_error({{0, 0}, {0, 20}, {0, 10}, {10, 5}}, 4, "folds back", 1);
  expect_geometry_error({{0, 0}, {0, 10}, {5, 5}, {10, 10}, {10, 0}, {5, 5}}, 5, "coincide", 5);
}

}  // namespace
}  // namespace m4mesh
