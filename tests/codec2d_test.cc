// Encoder and decoder together: split codes, motion ranges, wrapping,
// zero runs, Method I, Delaunay meshes, byte identity and determinism.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <tuple>

#include "conformance/suite.h"
#include "decoder/mesh_object_decoder.h"
#include "encoder/mesh_object_encoder.h"
#include "mesh/decoded_text.h"
#include "syntax/mesh_object.h"
#include "tests/test_util.h"

namespace m4mesh {
namespace {

// Decodes and checks every plane's positions against the input.
void expect_decodes_to(const std::vector<uint8_t>& stream, const std::vector<MeshPlane>& planes,
                       MotionMethod method = MotionMethod::kMethod2) {
  DecoderOptions options;
  options.method = method;
  Decoder decoder(stream, options);
  size_t k = 0;
  while (decoder.next()) {
    ASSERT_LT(k, planes.size());
    ASSERT_TRUE(std::equal(decoder.nodes().begin(), decoder.nodes().end(), planes[k].nodes.begin(), planes[k].nodes.end()))
        << "plane " << k;
    ++k;
  }
  EXPECT_EQ(k, planes.size());
}

std::vector<MeshPlane> random_motion(MeshPlane intra, int frames, int lo, int hi, uint64_t seed) {
  std::vector<MeshPlane> planes{intra};
  test::Random random(seed);
  for (int k = 1; k < frames; ++k) {
    std::vector<Point> next = planes.back().nodes;
    for (Point& p : next) {
      p.x += random.uniform(lo, hi);
      p.y += random.uniform(lo, hi);
    }
    planes.push_back(inter_plane(next));
  }
  return planes;
}

TEST(Uniform, SplitCodesFollowSection5) {
  // Rectangle (c, r): '10' splits TL–BR when c + r is even.
  for (uint32_t c = 0; c < 4; ++c) {
    for (uint32_t r = 0; r < 4; ++r) {
      EXPECT_TRUE(uniform_split_tl_br(0, c, r));
      EXPECT_FALSE(uniform_split_tl_br(1, c, r));
      EXPECT_EQ(uniform_split_tl_br(2, c, r), (c + r) % 2 == 0);
      EXPECT_EQ(uniform_split_tl_br(3, c, r), (c + r) % 2 == 1);
    }
  }
  // 2×2 nodes: one rectangle.
  const std::vector<Point> nodes = uniform_nodes({2, 2, 10, 10, 0});
  EXPECT_EQ(canonical_triangles(uniform_triangles({2, 2, 10, 10, 0}), nodes),
            (std::vector<Triangle>{{{0, 1, 3}}, {{0, 3, 2}}}));
  EXPECT_EQ(canonical_triangles(uniform_triangles({2, 2, 10, 10, 1}), nodes),
            (std::vector<Triangle>{{{0, 1, 2}}, {{1, 3, 2}}}));
}

TEST(Uniform, EverySplitCodeRoundTrips) {
  for (uint32_t split = 0; split < 4; ++split) {
    const auto planes = random_motion(uniform_plane(7, 5, 20, 16, split), 6, -20, 20, split);
    const std::vector<uint8_t> stream = encode(planes).stream;
    expect_decodes_to(stream, planes);
    Decoder decoder(stream);
    ASSERT_TRUE(decoder.next());
    EXPECT_EQ(decoder.info().uniform.split, split);
    EXPECT_EQ(decoder.triangles().size(), 2u * 6 * 4);
  }
}

TEST(Uniform, ExtremeShapes) {
  for (auto [cols, rows] : {std::pair{2u, 2u}, {1023u, 2u}, {2u, 1023u}}) {
    const auto planes = random_motion(uniform_plane(cols, rows, 1, 255, 2), 3, -3, 3, cols);
    expect_decodes_to(encode(planes).stream, planes);
  }
}

// Every motion_range_code, with vectors at low and at high.
TEST(Motion, EveryRangeAtItsLimits) {
  for (uint32_t code = 1; code <= 3; ++code) {
    const std::vector<MeshPlane> planes = range_limit_planes(code);
    const std::vector<uint8_t> stream = encode(planes).stream;
    expect_decodes_to(stream, planes);
    MeshObject object = syntax::read_mesh_object(stream);
    EXPECT_EQ(object.planes[1].motion.motion_range_code, code);
  }
}

// Neighbouring vectors at opposite ends of the range make the difference
// leave [low, high] both ways.
TEST(Motion, WrappingInBothDirections) {
  for (uint32_t code = 1; code <= 3; ++code) {
    const std::vector<MeshPlane> planes = wrap_planes(code);
    expect_decodes_to(encode(planes).stream, planes);
  }
}

TEST(Motion, ExplicitRangeIsKeptAndTooSmallIsRefused) {
  std::vector<MeshPlane> planes{uniform_plane(3, 3, 16, 16, 0)};
  std::vector<Point> nodes = planes[0].nodes;
  nodes[4].x += 5;
  planes.push_back(inter_plane(nodes, 3));
  MeshObject object = syntax::read_mesh_object(encode(planes).stream);
  EXPECT_EQ(object.planes[1].motion.motion_range_code, 3u);
  nodes[4].x += 60;
  planes[1] = inter_plane(nodes, 1);
  EXPECT_THROW(encode(planes), Error);
  planes[1] = inter_plane(nodes, 0);
  nodes[4].x += 200;  // beyond [−128, 127]: a uniform mesh cannot code it
  planes[1] = inter_plane(nodes, 0);
  EXPECT_THROW(encode(planes), Error);
}

TEST(Motion, LongZeroMotionRuns) {
  std::vector<MeshPlane> planes{uniform_plane(40, 40, 8, 8, 0)};
  for (int k = 0; k < 5; ++k) planes.push_back(inter_plane(planes[0].nodes));
  std::vector<Point> moved = planes[0].nodes;
  moved[1599].y -= 1;
  planes.push_back(inter_plane(moved));
  const std::vector<uint8_t> stream = encode(planes).stream;
  expect_decodes_to(stream, planes);
  // A still plane is range '01' and 1600 '0' flags: 2 + 1 + 1600 bits then stuffing.
  MeshObject object = syntax::read_mesh_object(stream);
  for (int k = 1; k <= 5; ++k)
    for (const NodeMotion& n : object.planes[k].motion.nodes) ASSERT_EQ(n.node_motion_vector_flag, 0);
  EXPECT_EQ(stream.size(), 4 + (4 + 6) + 5 * (4 + 201) + (4 + 201) + 4);
}

TEST(Motion, MethodOneRoundTripsOnlyWithMethodOne) {
  const auto planes = random_motion(uniform_plane(9, 7, 16, 16, 2), 5, -10, 10, 3);
  EncoderOptions options;
  options.method = MotionMethod::kMethod1;
  const std::vector<uint8_t> stream = encode(planes, options).stream;
  expect_decodes_to(stream, planes, MotionMethod::kMethod1);
  EXPECT_NE(stream, encode(planes).stream);
  EXPECT_EQ(boustrophedon(3, 3), (std::vector<NodeIndex>{0, 1, 2, 5, 4, 3, 6, 7, 8}));
}

std::vector<Point> square_with_interior(int interior, uint64_t seed) {
  std::vector<Point> nodes{{100, 100}, {100, 900}, {900, 900}, {900, 100}};
  test::Random random(seed);
  std::set<std::pair<int, int>> used;
  while (static_cast<int>(nodes.size()) < 4 + interior) {
    const Point p{random.uniform(101, 899), random.uniform(101, 899)};
    if (used.insert({p.x, p.y}).second) nodes.push_back(p);
  }
  return nodes;
}

// §10: after the boundary, each node is the remaining one nearest (L1, then
// smaller y, then smaller x) to the previous; coordinates may be negative.
TEST(Delaunay, NodeOrderMatchesTheDefinitionWithNegativeCoordinates) {
  test::Random random(12);
  std::vector<Point> nodes{{-500, -400}, {-500, 300}, {600, 300}, {600, -400}};
  std::set<std::pair<int, int>> used;
  for (const Point& p : nodes) used.insert({p.x, p.y});
  while (nodes.size() < 400) {
    const Point p{random.uniform(-499, 599), random.uniform(-399, 299)};
    if (used.insert({p.x, p.y}).second) nodes.push_back(p);
  }
  const std::vector<NodeIndex> order = delaunay_node_order(nodes, 4);
  std::vector<NodeIndex> expected(order.begin(), order.begin() + 4);
  std::set<NodeIndex> remaining;
  for (NodeIndex i = 4; i < nodes.size(); ++i) remaining.insert(i);
  while (!remaining.empty()) {
    const Point& from = nodes[expected.back()];
    auto key = [&](NodeIndex i) {
      return std::tuple(std::abs(nodes[i].x - from.x) + std::abs(nodes[i].y - from.y), nodes[i].y, nodes[i].x);
    };
    const NodeIndex best = *std::min_element(remaining.begin(), remaining.end(), [&](NodeIndex a, NodeIndex b) { return key(a) < key(b); });
    expected.push_back(best);
    remaining.erase(best);
  }
  EXPECT_EQ(order, expected);
}

TEST(Delaunay, RandomMotionRoundTrips) {
  const auto planes = random_motion(delaunay_plane(square_with_interior(300, 5), 4), 5, -60, 60, 9);
  const EncodeResult result = encode(planes);
  // The encoder reorders nodes (§10): compare through the decoded text instead.
  const std::string text = test::decoded_text(result.stream);
  const std::vector<MeshPlane> decoded = parse_decoded_text(text, "decoded");
  ASSERT_EQ(decoded.size(), planes.size());
  std::multiset<std::pair<int, int>> in, out;
  for (const Point& p : planes.back().nodes) in.insert({p.x, p.y});
  for (const Point& p : decoded.back().nodes) out.insert({p.x, p.y});
  EXPECT_EQ(in, out);
}

TEST(Delaunay, LargeMotionBecomesANewIntraPlane) {
  std::vector<MeshPlane> planes{delaunay_plane(square_with_interior(20, 1), 4)};
  std::vector<Point> moved = planes[0].nodes;
  for (Point& p : moved) p.x -= 90;  // fits range 3
  planes.push_back(inter_plane(moved));
  for (Point& p : moved) p.x += 150;  // does not fit [−128, 127]
  planes.push_back(inter_plane(moved));
  std::vector<std::string> reports;
  EncoderOptions options;
  options.report = [&](const std::string& message) { reports.push_back(message); };
  const EncodeResult result = encode(planes, options);
  EXPECT_EQ(result.intra_planes, 2);
  EXPECT_EQ(result.inter_planes, 1);
  EXPECT_EQ(reports.size(), 1u);
}

// decode → §9 text → encode reproduces the stream byte for byte.
TEST(Identity, DecodeThenEncodeReproducesTheStream) {
  std::vector<std::vector<MeshPlane>> inputs{
      random_motion(uniform_plane(11, 9, 12, 14, 3), 8, -70, 70, 1),
      random_motion(delaunay_plane(square_with_interior(500, 2), 4), 6, -5, 5, 2)};
  inputs.push_back(inputs[0]);
  inputs.back().push_back(uniform_plane(3, 3, 5, 5, 1));  // a repeated I-plane
  for (const auto& planes : inputs) {
    const std::vector<uint8_t> stream = encode(planes).stream;
    const std::vector<MeshPlane> decoded = parse_decoded_text(test::decoded_text(stream), "decoded");
    EXPECT_EQ(encode(decoded).stream, stream);
  }
}

TEST(Identity, EncoderIsDeterministic) {
  const auto planes = random_motion(delaunay_plane(square_with_interior(400, 4), 4), 4, -30, 30, 8);
  const std::vector<uint8_t> first = encode(planes).stream;
  for (int i = 0; i < 3; ++i) EXPECT_EQ(encode(planes).stream, first);
}

}  // namespace
}  // namespace m4mesh
