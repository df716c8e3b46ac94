// The Affine-Octree codec (codec_id 2): octree cells, integer reconstruction,
// the error bound ME, intra frames, and streams that must fail cleanly.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "common/atomic_file.h"
#include "common/error.h"
#include "conformance/suite3d/suite3d.h"
#include "decoder/mesh3d/container_decoder.h"
#include "encoder/mesh3d/container_encoder.h"
#include "mesh3d/affine_octree.h"
#include "mesh3d/metrics.h"
#include "mesh3d/quantization.h"
#include "syntax/mesh3d/affine_octree.h"
#include "tests/test_util.h"

namespace m4mesh {
namespace {

namespace fs = std::filesystem;

TEST(Octree, CellsByHand) {
  // Cube: min (0, 0, 0), side 8. Depth 1 splits at 4 (≥ 4 goes up), depth 2 at 2 and 6.
  const std::vector<IntPoint3> p{{0, 0, 0}, {4, 0, 0}, {3, 3, 3}, {8, 8, 8}, {5, 1, 7}, {6, 0, 0}, {1, 0, 0}};
  const RootCube cube = root_cube(p);
  EXPECT_EQ(cube.min, (std::array<int64_t, 3>{0, 0, 0}));
  EXPECT_EQ(cube.side, 8);
  OctreePartition partition;
  std::vector<std::string> seen;
  partition.walk(p, cube, [&](const OctreeCell& cell) {
    std::string s = std::to_string(cell.depth) + ":" + std::to_string(cell.index[0]) + std::to_string(cell.index[1]) +
                    std::to_string(cell.index[2]) + "@" + std::to_string(cell.corner[0]) + "[";
    for (uint32_t v : cell.vertices) s += std::to_string(v);
    seen.push_back(s + "]");
    return cell.depth == 0 || (cell.depth == 1 && cell.index[0] == 1 && cell.index[1] == 0 && cell.index[2] == 0);
  });
  // Children in the order x + 2y + 4z; vertices keep their order inside a cell.
  const std::vector<std::string> expected{"0:000@0[0123456]", "1:000@0[026]", "1:100@4[15]", "2:200@4[1]", "2:300@6[5]",
                                          "1:101@4[4]", "1:111@4[3]"};
  EXPECT_EQ(seen, expected);
}

TEST(Octree, AffineReconstructionByHand) {
  // f = 2: Q/4. x' = corner + (1.25 dx + 0.5 side + rounding), y' = corner + dy, z' = corner − dz.
  AffineMatrix q{5, 0, 0, 2, 0, 4, 0, 0, 0, 0, -4, 0};
  const std::array<int64_t, 3> out = apply_affine(q, 2, {10, 20, 30}, 8, {13, 27, 31});
  // x: (5·3 + 2·8 + 2) >> 2 = 33 >> 2 = 8 → 18; y: (4·7 + 2) >> 2 = 7 → 27; z: (−4 + 2) >> 2 = −1 → 29.
  EXPECT_EQ(out, (std::array<int64_t, 3>{18, 27, 29}));
}

// The world-space side of the bounding cube of a decoded frame.
double cube_side(const std::vector<Float3>& p) {
  double side = 0;
  for (int axis = 0; axis < 3; ++axis) {
    float lo = p[0][axis], hi = p[0][axis];
    for (const Float3& v : p) lo = std::min(lo, v[axis]), hi = std::max(hi, v[axis]);
    side = std::max(side, static_cast<double>(hi) - lo);
  }
  return side;
}

Encode3dOptions affine(const std::string& me_percent = "1", int k = 16) {
  Encode3dOptions options;
  options.codec = "affine-octree";
  options.codec_options = {{"me", me_percent}, {"matrix-bits", std::to_string(k)}};
  return options;
}

int64_t statistic(const Encode3dResult& result, const std::string& name) {
  for (const auto& [key, value] : result.statistics)
    if (key == name) return static_cast<int64_t>(value);
  return -1;
}

// Every decoded vertex lies within ME of the original (plus the grid's rounding).
void expect_within_me(const MeshSequence& s, const Encode3dOptions& options) {
  const Encode3dResult encoded = encode_mesh3d(s, options);
  Mesh3dDecoder decoder(encoded.stream, test::verifying());
  std::vector<Float3> previous;
  uint32_t frames = 0;
  const double step = Grid::over(s.frames[0], 12, true).step[0];
  const double me = std::stod(options.codec_options.at("me")) / 100;
  while (decoder.next_frame()) {
    const double bound = frames == 0 ? step : me * cube_side(previous) + 2 * step;
    for (uint32_t i = 0; i < s.vertex_count; ++i) {
      const Float3& p = decoder.positions()[i];
      const Vec3& o = s.frames[frames][i];
      const double error = std::sqrt((p[0] - o.x) * (p[0] - o.x) + (p[1] - o.y) * (p[1] - o.y) + (p[2] - o.z) * (p[2] - o.z));
      ASSERT_LE(error, bound) << "frame " << frames << ", vertex " << i;
    }
    previous = decoder.positions();
    ++frames;
  }
  EXPECT_EQ(frames, s.frames.size());
  for (uint32_t f = 0; f < frames; ++f) EXPECT_TRUE(decoder.hash_result(f).value_or(false)) << "frame " << f;
}

TEST(AffineOctree, EveryVertexWithinMe) {
  const MeshSequence s = test::test_sequence(8, 11);
  for (const char* me : {"0.2", "1", "5", "25"})
    for (int k : {10, 16}) expect_within_me(s, affine(me, k));
}

TEST(AffineOctree, LargerMeCostsFewerBytesAndMatrices) {
  const MeshSequence s = test::test_sequence(8, 12);
  const Encode3dResult fine = encode_mesh3d(s, affine("0.2"));
  const Encode3dResult coarse = encode_mesh3d(s, affine("10"));
  EXPECT_LT(coarse.frame_bytes(), fine.frame_bytes());
  EXPECT_GT(statistic(coarse, "matrices"), 0);
  EXPECT_LT(statistic(coarse, "matrices") + statistic(coarse, "vertices coded directly"),
            statistic(fine, "matrices") + statistic(fine, "vertices coded directly"));
}

// A flat sheet: every cell's points are coplanar, so every fit is singular.
TEST(AffineOctree, CoplanarCellsUseTheTruncatedSvd) {
  MeshSequence s;
  const int n = 12;
  for (int y = 0; y + 1 < n; ++y)
    for (int x = 0; x + 1 < n; ++x) {
      const NodeIndex a = static_cast<NodeIndex>(y * n + x);
      s.faces.push_back({{a, a + 1, a + n + 1}});
      s.faces.push_back({{a, a + n + 1, a + n}});
    }
  s.vertex_count = n * n;
  for (int f = 0; f < 6; ++f) {
    std::vector<Vec3> frame;
    const double angle = 0.05 * f;
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) frame.push_back({std::cos(angle) * x - std::sin(angle) * y, std::sin(angle) * x + std::cos(angle) * y, 0});
    s.frames.push_back(std::move(frame));
  }
  const Encode3dOptions options = affine();
  const Encode3dResult encoded = encode_mesh3d(s, options);
  // A rotation of a flat sheet: one matrix per frame suffices.
  EXPECT_EQ(statistic(encoded, "matrices"), 5);
  expect_within_me(s, options);
}

TEST(AffineOctree, IntraFramesResendTheBaseMesh) {
  const MeshSequence s = test::test_sequence(7, 13);
  Encode3dOptions options = affine();
  options.codec_options["intra-period"] = "3";
  const Encode3dResult encoded = encode_mesh3d(s, options);
  const ContainerParts parts = split_container(encoded.stream);
  std::vector<uint32_t> intra;
  for (const ContainerUnit& unit : parts.units)
    if (unit.payload[0] == static_cast<uint8_t>(UnitType::kBaseMesh)) intra.push_back(unit.payload[4]);
  EXPECT_EQ(intra, (std::vector<uint32_t>{0, 3, 6}));
  // An intra frame decodes to the quantized original exactly.
  Mesh3dDecoder decoder(encoded.stream, test::verifying());
  const Grid grid = Grid::over(s.frames[0], 12, true);
  while (decoder.next_frame()) {
    if (decoder.frame_index() % 3 != 0) continue;
    for (uint32_t i = 0; i < s.vertex_count; ++i) {
      IntPoint3 q;
      ASSERT_TRUE(grid.quantize(s.frames[decoder.frame_index()][i], q));
      for (int axis = 0; axis < 3; ++axis) ASSERT_EQ(decoder.positions()[i][axis], grid.position(axis, q[axis]));
    }
  }
  EXPECT_FALSE(decoder.first_mismatch().has_value());
  expect_within_me(s, options);
}

TEST(AffineOctree, EncoderIsDeterministic) {
  const MeshSequence s = test::test_sequence(5, 14);
  EXPECT_EQ(encode_mesh3d(s, affine()).stream, encode_mesh3d(s, affine()).stream);
}

TEST(AffineOctree, CorruptAndTruncatedStreamsFailCleanly) {
  const MeshSequence s = test::test_sequence(4, 15);
  EXPECT_GT(test::decode_damaged_mesh3d(encode_mesh3d(s, affine("0.5")).stream, 5, 15), 0);
}

TEST(AffineOctree, BadOptionsAreUsageErrors) {
  const MeshSequence s = test::test_sequence(2, 16);
  EXPECT_THROW(encode_mesh3d(s, affine("0")), Error);
  EXPECT_THROW(encode_mesh3d(s, affine("1", 2)), Error);
  Encode3dOptions options = affine();
  options.codec_options["parallelogram"] = "1";  // bfs3d's
  EXPECT_THROW(encode_mesh3d(s, options), Error);
}

// A codec's fixed fields are located to the bit: raw_bytes_z is the sixth
// u(32) of frame 1's data, after the start code and the unit header.
TEST(Conformance3d, Bfs3dLengthErrorGivesTheFieldsBitOffset) {
  const std::vector<SuiteCase> suite = build_suite3d();
  const auto bad = std::find_if(suite.begin(), suite.end(), [](const SuiteCase& c) { return c.id == "x-10-bfs3d-lengths"; });
  ASSERT_NE(bad, suite.end());
  uint64_t unit_start = 0;
  for (const ContainerUnit& unit : split_container(bad->stream).units)
    if (unit.payload[0] == static_cast<uint8_t>(UnitType::kFrame) && unit.payload[4] == 1) unit_start = unit.byte_offset;
  ASSERT_NE(unit_start, 0u);
  try {
    Mesh3dDecoder decoder(bad->stream);
    while (decoder.next_frame()) {
    }
    FAIL() << "decoded";
  } catch (const Error& e) {
    EXPECT_EQ(e.element(), "raw_bytes_z");
    EXPECT_EQ(e.plane(), 1);
    EXPECT_EQ(e.bit_offset(), static_cast<int64_t>(8 * unit_start + syntax::unit_data_offset() + 5 * 32));
  }
}

// ---- the paper's sequences (../shared/data) -----------------------------------

const fs::path kData = fs::path(M4MESH_SOURCE_DIR) / ".." / "shared" / "data";

// The paper's Table IV at ME = 15 %: ratio 58.33 : 1 at 15.27 dB (on 193 frames).
TEST(RealData, CowAtMe15BeatsThePapersRatioAndPsnr) {
  if (!fs::exists(kData / "pcow")) GTEST_SKIP() << "../shared/data/pcow is absent";
  const MeshSequence cow = load_sequence((kData / "pcow").string());
  Encode3dOptions options = affine("15", 12);
  options.hashes = false;
  const Encode3dResult encoded = encode_mesh3d(cow, options);
  const double raw = 12.0 * cow.vertex_count * static_cast<double>(cow.frames.size());
  EXPECT_GE(raw / static_cast<double>(encoded.stream.size()), 58.33);
  const SequenceMetrics m = compare_sequences(cow, decode_mesh3d(encoded.stream));
  EXPECT_GE(m.psnr, 15.27);
}

}  // namespace
}  // namespace m4mesh
