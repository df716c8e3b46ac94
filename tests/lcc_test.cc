// The shared process of the cloth codec (mesh3d/lcc.h): traversal, local
// cylindrical frames and the angle table.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <set>

#include "common/bit_cast.h"
#include "common/md5.h"
#include "mesh3d/lcc.h"
#include "tests/test_util.h"

namespace m4mesh {
namespace {

TEST(Lcc, EveryVertexOnceAfterWhatItRefersTo) {
  const MeshSequence s = test::test_sequence(1, 31);  // a closed sphere, an open sheet, an isolated vertex
  const LccOrder order = lcc_order(s.faces, s.vertex_count);
  std::set<NodeIndex> coded(order.direct.begin(), order.direct.end());
  EXPECT_EQ(coded.size(), order.direct.size());
  for (const LccStep& step : order.steps) {
    for (NodeIndex v : {step.a, step.b, step.c}) ASSERT_TRUE(coded.count(v)) << "vertex " << step.d << " refers to " << v << " before it";
    ASSERT_TRUE(coded.insert(step.d).second) << "vertex " << step.d << " twice";
  }
  EXPECT_EQ(coded.size(), s.vertex_count);
  EXPECT_EQ(order.direct.size(), 3u + 3u + 1u);  // two components' root triangles and the isolated vertex
  EXPECT_EQ(order.direct.back(), s.vertex_count - 1);
  EXPECT_EQ(lcc_order(s.faces, s.vertex_count).steps.size(), order.steps.size());
}

TEST(Lcc, CylindricalCoordinatesRoundTrip) {
  test::Random random(32);
  auto point = [&] { return Vec3{random.uniform(-1000, 1000) / 100.0, random.uniform(-1000, 1000) / 100.0, random.uniform(-1000, 1000) / 100.0}; };
  for (int i = 0; i < 1000; ++i) {
    const Vec3 a = point(), b = point(), c = point(), d = point();
    const LccFrame frame = lcc_frame(a, b, c);
    const Cylindrical p = to_cylindrical(frame, d);
    EXPECT_EQ(radius_and_height(frame, d).radius, p.radius);
    const Vec3 o{d.x - frame.origin.x, d.y - frame.origin.y, d.z - frame.origin.z};
    ASSERT_NEAR(p.theta, std::atan2(o.x * frame.y.x + o.y * frame.y.y + o.z * frame.y.z, o.x * frame.x.x + o.y * frame.x.y + o.z * frame.x.z),
                1e-9);
    const Vec3 back = from_cylindrical(frame, std::cos(p.theta), std::sin(p.theta), p.radius, p.height);
    ASSERT_NEAR(back.x, d.x, 3e-8);
    ASSERT_NEAR(back.y, d.y, 3e-8);
    ASSERT_NEAR(back.z, d.z, 3e-8);
  }
  // A flat continuation across the edge has θ = 0: the polar axis points away from a.
  const LccFrame flat = lcc_frame({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  EXPECT_NEAR(to_cylindrical(flat, {1, 1, 0}).theta, 0, 1e-15);
  EXPECT_NEAR(to_cylindrical(flat, {0, 0, 0}).theta, std::numbers::pi, 1e-15);
  // Every octant's boundary and the axes.
  const LccFrame axes{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (int k = -8; k <= 8; ++k) {
    const double angle = k * std::numbers::pi / 8;
    EXPECT_NEAR(to_cylindrical(axes, {std::cos(angle), std::sin(angle), 0}).theta, std::atan2(std::sin(angle), std::cos(angle)), 1e-9) << k;
  }
}

TEST(Lcc, DegenerateTrianglesGetAFiniteFrame) {
  for (const auto& [a, b, c] : {std::array<Vec3, 3>{Vec3{0, 0, 0}, Vec3{1, 1, 1}, Vec3{1, 1, 1}},   // a zero edge
                                std::array<Vec3, 3>{Vec3{0, 0, 0}, Vec3{1, 0, 0}, Vec3{2, 0, 0}},   // collinear
                                std::array<Vec3, 3>{Vec3{5, 5, 5}, Vec3{5, 5, 5}, Vec3{5, 5, 5}}}) {  // a point
    const LccFrame f = lcc_frame(a, b, c);
    for (const Vec3& axis : {f.x, f.y, f.z}) {
      ASSERT_TRUE(std::isfinite(axis.x) && std::isfinite(axis.y) && std::isfinite(axis.z));
      EXPECT_NEAR(axis.x * axis.x + axis.y * axis.y + axis.z * axis.z, 1, 1e-12);
    }
    EXPECT_NEAR(f.x.x * f.z.x + f.x.y * f.z.y + f.x.z * f.z.z, 0, 1e-12);
  }
}

// The decoder places a chunk's steps two at a time: the same bits as
// place() one step after the other, degenerate triangles included (the
// closed sphere's root triangle made collinear, the open sheet's a point).
TEST(Lcc, ChunksPlaceWhatStepsPlaceOneByOne) {
  MeshSequence s = test::test_sequence(1, 31);
  // A 40 × 40 sheet after it, for more than one chunk.
  const uint32_t n = 40, first = s.vertex_count;
  for (uint32_t i = 0; i < n; ++i)
    for (uint32_t j = 0; j < n; ++j) s.frames[0].push_back({0.1 * i, 0.1 * j, 0.01 * ((i * 7 + j * 3) % 5)});
  for (uint32_t i = 0; i + 1 < n; ++i)
    for (uint32_t j = 0; j + 1 < n; ++j) {
      const uint32_t v = first + i * n + j;
      s.faces.push_back({{v, v + n, v + 1}});
      s.faces.push_back({{v + 1, v + n, v + n + 1}});
    }
  s.vertex_count = static_cast<uint32_t>(s.frames[0].size());
  const LccModel model(s.faces, s.frames[0], 9, 8, 0.75);
  const LccOrder& order = model.order();
  std::vector<Vec3> one_by_one = s.frames[0];
  const Vec3 root = one_by_one[order.direct[0]], along{0.25, -0.5, 0.125};
  one_by_one[order.direct[1]] = {root.x + along.x, root.y + along.y, root.z + along.z};
  one_by_one[order.direct[2]] = {root.x + 2 * along.x, root.y + 2 * along.y, root.z + 2 * along.z};
  for (size_t i = 4; i < 6; ++i) one_by_one[order.direct[i]] = one_by_one[order.direct[3]];
  std::vector<Vec3> chunked = one_by_one;
  test::Random random(71);
  std::vector<int32_t> indices(3 * order.steps.size());
  for (size_t k = 0; k < order.steps.size(); ++k) {
    indices[3 * k] = random.uniform(-model.theta_limit(), model.theta_limit() - 1);
    indices[3 * k + 1] = random.uniform(-model.rh_limit(), model.rh_limit());
    indices[3 * k + 2] = random.uniform(-model.rh_limit(), model.rh_limit());
  }
  for (size_t k = 0; k < order.steps.size(); ++k)
    one_by_one[order.steps[k].d] = model.place(k, one_by_one, indices[3 * k], indices[3 * k + 1], indices[3 * k + 2]);
  for (size_t chunk = 0; chunk * kLccStepChunk < order.steps.size(); ++chunk) model.place_chunk(chunk, indices, chunked);
  ASSERT_GT(order.steps.size(), kLccStepChunk);  // more than one chunk
  const auto bits = [](const Vec3& p) { return std::array{bit_cast<uint64_t>(p.x), bit_cast<uint64_t>(p.y), bit_cast<uint64_t>(p.z)}; };
  for (size_t v = 0; v < s.vertex_count; ++v) ASSERT_EQ(bits(chunked[v]), bits(one_by_one[v])) << "vertex " << v;
}

TEST(Lcc, AngleTableMatchesTheCircle) {
  for (int bits : {3, 6, 12, 16}) {
    const AngleTable table(bits);
    const int64_t n = int64_t{1} << bits;
    for (int64_t index = 0; index < n; ++index) {
      const double angle = 2 * std::numbers::pi * static_cast<double>(index - n / 2) / static_cast<double>(n);
      ASSERT_NEAR(table.cos(static_cast<size_t>(index)), std::cos(angle), 4e-16) << bits << " bits, index " << index;
      ASSERT_NEAR(table.sin(static_cast<size_t>(index)), std::sin(angle), 4e-16) << bits << " bits, index " << index;
    }
    EXPECT_EQ(table.cos(static_cast<size_t>(n / 2)), 1.0);  // θ = 0
    EXPECT_EQ(table.sin(static_cast<size_t>(n / 2)), 0.0);
    EXPECT_EQ(table.cos(0), -1.0);  // θ = −π
  }
}

// The table's bytes are pinned: every compiler and optimisation level that
// runs this test (the release and the sanitizer builds of CI) computes the
// same binary64 values, which decoding depends on.
TEST(Lcc, AngleTableIsTheSameEverywhere) {
  const AngleTable table(12);
  std::string bytes;
  for (size_t i = 0; i < (size_t{1} << 12); ++i)
    for (double v : {table.cos(i), table.sin(i)}) {
      const uint64_t bits = bit_cast<uint64_t>(v);
      for (int b = 0; b < 8; ++b) bytes += static_cast<char>((bits >> (8 * b)) & 0xFF);
    }
  EXPECT_EQ(md5_hex(bytes), "6f214439f4232a094e50ecc12474e22a");
}

}  // namespace
}  // namespace m4mesh
