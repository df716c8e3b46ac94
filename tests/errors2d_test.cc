// Bad streams: every error names its kind, element, plane and bit offset;
// nothing crashes, nothing is trusted.
#include <gtest/gtest.h>

#include "decoder/mesh_object_decoder.h"
#include "encoder/mesh_object_encoder.h"
#include "syntax/mesh_object.h"
#include "syntax/values.h"
#include "syntax/vlc.h"
#include "tests/test_util.h"

namespace m4mesh {
namespace {

constexpr const char* kObjectStart = "00000000 00000000 00000001 10111100";
constexpr const char* kPlaneStart = "00000000 00000000 00000001 10111101";
constexpr const char* kEnd = "00000000 00000000 00000001 10110001";

// Decodes all planes; returns the error, or nothing.
std::optional<Error> decode_error(const std::vector<uint8_t>& stream) {
  try {
    Decoder decoder(stream);
    while (decoder.next()) {
    }
  } catch (const Error& e) {
    return e;
  }
  return std::nullopt;
}

// The object start code, then body padded with zeros to a byte.
std::vector<uint8_t> stream_of(const std::string& body) {
  std::string bits = std::string(kObjectStart) + body;
  size_t count = 0;
  for (char c : bits) count += c == '0' || c == '1';
  return test::bytes_from_bits(bits + std::string((8 - count % 8) % 8, '0'));
}

void expect_error(const std::vector<uint8_t>& stream, ErrorKind kind, const std::string& element, int64_t plane,
                  int64_t bit) {
  const std::optional<Error> error = decode_error(stream);
  ASSERT_TRUE(error.has_value()) << "accepted";
  EXPECT_EQ(error->kind(), kind) << error->what();
  EXPECT_EQ(error->element(), element) << error->what();
  EXPECT_EQ(error->plane(), plane) << error->what();
  EXPECT_EQ(error->bit_offset(), bit) << error->what();
}

// A valid 3×3 uniform I-plane body (plane start code included).
std::string uniform_plane_bits(const char* mesh_type = "00") {
  return std::string(kPlaneStart) + "1" + mesh_type + "0000000011 0000000011 00010000 00010000 00" + "0111111";
}

TEST(Errors, ReservedMeshTypeCode) {
  expect_error(stream_of(uniform_plane_bits("10") + kEnd), ErrorKind::kReservedValue, "mesh_type_code", 0, 65);
  expect_error(stream_of(uniform_plane_bits("11") + kEnd), ErrorKind::kReservedValue, "mesh_type_code", 0, 65);
}

TEST(Errors, MotionRangeCodeZero) {
  const std::string p = std::string(kPlaneStart) + "0 00" + std::string(9, '0') + "0000";  // 12 bits + 4 stuffing
  expect_error(stream_of(uniform_plane_bits() + p + kEnd), ErrorKind::kReservedValue, "motion_range_code", 1, 145);
}

TEST(Errors, BadStuffing) {
  const std::string bad = std::string(kPlaneStart) + "1" + "00" + "0000000011 0000000011 00010000 00010000 00" + "0111110";
  expect_error(stream_of(bad + kEnd), ErrorKind::kBadStuffing, "next_start_code", 0, 64 + 41);
}

TEST(Errors, PPlaneBeforeAnyIPlane) {
  const std::string p = std::string(kPlaneStart) + "0 01" + "00000";
  expect_error(stream_of(p + kEnd), ErrorKind::kStructure, "new_mesh_flag", 0, 64);
}

TEST(Errors, CountsOutOfRange) {
  // nr_of_mesh_nodes_hori = 1
  const std::string bad = std::string(kPlaneStart) + "1" + "00" + "0000000001 0000000011 00010000 00010000 00" + "0111111";
  expect_error(stream_of(bad + kEnd), ErrorKind::kOutOfRange, "nr_of_mesh_nodes_hori", 0, 67);
  // mesh_rect_size_verti = 0
  const std::string zero = std::string(kPlaneStart) + "1" + "00" + "0000000011 0000000011 00010000 00000000 00" + "0111111";
  expect_error(stream_of(zero + kEnd), ErrorKind::kOutOfRange, "mesh_rect_size_verti", 0, 95);
  // Delaunay: 2 nodes; then 4 boundary nodes of 3.
  const std::string two = std::string(kPlaneStart) + "1" + "01" + "0000000000000010";
  expect_error(stream_of(two + "0000000000000" + kEnd), ErrorKind::kOutOfRange, "nr_of_mesh_nodes", 0, 67);
  const std::string more = std::string(kPlaneStart) + "1" + "01" + "0000000000000011" + "0000000100";
  expect_error(stream_of(more + "000000" + kEnd), ErrorKind::kOutOfRange, "nr_of_boundary_nodes", 0, 83);
}

TEST(Errors, HugeCountWithTinyPayloadFailsBeforeAllocating) {
  // 65535 nodes claimed, a few bytes follow.
  const std::string bits = std::string(kPlaneStart) + "1" + "01" + "1111111111111111" + "0000000011" + "0000000000" +
                           "0000000000" + "0";
  expect_error(stream_of(bits + "000000"), ErrorKind::kTruncated, "delta_x_len_vlc", 0, 113);
}

// The largest uniform mesh (1,046,529 nodes) costs 18 bytes; a P-plane for
// it must then hold at least one bit per node before anything is allocated.
TEST(Errors, PPlaneOfTheLargestMeshWithATinyPayload) {
  const std::string intra = std::string(kPlaneStart) + "1" + "00" + "1111111111 1111111111 00000001 00000001 00" + "0111111";
  const std::string inter = std::string(kPlaneStart) + "0 01" + "1 1 1 1 1";
  expect_error(stream_of(intra + inter), ErrorKind::kTruncated, "node_motion_vector_flag", 1, 112 + 32 + 3);
  // The same I-plane alone decodes: the syntax allows it.
  const std::vector<uint8_t> alone = stream_of(intra + kEnd);
  Decoder decoder(alone);
  ASSERT_TRUE(decoder.next());
  EXPECT_EQ(decoder.nodes().size(), 1023u * 1023u);
}

TEST(Errors, DeltaLengthTwelveAndCoordinateRange) {
  // 3 nodes, node0 (0, 0), then a length code of nine '1's.
  const std::string head = std::string(kPlaneStart) + "1" + "01" + "0000000000000011" + "0000000011" + "0000000000" + "0000000000";
  expect_error(stream_of(head + "111111111" + "0000000" + std::string(64, '0')), ErrorKind::kInvalidCode,
               "delta_x_len_vlc", 0, 113);
  // node 1: dx = −1 takes x below 0.
  expect_error(stream_of(head + "010 0" + "00" + "00" + "00" + std::string(64, '0')), ErrorKind::kOutOfRange, "delta_x",
               0, 116);
  // node 1: dx = +1023 then +1 takes x past 1023 at node 2.
  expect_error(stream_of(head + "11111110 1111111111" + "00" + "010 1" + "00" + "0000" + std::string(64, '0')),
               ErrorKind::kOutOfRange, "delta_x", 0, 113 + 18 + 2 + 3);
}

TEST(Errors, TrailingDataAfterTheEndCode) {
  expect_error(stream_of(uniform_plane_bits() + kEnd + "00000000"), ErrorKind::kTrailingData, "mesh_object_end_code",
               kNoPlane, 144);
}

TEST(Errors, GarbageWhereAStartCodeShouldBe) {
  expect_error(stream_of(uniform_plane_bits() + "00000000 00000000 00000001 10111111"), ErrorKind::kMissingStartCode,
               "mesh_object_end_code", kNoPlane, 112);
  expect_error(test::bytes_from_bits("00000000 00000000 00000001 10111101"), ErrorKind::kMissingStartCode,
               "mesh_object_start_code", kNoPlane, 0);
}

TEST(Errors, MissingEndCodeIsAWarning) {
  const std::vector<uint8_t> stream = stream_of(uniform_plane_bits());
  Decoder decoder(stream);
  EXPECT_TRUE(decoder.next());
  EXPECT_FALSE(decoder.next());
  EXPECT_FALSE(decoder.has_end_code());
  ASSERT_EQ(decoder.warnings().size(), 1u);
}

// Every truncation of a real stream is an error or, exactly at a plane
// boundary, a missing end code; never a crash.
TEST(Errors, EveryTruncationIsHandled) {
  std::vector<MeshPlane> planes{uniform_plane(5, 5, 9, 9, 2)};
  test::Random random(3);
  for (int k = 0; k < 3; ++k) {
    std::vector<Point> next = planes.back().nodes;
    for (Point& p : next) p.x += random.uniform(-100, 100);
    planes.push_back(inter_plane(next));
  }
  const std::vector<uint8_t> full = encode(planes).stream;
  int warnings = 0;
  for (size_t size = 0; size < full.size(); ++size) {
    const std::vector<uint8_t> cut(full.begin(), full.begin() + static_cast<std::ptrdiff_t>(size));
    const std::optional<Error> error = decode_error(cut);
    if (!error) {
      ++warnings;
      continue;
    }
    EXPECT_TRUE(error->kind() == ErrorKind::kTruncated || error->kind() == ErrorKind::kMissingStartCode)
        << size << ": " << error->what();
  }
  EXPECT_EQ(warnings, 4);  // cut right after each of the four planes
}

TEST(Errors, RandomCorruptionNeverCrashes) {
  std::vector<MeshPlane> planes{uniform_plane(6, 6, 9, 9, 1)};
  std::vector<Point> next = planes[0].nodes;
  for (Point& p : next) p.y += 7;
  planes.push_back(inter_plane(next));
  const std::vector<uint8_t> full = encode(planes).stream;
  test::Random random(11);
  for (int trial = 0; trial < 2000; ++trial) {
    std::vector<uint8_t> bad = full;
    const int flips = 1 + static_cast<int>(random.next() % 4);
    for (int f = 0; f < flips; ++f) bad[random.next() % bad.size()] ^= static_cast<uint8_t>(1u << (random.next() % 8));
    decode_error(bad);  // must return, with or without an error
  }
}

TEST(Errors, MessageNamesPlaneElementAndOffset) {
  const std::optional<Error> error = decode_error(stream_of(uniform_plane_bits("11") + kEnd));
  ASSERT_TRUE(error);
  EXPECT_EQ(std::string(error->what()), "plane 0, mesh_type_code at bit 65: reserved value");
}

// A Delaunay I-plane of these nodes (no geometry check on writing), and
// the bit where each node's first element starts.
std::vector<uint8_t> delaunay_stream(const std::vector<Point>& nodes, uint32_t boundary, std::vector<int64_t>& node_bits) {
  syntax::MeshObjectWriter writer;
  MeshObjectPlane plane;
  plane.new_mesh_flag = 1;
  plane.geometry.mesh_type_code = kMeshTypeDelaunay;
  DelaunayGeometry& g = plane.geometry.delaunay;
  g.nr_of_mesh_nodes = static_cast<uint32_t>(nodes.size());
  g.nr_of_boundary_nodes = boundary;
  g.node0_x = static_cast<uint32_t>(nodes[0].x);
  g.node0_y = static_cast<uint32_t>(nodes[0].y);
  int64_t bit = 32 + 32 + 1 + 2 + 16 + 10;  // object and plane start codes, flag, type, counts
  node_bits = {bit};
  bit += 20;
  for (size_t i = 1; i < nodes.size(); ++i) {
    node_bits.push_back(bit);
    const NodeDelta d{delta_code(nodes[i].x - nodes[i - 1].x), delta_code(nodes[i].y - nodes[i - 1].y)};
    for (const DeltaCode& c : {d.x, d.y}) bit += delta_length_table().code(c.length).length + c.length;
    g.deltas.push_back(d);
  }
  writer.write(plane);
  return writer.finish();
}

TEST(Errors, GeometryErrorsNamingANodeArePlacedAtThatNode) {
  struct Case {
    std::vector<Point> nodes;
    uint32_t boundary;
    int node;  // -1: the plane's start code
  } cases[] = {
      {{{0, 0}, {0, 100}, {100, 100}, {100, 0}, {50, 50}, {60, 40}, {50, 50}}, 4, 6},  // coincident: the later
      {{{50, 50}, {0, 100}, {100, 100}, {100, 0}}, 4, 3},                              // the top-left node
      {{{0, 0}, {0, 100}, {100, 100}, {100, 0}, {150, 50}}, 4, 4},                     // outside the boundary
      {{{0, 0}, {0, 100}, {100, 100}, {100, 0}, {100, 50}}, 4, 4},                     // on a boundary edge
      {{{0, 0}, {0, 200}, {0, 100}, {100, 50}}, 4, 1},                                 // a fold
      {{{0, 0}, {100, 0}, {100, 100}, {0, 100}}, 4, -1},                               // clockwise
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(testing::Message() << "case with " << c.nodes.size() << " nodes, node " << c.node);
    std::vector<int64_t> node_bits;
    const std::vector<uint8_t> stream = delaunay_stream(c.nodes, c.boundary, node_bits);
    expect_error(stream, ErrorKind::kGeometry, "MeshGeometry", 0, c.node < 0 ? 32 : node_bits[static_cast<size_t>(c.node)]);
  }
}

}  // namespace
}  // namespace m4mesh
