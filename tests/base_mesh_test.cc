// The base mesh's own coding (docs/base_mesh.md): round trips on meshes
// with what real ones have (components, borders, isolated vertices,
// non-manifold edges and vertices, degenerate and repeated faces, a face
// turned the wrong way), the vertex orders, damaged payloads, and the rate
// targets on the real sequences.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <numeric>
#include <optional>

#include "anchors/draco_reference.h"
#include "codecs3d/codec_decoder.h"
#include "codecs3d/codec_encoder.h"
#include "encoder/mesh3d/base_mesh.h"
#include "mesh3d/gate_traversal.h"
#include "mesh3d/position_order.h"
#include "mesh3d/quantization.h"
#include "test_util.h"

namespace m4mesh {
namespace {

namespace fs = std::filesystem;

// An n × n sheet of vertices from `first`, two faces per cell.
void add_sheet(std::vector<Triangle>& faces, uint32_t first, uint32_t n) {
  for (uint32_t y = 0; y + 1 < n; ++y)
    for (uint32_t x = 0; x + 1 < n; ++x) {
      const uint32_t a = first + y * n + x;
      faces.push_back({{a, a + 1, a + n + 1}});
      faces.push_back({{a, a + n + 1, a + n}});
    }
}

// Everything at once, numbered at random: a sheet, a closed octahedron, two
// fans sharing a vertex, an edge with three faces, a degenerate face, a
// repeated face, a face turned the wrong way, isolated vertices.
struct TestMesh {
  uint32_t vertex_count = 0;
  std::vector<Triangle> faces;
  std::vector<IntPoint3> positions;
};

TestMesh awkward_mesh(uint64_t seed) {
  TestMesh m;
  add_sheet(m.faces, 0, 6);                                     // 0 … 35
  const uint32_t o = 36;                                        // octahedron 36 … 41
  const uint32_t octahedron[8][3] = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  for (const auto& f : octahedron) m.faces.push_back({{o + f[0], o + f[1], o + f[2]}});
  m.faces.push_back({{42, 43, 44}});  // two fans meeting at 42
  m.faces.push_back({{42, 44, 45}});
  m.faces.push_back({{42, 46, 47}});
  m.faces.push_back({{42, 47, 48}});
  m.faces.push_back({{0, 1, 49}});    // a third face on the sheet's edge 0 → 1
  m.faces.push_back({{50, 50, 51}});  // degenerate
  m.faces.push_back({{42, 43, 44}});  // repeated
  m.faces.push_back({{44, 43, 52}});  // consistent with the first fan
  m.faces.push_back({{43, 44, 53}});  // turned the wrong way: repeats 43 → 44
  m.vertex_count = 57;                // 54 … 56 isolated
  test::Random random(seed);
  std::vector<uint32_t> shuffle(m.vertex_count);
  std::iota(shuffle.begin(), shuffle.end(), 0u);
  for (uint32_t i = m.vertex_count - 1; i > 0; --i) std::swap(shuffle[i], shuffle[random.uniform(0, static_cast<int32_t>(i))]);
  for (Triangle& t : m.faces)
    for (NodeIndex& v : t.v) v = shuffle[v];
  for (uint32_t i = 0; i < m.vertex_count; ++i)
    m.positions.push_back({random.uniform(-4000, 4000), random.uniform(0, 4095), random.uniform(-9, 9)});
  return m;
}

std::vector<uint8_t> write_unit(std::span<const Triangle> faces, std::span<const IntPoint3> positions, const BaseMeshCoding& coding = {}) {
  BitWriter writer;
  syntax::WriteIO io(writer);
  write_base_mesh(io, faces, positions, coding);
  return writer.take_bytes();
}

BaseMesh read_unit(const std::vector<uint8_t>& unit, uint32_t vertex_count, uint32_t face_count) {
  BitReader reader(unit.data(), unit.size());
  syntax::ReadIO io(reader);
  return read_base_mesh(io, ObjectHeader{kFormatVersion, 1, vertex_count, face_count, 1, 25, 1}, nullptr);
}

TEST(BaseMesh, RoundTripsAwkwardMeshesInTheInputVertexOrder) {
  for (uint64_t seed = 1; seed <= 20; ++seed) {
    const TestMesh m = awkward_mesh(seed);
    const BaseMeshPlan plan = plan_base_mesh(m.faces, m.vertex_count, false);
    EXPECT_EQ(plan.loose_faces, 4u);  // the third face on an edge, the degenerate, repeated and turned faces
    EXPECT_TRUE(same_faces(plan.faces, m.faces));
    const std::vector<uint8_t> unit = write_unit(plan.faces, m.positions);
    const BaseMesh base = read_unit(unit, m.vertex_count, static_cast<uint32_t>(m.faces.size()));
    ASSERT_EQ(base.positions, m.positions) << "seed " << seed;
    ASSERT_EQ(base.faces, plan.faces) << "seed " << seed;
  }
}

// docs/base_mesh.md, "Position order", read literally: at each step every
// candidate's parallelograms and known corners counted again, the most taken.
std::vector<uint32_t> order_as_written(std::span<const Triangle> faces, const std::vector<uint32_t>& candidates, uint32_t vertex_count) {
  const auto opposite = [&](uint32_t from, uint32_t to) -> std::optional<uint32_t> {
    for (const Triangle& t : faces)
      for (int i = 0; i < 3; ++i)
        if (t.v[i] == from && t.v[(i + 1) % 3] == to) return t.v[(i + 2) % 3];
    return std::nullopt;
  };
  std::vector<uint8_t> known(vertex_count, 0);
  std::vector<uint32_t> order;
  while (order.size() < candidates.size()) {
    std::optional<uint32_t> best;
    std::array<uint32_t, 2> best_support{};
    for (const uint32_t v : candidates) {
      if (known[v]) continue;
      std::array<uint32_t, 2> support{};
      for (const Triangle& t : faces)
        for (const NodeIndex corner_vertex : t.v) {
          if (corner_vertex != v) continue;  // the face once per corner of v
          const int corner = t.corner_of(v);
          const uint32_t x = t.v[(corner + 1) % 3], y = t.v[(corner + 2) % 3];
          const std::optional<uint32_t> z = opposite(y, x);
          support[0] += known[x] && known[y] && z && known[*z];
          for (const NodeIndex u : t.v) support[1] += u != v && known[u];
        }
      if (!best || support > best_support) best = v, best_support = support;
    }
    known[*best] = 1;
    order.push_back(*best);
  }
  return order;
}

// A seed (0, 1, 2) and new vertices 3 … behind the gates, first in first
// out, until `faces` faces; the next gate goes to `gate`.
GateTraversal strip(uint32_t faces, HalfEdge& gate) {
  GateTraversal t(faces);
  for (int corner = 0; corner < 3; ++corner) t.new_vertex();
  EXPECT_TRUE(t.seed({{0, 1, 2}}));
  while (t.next_gate(gate) && t.faces().size() < faces) EXPECT_TRUE(t.attach(gate, t.new_vertex()));
  return t;
}

TEST(DirectedEdgeIndex, KeepsBothDirectionsOfAnEdgeApartAsItGrows) {
  // 3,000 edges, no reserve (the table grows from empty); every other one
  // also the other way, inserted second, half of them from the higher end.
  DirectedEdgeIndex index;
  const auto ends = [](uint32_t i) { return HalfEdge{i, 5003 + (i * 7919) % 5003}; };
  constexpr uint32_t kEdges = 3000;
  for (uint32_t i = 0; i < kEdges; ++i) {
    auto [a, b] = ends(i);
    if (i % 4 == 1) std::swap(a, b);
    EXPECT_EQ(index.insert_and_find_reverse(a, b, 2 * i), DirectedEdgeIndex::kNone);
    if (i % 2 == 0) {
      EXPECT_EQ(index.insert_and_find_reverse(b, a, 2 * i + 1), 2 * i);
    }
  }
  for (uint32_t i = 0; i < kEdges; ++i) {
    auto [a, b] = ends(i);
    if (i % 4 == 1) std::swap(a, b);
    EXPECT_EQ(index.find(a, b), 2 * i);
    EXPECT_EQ(index.find(b, a), i % 2 == 0 ? 2 * i + 1 : DirectedEdgeIndex::kNone);
    EXPECT_EQ(index.find(a, a), DirectedEdgeIndex::kNone);
    EXPECT_EQ(index.find(a, b + 1), DirectedEdgeIndex::kNone);
  }
}

TEST(GateTraversal, FrontAlternatesBothWaysWithoutGateCandidatesOrRepeats) {
  // Faces (1, 0, 3), (2, 1, 4), (0, 2, 5), (3, 0, 6): the open loop
  // 0 → 6 → 3 → 1 → 4 → 2 → 5 → 0, the next gate 3 → 1. Candidates 4 (after
  // 1) and 6 (before 3); ahead of 1: 4, 2, 5, 0; behind 3: 6, 0, 5, 2.
  HalfEdge gate{};
  const GateTraversal t = strip(5, gate);
  ASSERT_EQ(gate.from, 3u);
  ASSERT_EQ(gate.to, 1u);
  std::vector<uint32_t> candidates, front;
  t.candidates(gate, candidates);
  EXPECT_EQ(candidates, (std::vector<uint32_t>{4, 6}));
  t.front(gate, candidates, front);
  EXPECT_EQ(front, (std::vector<uint32_t>{2, 0, 5}));
}

TEST(GateTraversal, FrontWalksEightStepsEachWay) {
  // A long loop: steps 2 … 8 each way, the first steps being the candidates.
  HalfEdge gate{};
  const GateTraversal t = strip(60, gate);
  std::vector<uint32_t> candidates, front;
  t.candidates(gate, candidates);
  t.front(gate, candidates, front);
  EXPECT_EQ(candidates.size(), 2u);
  EXPECT_EQ(front.size(), GateTraversal::kMaxFront);
}

TEST(BaseMesh, FarVerticesOnTheFrontRoundTrip) {
  // A torus of 16 × 12 cells, diagonals at random: the front meets itself around it.
  constexpr uint32_t kAround = 16, kAcross = 12;
  test::Random random(7);
  std::vector<Triangle> faces;
  for (uint32_t y = 0; y < kAcross; ++y)
    for (uint32_t x = 0; x < kAround; ++x) {
      const uint32_t a = y * kAround + x, b = y * kAround + (x + 1) % kAround, c = (y + 1) % kAcross * kAround + (x + 1) % kAround,
                     d = (y + 1) % kAcross * kAround + x;
      if (random.uniform(0, 1)) {
        faces.push_back({{a, b, c}});
        faces.push_back({{a, c, d}});
      } else {
        faces.push_back({{a, b, d}});
        faces.push_back({{b, c, d}});
      }
    }
  std::vector<IntPoint3> positions(kAround * kAcross);
  for (IntPoint3& p : positions) p = {random.uniform(0, 99), random.uniform(0, 99), random.uniform(0, 99)};
  const BaseMeshPlan plan = plan_base_mesh(faces, kAround * kAcross, false);
  const std::vector<uint8_t> unit = write_unit(plan.faces, positions);
  const BaseMesh base = read_unit(unit, kAround * kAcross, static_cast<uint32_t>(plan.faces.size()));
  EXPECT_EQ(base.faces, plan.faces);
  EXPECT_EQ(base.positions, positions);
}

TEST(PositionOrder, IsTheDefinitionsOrder) {
  for (uint64_t seed = 1; seed <= 10; ++seed) {
    const TestMesh m = awkward_mesh(seed);
    const std::vector<Triangle> faces = plan_base_mesh(m.faces, m.vertex_count, false).faces;
    const MeshPredictor predictor(faces, m.vertex_count);
    std::vector<uint32_t> all(m.vertex_count);
    std::iota(all.begin(), all.end(), 0u);
    ASSERT_EQ(PositionOrder(predictor, m.vertex_count).of(all), order_as_written(faces, all, m.vertex_count)) << "seed " << seed;
    // A cluster's members, in the order that breaks ties: the others are never known.
    std::vector<uint32_t> some;
    for (uint32_t v = m.vertex_count; v-- > 0;)
      if (v % 3 != 0) some.push_back(v);
    ASSERT_EQ(PositionOrder(predictor, m.vertex_count).of(some), order_as_written(faces, some, m.vertex_count)) << "seed " << seed;
  }
}

// Its definition: across the edge of t opposite v[j], the lowest triangle
// holding v[j + 2] → v[j + 1]; on the awkward meshes and as given (repeated,
// degenerate and wrongly turned faces, a vertex at two corners).
TEST(TriangleNeighbours, IsTheLowestTriangleOnTheReverseEdge) {
  for (uint64_t seed = 1; seed <= 10; ++seed) {
    TestMesh m = awkward_mesh(seed);
    m.faces.push_back({{7, 8, 7}});
    const TriangleNeighbours neighbours = triangle_neighbours(m.faces, m.vertex_count);
    for (uint32_t k = 0; k < m.faces.size(); ++k)
      for (int j = 0; j < 3; ++j) {
        const NodeIndex a = m.faces[k].v[(j + 2) % 3], b = m.faces[k].v[(j + 1) % 3];
        uint32_t expected = kNoTriangle;
        for (uint32_t t = 0; t < m.faces.size() && expected == kNoTriangle; ++t)
          for (int i = 0; i < 3; ++i)
            if (m.faces[t].v[i] == a && m.faces[t].v[(i + 1) % 3] == b) expected = t;
        ASSERT_EQ(neighbours[k][j], expected) << "seed " << seed << ", triangle " << k << ", corner " << j;
      }
  }
}

// Two faces on the edge 1 – 2 and a vertex in no face, candidates given
// from the highest number: 4 and 3 come first as given (no support), 2 and
// 1 then tie on one corner each, so 2 as given earlier; 1 follows with
// three corners and 0 last, the only one with a parallelogram (1 + 2 − 3).
TEST(PositionOrder, SupportThenTheCandidatesOrder) {
  const std::vector<Triangle> faces = {{{0, 1, 2}}, {{2, 1, 3}}};
  const MeshPredictor predictor(faces, 5);
  EXPECT_EQ(PositionOrder(predictor, 5).of(std::vector<uint32_t>{4, 3, 2, 1, 0}), (std::vector<uint32_t>{4, 3, 2, 1, 0}));
  // Given in increasing order, 3 waits for its parallelogram (2 + 1 − 0) after 2's three corners.
  EXPECT_EQ(PositionOrder(predictor, 5).of(std::vector<uint32_t>{0, 1, 2, 3, 4}), (std::vector<uint32_t>{0, 1, 2, 3, 4}));
  // 3 given first: 2 and 1 tie on its corner; 0 then has a parallelogram (1 + 2 − 3) and 4 nothing.
  EXPECT_EQ(PositionOrder(predictor, 5).of(std::vector<uint32_t>{3, 4, 2, 1, 0}), (std::vector<uint32_t>{3, 2, 1, 0, 4}));
}

TEST(BaseMesh, ReorderNumbersVerticesInCodingOrder) {
  const TestMesh m = awkward_mesh(7);
  const BaseMeshPlan plan = plan_base_mesh(m.faces, m.vertex_count, true);
  std::vector<IntPoint3> coded(m.vertex_count);
  for (uint32_t i = 0; i < m.vertex_count; ++i) coded[i] = m.positions[plan.input_of[i]];
  const std::vector<uint8_t> unit = write_unit(plan.faces, coded, BaseMeshCoding{std::nullopt, true});
  EXPECT_EQ(unit[0], kVertexOrderCoding);
  // Not asked for: the input's numbers are sent, though the traversal numbers the vertices as they are.
  EXPECT_NE(write_unit(plan.faces, coded)[0], kVertexOrderCoding);
  const BaseMesh base = read_unit(unit, m.vertex_count, static_cast<uint32_t>(m.faces.size()));
  EXPECT_EQ(base.positions, coded);
  EXPECT_EQ(base.faces, plan.faces);
  EXPECT_LT(unit.size(), write_unit(plan_base_mesh(m.faces, m.vertex_count, false).faces, m.positions).size());
}

TEST(BaseMesh, PlanningFacesInCodingOrderChangesNothing) {
  const TestMesh m = awkward_mesh(3);
  for (bool reorder : {false, true}) {
    const BaseMeshPlan plan = plan_base_mesh(m.faces, m.vertex_count, reorder);
    const BaseMeshPlan again = plan_base_mesh(plan.faces, m.vertex_count, reorder);
    EXPECT_EQ(again.faces, plan.faces);
    if (reorder) {
      EXPECT_TRUE(std::is_sorted(again.input_of.begin(), again.input_of.end()));
    }
  }
}

TEST(BaseMesh, RefusesFacesNotInCodingOrder) {
  const TestMesh m = awkward_mesh(4);
  std::vector<Triangle> faces = plan_base_mesh(m.faces, m.vertex_count, false).faces;
  std::swap(faces[3], faces[9]);
  EXPECT_THROW(write_unit(faces, m.positions), Error);
}

TEST(BaseMesh, ParallelogramsOfInputNumbersPredictARowMajorGrid) {
  std::vector<Triangle> faces;
  add_sheet(faces, 0, 40);
  std::vector<IntPoint3> positions;
  for (int32_t y = 0; y < 40; ++y)
    for (int32_t x = 0; x < 40; ++x) positions.push_back({x * 100, y * 100, (x * y) % 7});
  const std::vector<uint8_t> unit = write_unit(plan_base_mesh(faces, 1600, false).faces, positions);
  EXPECT_EQ(unit[0], kVertexOrderFromParallelogram);
  EXPECT_LT(unit.size(), 1600u);  // under 8 bits per vertex, the vertex order nearly free
}

// A bumpy sheet: its parallelograms miss by the bumps, which the neighbours' mean halves.
TEST(BaseMesh, EveryPositionBlendRoundTripsAndAutoTakesTheSmallest) {
  std::vector<Triangle> faces;
  add_sheet(faces, 0, 30);
  std::vector<IntPoint3> positions;
  test::Random random(11);
  for (int32_t y = 0; y < 30; ++y)
    for (int32_t x = 0; x < 30; ++x) positions.push_back({x * 64 + random.uniform(-9, 9), y * 64 + random.uniform(-9, 9), random.uniform(-40, 40)});
  const std::vector<Triangle> planned = plan_base_mesh(faces, 900, false).faces;
  size_t smallest = SIZE_MAX;
  uint32_t best = 0;
  for (uint32_t blend = 0; blend <= kPositionBlendUnit; ++blend) {
    const std::vector<uint8_t> unit = write_unit(planned, positions, BaseMeshCoding{blend});
    EXPECT_EQ(unit[1], blend);  // after vertex_order
    const BaseMesh base = read_unit(unit, 900, static_cast<uint32_t>(faces.size()));
    ASSERT_EQ(base.positions, positions) << "blend " << blend;
    if (unit.size() < smallest) {
      smallest = unit.size();
      best = blend;
    }
  }
  EXPECT_GT(best, 0u);
  const std::vector<uint8_t> automatic = write_unit(planned, positions);
  EXPECT_EQ(automatic[1], best);
  EXPECT_EQ(automatic.size(), smallest);
}

// Every damaged copy decodes or raises Error: never a crash, a hang or an overrun (ASan).
TEST(BaseMesh, DamagedUnitsFailCleanly) {
  const TestMesh m = awkward_mesh(9);
  const std::vector<uint8_t> unit = write_unit(plan_base_mesh(m.faces, m.vertex_count, false).faces, m.positions);
  test::Random random(11);
  int rejected = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    std::vector<uint8_t> damaged = unit;
    if (trial % 4 == 0) damaged.resize(static_cast<size_t>(random.uniform(0, static_cast<int32_t>(unit.size()) - 1)));
    else damaged[static_cast<size_t>(random.uniform(5, static_cast<int32_t>(unit.size()) - 1))] ^= static_cast<uint8_t>(1 << random.uniform(0, 7));
    try {
      read_unit(damaged, m.vertex_count, static_cast<uint32_t>(m.faces.size()));
    } catch (const Error&) {
      ++rejected;
    }
  }
  EXPECT_GT(rejected, 1000);
}

// The rate targets of docs/base_mesh.md at 12 bits: at most 32 bits per
// vertex in the input order, and with --reorder no more than Draco's edgebreaker.
TEST(BaseMeshRealData, TwelveBitsStayWithinTheTargets) {
  const fs::path data = fs::path(M4MESH_SOURCE_DIR) / ".." / "shared" / "data";
  for (const char* name : {"horse-gallop", "pcow", "openfamc_testdata/dance_mesh", "openfamc_testdata/dog_mesh",
                           "openfamc_testdata/handstand_mesh"}) {
    if (!fs::exists(data / name)) GTEST_SKIP() << "../shared/data/" << name << " is absent";
    MeshSequence s = load_sequence((data / name).string());
    const Grid grid = Grid::over(s.frames[0], 12, true);
    std::vector<IntPoint3> q(s.vertex_count);
    for (uint32_t i = 0; i < s.vertex_count; ++i) ASSERT_TRUE(grid.quantize(s.frames[0][i], q[i]));
    const double ordered = 8.0 * static_cast<double>(write_unit(plan_base_mesh(s.faces, s.vertex_count, false).faces, q).size()) / s.vertex_count;
    const BaseMeshPlan plan = plan_base_mesh(s.faces, s.vertex_count, true);
    std::vector<IntPoint3> coded(s.vertex_count);
    for (uint32_t i = 0; i < s.vertex_count; ++i) coded[i] = q[plan.input_of[i]];
    const double reordered = 8.0 * static_cast<double>(write_unit(plan.faces, coded).size()) / s.vertex_count;
    const double draco = 8.0 * static_cast<double>(draco_grid_size(s.faces, q, true)) / s.vertex_count;
    EXPECT_LE(ordered, 32.0) << name;
    EXPECT_LE(reordered, draco) << name;
    std::printf("%-34s %6.2f bits/vertex in input order, %6.2f reordered, Draco edgebreaker %6.2f\n", name, ordered, reordered, draco);
  }
}

}  // namespace
}  // namespace m4mesh
