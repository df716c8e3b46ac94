// A complete stream worked out by hand from the specification (not from
// the code): a 3×3 uniform mesh, then two P-planes.
#include <gtest/gtest.h>

#include "conformance/suite.h"
#include "decoder/mesh_object_decoder.h"
#include "encoder/mesh_object_encoder.h"
#include "tests/test_util.h"

namespace m4mesh {
namespace {

// Mesh: cols = rows = 3, dx = dy = 16, split '00'. Nodes (§5, index r·3 + c):
//   0 (0,0)   1 (16,0)   2 (32,0)
//   3 (0,16)  4 (16,16)  5 (32,16)
//   6 (0,32)  7 (16,32)  8 (32,32)
// Triangles, every rectangle TL–BR: (0,1,4) (0,4,3) (1,2,5) (1,5,4)
// (3,4,7) (3,7,6) (4,5,8) (4,8,7).
//
// Traversal (§7.1): t = 0, u = 1, initial ⟨0,1,4⟩.
//   pop ⟨0,1,4⟩: code 4 from (0,1); right (0,4) → ⟨0,4,3⟩; left (1,4) → ⟨4,1,5⟩
//   pop ⟨0,4,3⟩: code 3 from (0,4); right (0,3) boundary; left (4,3) → ⟨3,4,7⟩
//   pop ⟨4,1,5⟩: code 5 from (4,1); right (4,5) → ⟨4,5,8⟩; left (1,5) → ⟨5,1,2⟩
//   pop ⟨3,4,7⟩: code 7 from (3,4); right (3,7) → ⟨3,7,6⟩; left (4,7) → ⟨7,4,8⟩
//   pop ⟨4,5,8⟩: code 8 from (4,5); right (4,8) labelled; left (5,8) boundary
//   pop ⟨5,1,2⟩: code 2 from (5,1)
//   pop ⟨3,7,6⟩: code 6 from (3,7)
//   pop ⟨7,4,8⟩: 8 done
// Order 0, 1, 4, 3, 5, 7, 8, 2, 6.
//
// Plane 1, range 1 ([−32, 31], r_size 0): v0 = (1,0), v1 = (1,0), v4 = (2,1),
// v3 = (0,−2), v7 = (−3,0), others 0.
//   0: w (0,0)  d (1,0)   '1' 010 1
//   1: w (1,0)  d (0,0)   '1' 1 1           (non-zero vector: flag 1)
//   4: w ((1+1+1)>>1, (0+0+1)>>1) = (1,0), d (1,1)        '1' 010 010
//   3: w ((1+2+1)>>1, (0+1+1)>>1) = (2,1), d (−2,−3)      '1' 0011 00011
//   5: '0'
//   7: w ((0+2+1)>>1, (−2+1+1)>>1) = (1,0), d (−4,0)      '1' 0000111 1
//   8, 2, 6: '0' '0' '0'
// 41 bits after the start code, so 7 stuffing bits.
//
// Plane 2, range 2 ([−64, 63], f = 2): v0 = (40,−1), v1 = (−40,0), v4 = (0,63).
//   0: d (40,−1): m = ((39)>>1)+1 = 20, res 39&1 = 1;  m = −1, res 0
//      '1' 0000001000 0 | 1 | 01 1 | 0
//   1: w = v0 = (40,−1); d = (−80, 1) → −80 + 128 = 48: m = (47>>1)+1 = 24, res 1;  d_y 1: m 1, res 0
//      '1' 0000000100 0 | 1 | 01 0 | 0
//   4: w = ((40−40+1)>>1, (−1+0+1)>>1) = (0,0); d (0,63): m 0;  m = (62>>1)+1 = 32, res 0
//      '1' 1 | 000000000010 0 | 0
//   3, 5, 7, 8, 2, 6: six '0'
// 59 bits after the start code, so 5 stuffing bits.
constexpr const char* kHandStream =
    "00000000 00000000 00000001 10111100"  // mesh_object_start_code
    "00000000 00000000 00000001 10111101"  // plane 0: start code
    "1 00 0000000011 0000000011 00010000 00010000 00"  // I, uniform, 3, 3, 16, 16, split 00
    "0111111"                                          // stuffing (41 bits → 48)
    "00000000 00000000 00000001 10111101"  // plane 1
    "0 01"                                  // P, motion_range_code 1
    "1 010 1"  "1 1 1"  "1 010 010"  "1 0011 00011"  "0"  "1 0000111 1"  "0 0 0"
    "0111111"                               // stuffing
    "00000000 00000000 00000001 10111101"  // plane 2
    "0 10"                                  // P, motion_range_code 2
    "1 00000010000 1 011 0"  "1 00000001000 1 010 0"  "1 1 0000000000100 0"  "0 0 0 0 0 0"
    "01111"                                 // stuffing
    "00000000 00000000 00000001 10110001";  // mesh_object_end_code

// The planes of the worked example (shared with the conformance suite's p01).
std::vector<MeshPlane> hand_planes() { return hand_stream_planes(); }

TEST(HandStream, EncoderWritesTheHandComputedBits) {
  const std::vector<uint8_t> expected = test::bytes_from_bits(kHandStream);
  ASSERT_EQ(expected.size(), 40u);
  const EncodeResult result = encode(hand_planes());
  EXPECT_EQ(test::bits_of(result.stream), test::bits_of(expected));
}

TEST(HandStream, DecoderReproducesThePositions) {
  const std::vector<MeshPlane> planes = hand_planes();
  const std::vector<uint8_t> stream = test::bytes_from_bits(kHandStream);
  Decoder decoder(stream);
  size_t k = 0;
  while (decoder.next()) {
    ASSERT_LT(k, planes.size());
    EXPECT_EQ(std::vector<Point>(decoder.nodes().begin(), decoder.nodes().end()), planes[k].nodes) << "plane " << k;
    ++k;
  }
  EXPECT_EQ(k, 3u);
  EXPECT_TRUE(decoder.has_end_code());
  EXPECT_TRUE(decoder.warnings().empty());
}

TEST(HandStream, MotionOrderMatchesTheHandTraversal) {
  const UniformParams params{3, 3, 16, 16, 0};
  const MeshTopology mesh = uniform_topology(params);
  const MotionOrder order = method2_order(mesh.triangles, mesh.neighbours, 9, 0, 1);
  EXPECT_EQ(order.node, (std::vector<NodeIndex>{0, 1, 4, 3, 5, 7, 8, 2, 6}));
  EXPECT_EQ(order.pred_a, (std::vector<NodeIndex>{9, 0, 0, 0, 4, 3, 4, 5, 3}));
  EXPECT_EQ(order.pred_b, (std::vector<NodeIndex>{9, 0, 1, 4, 1, 4, 5, 1, 7}));
}

}  // namespace
}  // namespace m4mesh
