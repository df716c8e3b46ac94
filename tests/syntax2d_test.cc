// Hand-computed bit strings for each syntax structure, read and written
// through the one description, and the bit counter and tracer over it.
#include <gtest/gtest.h>

#include <sstream>

#include "encoder/mesh_object_encoder.h"
#include "syntax/describe.h"
#include "syntax/io.h"
#include "syntax/mesh_object.h"
#include "tests/test_util.h"

namespace m4mesh {
namespace {

// Writes a structure and returns its bits, padded with zeros to a byte.
template <class S, class... Context>
std::string written_bits(S structure, Context... context) {
  BitWriter w;
  syntax::WriteIO io(w);
  syntax::describe(io, structure, context...);
  w.write(0, static_cast<int>((8 - w.position() % 8) % 8));
  return test::bits_of(w.bytes());
}

template <class S, class... Context>
uint64_t bit_length(S structure, Context... context) {
  syntax::CountIO io;
  syntax::describe(io, structure, context...);
  return io.bits();
}

template <class S, class... Context>
S read_back(const std::string& bits, Context... context) {
  const std::vector<uint8_t> bytes = test::bytes_from_bits(bits);
  BitReader r(bytes.data(), bytes.size());
  syntax::ReadIO io(r);
  S structure;
  syntax::describe(io, structure, context...);
  return structure;
}

std::string pad(std::string bits) {
  while (bits.size() % 8) bits += '0';
  return bits;
}

TEST(Syntax, UniformGeometry) {
  MeshGeometry g;
  g.mesh_type_code = kMeshTypeUniform;
  g.uniform = UniformGeometry{1023, 2, 255, 1, 2};
  // '00' | 1111111111 | 0000000010 | 11111111 | 00000001 | '10'
  const std::string expected = "00" "1111111111" "0000000010" "11111111" "00000001" "10";
  EXPECT_EQ(written_bits(g), pad(expected));
  EXPECT_EQ(bit_length(g), expected.size());
  const MeshGeometry back = read_back<MeshGeometry>(pad(expected));
  EXPECT_EQ(back.uniform.nr_of_mesh_nodes_hori, 1023u);
  EXPECT_EQ(back.uniform.mesh_rect_size_hori, 255u);
  EXPECT_EQ(back.uniform.triangle_split_code, 2u);
}

TEST(Syntax, DelaunayGeometry) {
  MeshGeometry g;
  g.mesh_type_code = kMeshTypeDelaunay;
  DelaunayGeometry& d = g.delaunay;
  d.nr_of_mesh_nodes = 3;
  d.nr_of_boundary_nodes = 3;
  d.node0_x = 5;
  d.node0_y = 1023;
  // node 1: dx = −1 (L 1, '0'), dy = 0 (L 0); node 2: dx = +3 (L 2, '11'), dy = −1000 (L 10).
  d.deltas = {NodeDelta{delta_code(-1), delta_code(0)}, NodeDelta{delta_code(3), delta_code(-1000)}};
  // −1000 with L 10: −1000 + 1023 = 23 = 0000010111.
  const std::string expected =
      "01" "0000000000000011" "0000000011" "0000000101" "1111111111"
      "010" "0" "00"
      "011" "11" "11111110" "0000010111";
  EXPECT_EQ(written_bits(g), pad(expected));
  EXPECT_EQ(bit_length(g), expected.size());
  const MeshGeometry back = read_back<MeshGeometry>(pad(expected));
  ASSERT_EQ(back.delaunay.deltas.size(), 2u);
  EXPECT_EQ(delta_value(back.delaunay.deltas[1].y), -1000);
  EXPECT_EQ(back.delaunay.node0_y, 1023u);
}

TEST(Syntax, MeshMotionWithResiduals) {
  MeshMotion m;
  m.motion_range_code = 3;  // r_size 2
  // Node 0: m_x = −5, res 3; m_y = 0 (no residual). Node 1: flag 0. Node 2: m_x 32, res 0; m_y 1, res 2.
  m.nodes = {NodeMotion{1, -5, 3, 0, 0}, NodeMotion{}, NodeMotion{1, 32, 0, 1, 2}};
  const std::string expected =
      "11"
      "1" "00001011" "11" "1"
      "0"
      "1" "0000000000100" "00" "010" "10";
  EXPECT_EQ(written_bits(m, 3u), pad(expected));
  EXPECT_EQ(bit_length(m, 3u), expected.size());
  const MeshMotion back = read_back<MeshMotion>(pad(expected), 3u);
  EXPECT_EQ(back.nodes[0].delta_mv_x, -5);
  EXPECT_EQ(back.nodes[0].delta_mv_x_res, 3);
  EXPECT_EQ(back.nodes[1].node_motion_vector_flag, 0);
  EXPECT_EQ(back.nodes[2].delta_mv_y_res, 2);
}

TEST(Syntax, MeshMotionRangeOneHasNoResiduals) {
  MeshMotion m;
  m.motion_range_code = 1;
  m.nodes = {NodeMotion{1, -32, 0, 31, 0}};
  // −32: 000000000010 1; 31: 000000000011 0
  const std::string expected = "01" "1" "0000000000101" "0000000000110";
  EXPECT_EQ(written_bits(m, 1u), pad(expected));
}

TEST(Syntax, WriterRefusesValuesTheSyntaxCannotHold) {
  MeshGeometry g;
  g.uniform = UniformGeometry{1, 2, 16, 16, 0};  // hori < 2
  BitWriter w;
  syntax::WriteIO io(w);
  EXPECT_THROW(syntax::describe(io, g), Error);
  MeshMotion m;
  m.motion_range_code = 2;
  m.nodes = {NodeMotion{1, 3, 2, 0, 0}};  // res 2 needs 2 bits, r_size is 1
  BitWriter w2;
  syntax::WriteIO io2(w2);
  EXPECT_THROW(syntax::describe(io2, m, 1u), Error);
}

TEST(Syntax, WholeObjectRoundTripsThroughStructures) {
  std::vector<MeshPlane> planes{uniform_plane(4, 3, 8, 8, 3)};
  std::vector<Point> moved = planes[0].nodes;
  moved[5].x += 3;
  planes.push_back(inter_plane(moved));
  const std::vector<uint8_t> stream = encode(planes).stream;
  MeshObject object = syntax::read_mesh_object(stream);
  EXPECT_EQ(object.planes.size(), 2u);
  EXPECT_EQ(syntax::write_mesh_object(object), stream);
}

// The tracer prints the same lines whether the stream is written or read.
TEST(Syntax, EncoderAndDecoderTracesAreIdentical) {
  std::vector<MeshPlane> planes{uniform_plane(5, 4, 10, 12, 1)};
  test::Random random(7);
  for (int k = 0; k < 3; ++k) {
    std::vector<Point> next = planes.back().nodes;
    for (Point& p : next) p.x += random.uniform(-40, 40);
    planes.push_back(inter_plane(next));
  }
  std::ostringstream encoder_trace, decoder_trace;
  Trace write_trace(encoder_trace), read_trace(decoder_trace);
  EncoderOptions options;
  options.trace = &write_trace;
  const std::vector<uint8_t> stream = encode(planes, options).stream;
  syntax::read_mesh_object(stream, &read_trace);
  EXPECT_EQ(encoder_trace.str(), decoder_trace.str());
  EXPECT_NE(encoder_trace.str().find("mesh_object_end_code"), std::string::npos);
  EXPECT_NE(encoder_trace.str().find("delta_mv_x_res"), std::string::npos);
}

}  // namespace
}  // namespace m4mesh
