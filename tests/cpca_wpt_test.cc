// The clustered-PCA codec (codec_id 4): every prefix decodes and improves
// on the one before, full reconstruction, WPT against RPT, determinism,
// budgets and targets, damaged streams.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "decoder/mesh3d/container_decoder.h"
#include "encoder/mesh3d/container_encoder.h"
#include "mesh3d/cpca_wpt.h"
#include "mesh3d/metrics.h"
#include "syntax/mesh3d/container.h"
#include "tests/test_util.h"

namespace m4mesh {
namespace {

namespace fs = std::filesystem;

const fs::path kData = fs::path(M4MESH_SOURCE_DIR) / ".." / "shared" / "data";

Encode3dOptions cpca(CodecOptionValues values = {}) {
  Encode3dOptions options;
  options.codec = "cpca-wpt";
  options.codec_options = std::move(values);
  return options;
}

// (bytes received, KG error) after every unit but hash units.
std::vector<std::pair<uint64_t, double>> curve(const std::vector<uint8_t>& stream, const MeshSequence& original) {
  std::vector<std::pair<uint64_t, double>> points;
  for_each_prefix(stream, [&](size_t, uint64_t bytes, const MeshSequence& decoded) { points.emplace_back(bytes, kg_error(original, decoded)); });
  return points;
}

// The bytes a curve needs to reach a KG error, the curve read as a
// rate–distortion curve, linear between unit boundaries (INFINITY: never).
double bytes_to_reach(const std::vector<std::pair<uint64_t, double>>& points, double kg) {
  for (size_t k = 0; k < points.size(); ++k) {
    if (points[k].second > kg) continue;
    if (k == 0 || points[k].second == points[k - 1].second) return static_cast<double>(points[k].first);
    const double t = (points[k - 1].second - kg) / (points[k - 1].second - points[k].second);
    return static_cast<double>(points[k - 1].first) + t * static_cast<double>(points[k].first - points[k - 1].first);
  }
  return INFINITY;
}

TEST(CpcaWpt, EveryPrefixDecodesAndTheErrorNeverGrows) {
  const MeshSequence s = test::test_sequence(12, 7);
  const std::vector<uint8_t> stream = encode_mesh3d(s, cpca({{"clusters", "4"}})).stream;
  const ContainerParts parts = split_container(stream);
  ASSERT_GT(parts.units.size(), 10u);
  double previous = INFINITY;
  for (size_t k = 1; k < parts.units.size(); ++k) {
    if (parts.units[k].payload[0] == static_cast<uint8_t>(UnitType::kFrameHash)) continue;
    const ContainerPrefix prefix = container_prefix(parts, stream.size(), parts.units[k].byte_offset);
    ASSERT_EQ(prefix.units, k);
    const MeshSequence decoded = decode_mesh3d(std::span(stream).first(prefix.bytes));
    ASSERT_EQ(decoded.frames.size(), s.frames.size());
    const double kg = kg_error(s, decoded);
    EXPECT_LE(kg, previous) << "after " << k << " units";
    previous = kg;
  }
  EXPECT_EQ(container_prefix(parts, stream.size(), 3).units, 0u);
}

TEST(CpcaWpt, AllComponentsAtFineQuantizationReconstructTheOriginal) {
  const MeshSequence s = test::test_sequence(10, 3);
  const Encode3dResult r = encode_mesh3d(s, cpca({{"clusters", "3"}, {"components", "4096"}, {"noise", "-4"}, {"bits", "16"}}));
  EXPECT_LT(kg_error(s, decode_mesh3d(r.stream)), 0.001);
}

TEST(CpcaWpt, EncodingIsDeterministic) {
  const MeshSequence s = test::test_sequence(9, 11);
  EXPECT_EQ(encode_mesh3d(s, cpca()).stream, encode_mesh3d(s, cpca()).stream);
  EXPECT_EQ(encode_mesh3d(s, cpca({{"order", "rpt"}})).stream, encode_mesh3d(s, cpca({{"order", "rpt"}})).stream);
}

TEST(CpcaWpt, BudgetAndTargetAreMet) {
  const MeshSequence s = test::test_sequence(12, 5);
  Encode3dOptions options = cpca();
  options.hashes = false;
  const Encode3dResult full = encode_mesh3d(s, options);
  const uint64_t budget = full.stream.size() - full.unit_bytes[static_cast<size_t>(UnitType::kRefinement)] / 2;
  options.codec_options = {{"max-bytes", std::to_string(budget)}};
  const Encode3dResult half = encode_mesh3d(s, options);
  EXPECT_LE(half.stream.size() - 4, budget);  // through the last refinement
  EXPECT_GT(half.stream.size() - 4, budget - full.unit_bytes[static_cast<size_t>(UnitType::kRefinement)] / 4);
  for (double target : {5.0, 1.0}) {
    const Encode3dResult r = encode_mesh3d(s, cpca({{"target-kg", std::to_string(target)}}));
    const double kg = kg_error(s, decode_mesh3d(r.stream));
    EXPECT_LE(kg, target);
    // The prefix one refinement shorter misses the target: the first that reaches it.
    const ContainerParts parts = split_container(r.stream);
    size_t last_refinement = 0;
    for (size_t k = 0; k < parts.units.size(); ++k)
      if (parts.units[k].payload[0] == static_cast<uint8_t>(UnitType::kRefinement)) last_refinement = k;
    ASSERT_GT(last_refinement, 0u);
    EXPECT_GT(kg_error(s, decode_mesh3d(std::span(r.stream).first(parts.units[last_refinement].byte_offset))), target);
  }
  EXPECT_THROW(encode_mesh3d(s, cpca({{"target-kg", "0.000001"}, {"components", "1"}})), Error);
  EXPECT_THROW(encode_mesh3d(s, cpca({{"order", "fast"}})), Error);
  EXPECT_THROW(encode_mesh3d(s, cpca({{"noise", "13"}})), Error);
}

// With a KG target, clusters and components left to auto: of 5, 10, 20 and
// 40 clusters the one whose plan is smallest, with every component; the
// same stream as that count given.
TEST(CpcaWpt, ATargetChoosesTheClusterCount) {
  const MeshSequence s = test::test_sequence(12, 6);
  const Encode3dResult chosen = encode_mesh3d(s, cpca({{"target-kg", "1"}}));
  const auto clusters = std::find_if(chosen.statistics.begin(), chosen.statistics.end(), [](const CodecStatistic& c) { return c.first == "clusters"; });
  ASSERT_NE(clusters, chosen.statistics.end());
  const std::string count = std::to_string(static_cast<int>(clusters->second));
  EXPECT_EQ(encode_mesh3d(s, cpca({{"target-kg", "1"}, {"clusters", count}, {"components", "4096"}})).stream, chosen.stream);
  for (const char* other : {"5", "10", "20", "40"}) {
    const uint64_t bytes = encode_mesh3d(s, cpca({{"target-kg", "1"}, {"clusters", other}, {"components", "4096"}})).stream.size();
    EXPECT_LE(chosen.stream.size(), bytes + bytes / 50) << other << " clusters";  // the choice is on planned sizes
  }
  EXPECT_THROW(encode_mesh3d(s, cpca({{"clusters", "0"}})), Error);
  EXPECT_THROW(encode_mesh3d(s, cpca({{"components", "many"}})), Error);
}

TEST(CpcaWpt, CorruptAndTruncatedStreamsFailCleanly) {
  EXPECT_GT(test::decode_damaged_mesh3d(encode_mesh3d(test::test_sequence(6, 2), cpca({{"clusters", "3"}})).stream, 41, 5), 0);
}

// The report's claim on real sequences: weighted progressive transmission
// reaches every quality with no more bytes than round robin (compared as
// rate–distortion curves at the KG errors RPT reaches after a tenth, two
// tenths, … of its units), and the error never grows from one unit to the
// next.
TEST(CpcaWptRealData, WptNeverNeedsMoreBytesThanRpt) {
  for (const char* name : {"pcow", "horse-gallop"}) {
    if (!fs::exists(kData / name)) GTEST_SKIP() << "../shared/data/" << name << " is absent";
    const MeshSequence s = load_sequence((kData / name).string());
    const auto wpt = curve(encode_mesh3d(s, cpca()).stream, s);
    const auto rpt = curve(encode_mesh3d(s, cpca({{"order", "rpt"}})).stream, s);
    for (size_t k = 1; k < wpt.size(); ++k) EXPECT_LE(wpt[k].second, wpt[k - 1].second) << name << " unit " << k;
    for (int checkpoint = 1; checkpoint <= 10; ++checkpoint) {
      const double kg = rpt[(rpt.size() - 1) * static_cast<size_t>(checkpoint) / 10].second;
      EXPECT_LE(bytes_to_reach(wpt, kg), bytes_to_reach(rpt, kg)) << name << " at KG " << kg;
    }
  }
}

}  // namespace
}  // namespace m4mesh
