// The affine fit that predicts cpca-wpt's bases over the mesh
// (mesh3d/affine_fit.h), on cases worked out by hand from
// docs/codec_cpca_wpt.md ("Prediction by the mean shape").
#include "mesh3d/affine_fit.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "mesh3d/cpca_wpt.h"

namespace m4mesh {
namespace {

// Vertex 0 at the origin, then one vertex per position given, each with
// its value; the fit at vertex 0 from all the others.
int64_t fit_at_origin(const std::vector<IntPoint3>& around, const std::vector<int32_t>& values) {
  std::vector<IntPoint3> positions{{0, 0, 0}};
  positions.insert(positions.end(), around.begin(), around.end());
  std::vector<uint32_t> points;
  for (uint32_t u = 1; u < positions.size(); ++u) points.push_back(u);
  std::array<int64_t, 1> p{};
  affine_fit<1>(positions, 0, points, [&](uint32_t u) { return std::array<int32_t, 1>{values[u - 1]}; }, p);
  return p[0];
}

TEST(AffineFit, OnePointGivesItsValue) { EXPECT_EQ(fit_at_origin({{5, -2, 7}}, {-123}), -123); }

TEST(AffineFit, PointsAroundGiveTheirMean) { EXPECT_EQ(fit_at_origin({{4, 0, 0}, {-4, 0, 0}}, {10, 21}), 15); }

// All points at v's position: no spread, no gradient (the determinant is
// 0): the floor of the mean.
TEST(AffineFit, CoincidentPointsGiveTheirMean) { EXPECT_EQ(fit_at_origin({{0, 0, 0}, {0, 0, 0}}, {3, 4}), 3); }

// Points at x = 1 and 2 with values 100 and 200: the line through them
// meets 0 at v, the ridge (λ = 1/256 of Σ|q|² = 5) flattens it:
// C_xx = 5 − 9/2 + 5/256, r_x = 500 − 3 · 300 / 2 = 50, g = r_x / C_xx,
// c = (300 − 3g) / 2 = 5.639…
TEST(AffineFit, TheRidgeFlattensAnExtrapolation) { EXPECT_EQ(fit_at_origin({{1, 0, 0}, {2, 0, 0}}, {100, 200}), 5); }

// A full 3D fit of 5 points whose values are 7 + 20x − 30y + 50z: 8.799…
// (7 without the ridge).
TEST(AffineFit, FitsInThreeDimensions) {
  const std::vector<IntPoint3> around{{3, 0, 1}, {0, 4, -2}, {-5, 1, 0}, {1, -3, 2}, {2, 2, 2}};
  std::vector<int32_t> values;
  for (const IntPoint3& q : around) values.push_back(7 + 20 * q[0] - 30 * q[1] + 50 * q[2]);
  EXPECT_EQ(fit_at_origin(around, values), 8);
}

// Differences beyond 11 bits shift right first: 2^20 + 1000 and 3 · 2^20
// become 512 and 1536, and the fit 519.157… (518.476… unshifted).
TEST(AffineFit, LargeDifferencesShiftIntoElevenBits) {
  EXPECT_EQ(fit_at_origin({{(1 << 20) + 1000, 0, 0}, {3 << 20, 0, 0}}, {1000, 2000}), 519);
}

// An extrapolation beyond the values' range stops at ±2^15.
TEST(AffineFit, ThePredictionStaysWithinTheValuesRange) {
  EXPECT_EQ(fit_at_origin({{1, 0, 0}, {2, 0, 0}}, {-30000, 30000}), -32768);
  EXPECT_EQ(fit_at_origin({{1, 0, 0}, {2, 0, 0}}, {30000, -30000}), 32768);
}

// Faces (0, 1, 2) and (2, 1, 3): vertex 3's corners are 1 and 2, the apex
// of its parallelogram across 1–2 is 0.
TEST(AffineFit, SupportIsTheKnownCornersAndApexes) {
  const std::vector<Triangle> faces{{{0, 1, 2}}, {{2, 1, 3}}};
  const MeshPredictor predictor(faces, 4);
  std::vector<uint32_t> points;
  auto support = [&](std::vector<uint32_t> known) {
    return affine_fit_support(predictor, 3, [&](uint32_t u) { return std::find(known.begin(), known.end(), u) != known.end(); }, points);
  };
  EXPECT_EQ(support({2, 0, 1}), syntax::kParallelogramChannel);
  EXPECT_EQ(points, (std::vector<uint32_t>{0, 1, 2}));
  EXPECT_EQ(support({1, 2}), syntax::kNeighbourChannel);
  EXPECT_EQ(points, (std::vector<uint32_t>{1, 2}));
  EXPECT_EQ(support({0, 1}), syntax::kNeighbourChannel);  // no parallelogram without 2
  EXPECT_EQ(points, (std::vector<uint32_t>{1}));
  EXPECT_EQ(support({0}), -1);
  EXPECT_TRUE(points.empty());
}

// The encoder's basis values at rounding 0.5 are the nearest integers of
// its targets whatever the prediction; at 0.45 each residual from the
// prediction is rounded towards 0 unless its fraction reaches 0.55.
TEST(AffineFit, TheEncodersRoundingIsToNearestAtOneHalf) {
  const std::vector<Triangle> faces{{{0, 1, 2}}, {{2, 1, 3}}, {{2, 3, 4}}};
  const std::vector<IntPoint3> shape{{0, 0, 0}, {10, 0, 0}, {0, 10, 0}, {10, 10, 0}, {0, 20, 0}};
  const std::vector<uint32_t> cluster_of(5, 0), coding_order{0, 1, 2, 3, 4};
  const CpcaMeshPrediction mesh(faces, coding_order, cluster_of, 1, shape);
  const std::vector<double> target{10.4, 20.52, -30.3, 40.49, 7.2};
  std::vector<int32_t> nearest(5), towards(5);
  mesh.quantize<1>(0, target, 0.5, nearest);
  EXPECT_EQ(nearest, (std::vector<int32_t>{10, 21, -30, 40, 7}));
  mesh.quantize<1>(0, target, 0.45, towards);
  // Vertex 0 has no known neighbour: predicted 0, so 10.4 → 10. Vertex 1
  // is predicted by vertex 0 alone (10): 10.52 → 10 + 10. The others from their fits.
  EXPECT_EQ(towards[0], 10);
  EXPECT_EQ(towards[1], 20);
  for (size_t i = 0; i < target.size(); ++i) EXPECT_LE(std::abs(towards[i] - target[i]), 0.55 + 1e-9) << i;
}

}  // namespace
}  // namespace m4mesh
