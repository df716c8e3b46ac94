// The field's metrics (mesh3d/metrics.h): KG error, RMSE, PSNR and STED
// against values computed by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "mesh3d/metrics.h"
#include "mesh3d/sequence.h"
#include "tests/test_util.h"

namespace m4mesh {
namespace {

using test::test_sequence;

MeshSequence one_triangle(std::vector<std::vector<Vec3>> frames) {
  MeshSequence s;
  s.vertex_count = 3;
  s.faces = {{{0, 1, 2}}};
  s.frames = std::move(frames);
  return s;
}

TEST(Metrics, HandComputedValues) {
  // One frame: (0,0,0) (3,0,0) (0,4,0); the decoded moves vertex 1 by 0.3 in x.
  const MeshSequence a = one_triangle({{{0, 0, 0}, {3, 0, 0}, {0, 4, 0}}});
  const MeshSequence b = one_triangle({{{0, 0, 0}, {3.3, 0, 0}, {0, 4, 0}}});
  const SequenceMetrics m = compare_sequences(a, b);
  // Mean (1, 4/3, 0); spread Σ|v − mean|² = (1 + 16/9) + (4 + 16/9) + (1 + 64/9) = 50/3; error 0.09.
  EXPECT_NEAR(m.kg_error, 100 * std::sqrt(0.09) / std::sqrt(50.0 / 3), 1e-12);
  EXPECT_NEAR(m.rmse, std::sqrt(0.09 / 3), 1e-12);
  EXPECT_NEAR(m.max_error, 0.3, 1e-12);
  // dmax = diagonal of the box 3×4×0 = 5; AVGMSE = 0.03.
  EXPECT_NEAR(m.psnr, 10 * std::log10(25 / 0.03), 1e-9);
  // Edges 0-1 (3 → 3.3: ed 0.1), 1-2 (5 → √(3.3² + 16) : ed (√26.89 − 5)/5), 2-0 (4: ed 0).
  // Every vertex's neighbourhood holds all three edges (d = 1).
  const double e12 = (std::sqrt(26.89) - 5) / 5;
  const double mean = (0.1 * 3 + e12 * 5 + 0 * 4) / 12;
  const double deviation = std::sqrt(((0.1 - mean) * (0.1 - mean) * 3 + (e12 - mean) * (e12 - mean) * 5 + mean * mean * 4) / 12);
  EXPECT_NEAR(m.sted_spatial, deviation, 1e-12);
  EXPECT_EQ(m.sted_temporal, 0);  // one frame
  EXPECT_NEAR(m.sted, deviation, 1e-12);
}

TEST(Metrics, DiameterIsTheLargestPairwiseDistance) {
  test::Random random(77);
  auto brute = [](const std::vector<Vec3>& p) {
    double best = 0;
    for (size_t i = 0; i < p.size(); ++i)
      for (size_t j = i + 1; j < p.size(); ++j)
        best = std::max(best, std::sqrt((p[i].x - p[j].x) * (p[i].x - p[j].x) + (p[i].y - p[j].y) * (p[i].y - p[j].y) +
                                        (p[i].z - p[j].z) * (p[i].z - p[j].z)));
    return best;
  };
  for (int shape = 0; shape < 3; ++shape)
    for (int trial = 0; trial < 20; ++trial) {
      std::vector<Vec3> points;
      for (int i = 0; i < 300; ++i) {
        const double u = random.uniform(-1000, 1000) / 1000.0, v = random.uniform(-1000, 1000) / 1000.0, w = random.uniform(-1000, 1000) / 1000.0;
        const double n = std::sqrt(u * u + v * v + w * w) + 1e-9;
        points.push_back(shape == 0 ? Vec3{u, v, w} : shape == 1 ? Vec3{u / n, v / n, w / n} : Vec3{3 * u, v, 0});  // cube, sphere, flat
      }
      EXPECT_DOUBLE_EQ(diameter(points), brute(points)) << shape;
    }
  EXPECT_EQ(diameter(std::vector<Vec3>{}), 0);
  EXPECT_EQ(diameter(std::vector<Vec3>{{1, 2, 3}}), 0);
}

TEST(Metrics, TemporalStedByHand) {
  // Two frames; vertex 0 moves by 0.5 in the original and by 0.6 in the decoded; ld = 5.
  const MeshSequence a = one_triangle({{{0, 0, 0}, {3, 0, 0}, {0, 4, 0}}, {{0.5, 0, 0}, {3, 0, 0}, {0, 4, 0}}});
  const MeshSequence b = one_triangle({{{0, 0, 0}, {3, 0, 0}, {0, 4, 0}}, {{0.6, 0, 0}, {3, 0, 0}, {0, 4, 0}}});
  double spatial, temporal, combined;
  StedParams p;
  sted(a, b, p, spatial, temporal, combined);
  const double tel_a = std::sqrt(0.1 * 0.1 + p.dt * p.dt), tel_b = std::sqrt(0.12 * 0.12 + p.dt * p.dt);
  // ted = |tel − tel'| / s with s = tel (the window holds one frame); static vertices add 0.
  EXPECT_NEAR(temporal, (std::abs(tel_a - tel_b) / tel_a) / 3, 1e-12);
  EXPECT_NEAR(combined, std::sqrt(spatial * spatial + p.c * p.c * temporal * temporal), 1e-15);
}

TEST(Metrics, StedIgnoresRigidMotionAndUniformScaling) {
  const MeshSequence original = test_sequence(5, 9);
  MeshSequence decoded = original;
  test::Random random(9);
  for (auto& frame : decoded.frames)
    for (Vec3& v : frame) v.x += 1e-3 * random.uniform(-10, 10);
  double s0, t0, c0;
  sted(original, decoded, {}, s0, t0, c0);
  ASSERT_GT(c0, 0);
  const double kg0 = kg_error(original, decoded);
  auto transformed = [](MeshSequence s, double scale) {
    const double angle = 0.7;
    for (auto& frame : s.frames)
      for (Vec3& v : frame) {
        const double x = std::cos(angle) * v.x - std::sin(angle) * v.z, z = std::sin(angle) * v.x + std::cos(angle) * v.z;
        v = {scale * x + 5, scale * v.y - 2, scale * z + 1};
      }
    return s;
  };
  for (double scale : {1.0, 3.5}) {
    double s1, t1, c1;
    sted(transformed(original, scale), transformed(decoded, scale), {}, s1, t1, c1);
    EXPECT_NEAR(s1, s0, 1e-9 * s0);
    EXPECT_NEAR(t1, t0, 1e-9 * t0);
    EXPECT_NEAR(c1, c0, 1e-9 * c0);
    EXPECT_NEAR(kg_error(transformed(original, scale), transformed(decoded, scale)), kg0, 1e-9 * kg0);
  }
}

}  // namespace
}  // namespace m4mesh
