// bfs3d (codec_id 1): its traversal, round trips with both predictions,
// seeking, determinism and bad streams; on the cow, fewer bits than Draco
// coding every frame.
#include <gtest/gtest.h>

#include <filesystem>

#include "anchors/draco_reference.h"
#include "common/error.h"
#include "decoder/mesh3d/container_decoder.h"
#include "encoder/mesh3d/container_encoder.h"
#include "mesh3d/bfs3d.h"
#include "mesh3d/metrics.h"
#include "mesh3d/quantization.h"
#include "mesh3d/sequence.h"
#include "syntax/mesh3d/bfs3d.h"
#include "tests/test_util.h"

namespace m4mesh {
namespace {

namespace fs = std::filesystem;

using test::test_sequence;
using test::verifying;

TEST(Traversal3d, EveryVertexOnceAndPredictorsBeforeUse) {
  const MeshSequence s = test_sequence(1, 4);
  const MotionOrder3d order = bfs3d_order(s.faces, s.vertex_count);
  ASSERT_EQ(order.node.size(), s.vertex_count);
  std::set<NodeIndex> coded;
  for (size_t k = 0; k < order.node.size(); ++k) {
    for (NodeIndex p : {order.pred_a[k], order.pred_b[k], order.pred_c[k]})
      ASSERT_TRUE(p == order.zero_slot || coded.count(p)) << "predictor " << p << " of node " << order.node[k];
    ASSERT_TRUE(coded.insert(order.node[k]).second);
  }
  EXPECT_EQ(order.node.front(), s.faces[0].v[0]);
  EXPECT_EQ(order.node.back(), s.vertex_count - 1);  // the isolated vertex comes last
}

void expect_round_trip(const MeshSequence& s, const Encode3dOptions& options, int bits) {
  const Encode3dResult encoded = encode_mesh3d(s, options);
  Mesh3dDecoder decoder(encoded.stream, verifying());
  const Grid grid = Grid::over(s.frames[0], bits);
  uint32_t frames = 0;
  while (decoder.next_frame()) {
    ASSERT_EQ(decoder.frame_index(), frames);
    for (uint32_t i = 0; i < s.vertex_count; ++i) {
      IntPoint3 q;
      ASSERT_TRUE(grid.quantize(s.frames[frames][i], q));
      for (int axis = 0; axis < 3; ++axis) ASSERT_EQ(decoder.positions()[i][axis], grid.position(axis, q[axis]));
    }
    ++frames;
  }
  EXPECT_EQ(frames, s.frames.size());
  for (uint32_t f = 0; f < frames; ++f) EXPECT_TRUE(decoder.hash_result(f).value_or(false)) << "frame " << f;
  EXPECT_TRUE(decoder.has_end_code());
  uint64_t total = encoded.other_bytes;
  for (uint64_t bytes : encoded.unit_bytes) total += bytes;
  EXPECT_EQ(total, encoded.stream.size());
}

TEST(Bfs3d, RoundTripsWithBothPredictions) {
  const MeshSequence s = test_sequence(6, 6);
  for (bool parallelogram : {false, true})
    for (int bits : {8, 12, 16}) {
      Encode3dOptions options;
      options.codec_options = {{"bits", std::to_string(bits)}, {"parallelogram", parallelogram ? "1" : "0"}};
      expect_round_trip(s, options, bits);
    }
}

// Seeking starts at the last intra refresh at or before the frame asked
// for, and decodes from there exactly as a decoding from the start does.
TEST(Bfs3d, SeekStartsAtTheLastIntraRefresh) {
  const MeshSequence s = test_sequence(12, 8);
  Encode3dOptions options;
  options.codec_options["intra-period"] = "4";
  options.hash_group = 3;
  const std::vector<uint8_t> stream = encode_mesh3d(s, options).stream;
  std::vector<std::vector<Float3>> all;
  for (Mesh3dDecoder whole(stream); whole.next_frame();) all.push_back(whole.positions());
  Mesh3dDecoder decoder(stream, verifying());
  EXPECT_EQ(decoder.seek(9), 8u);
  uint32_t frames = 0;
  while (decoder.next_frame()) {
    ASSERT_EQ(decoder.frame_index(), 8 + frames);
    EXPECT_EQ(decoder.positions(), all[decoder.frame_index()]);
    ++frames;
  }
  EXPECT_EQ(frames, 4u);
  EXPECT_FALSE(decoder.first_mismatch().has_value());
  EXPECT_FALSE(decoder.hash_result(5).has_value());  // before the refresh: never decoded, never checked
  Mesh3dDecoder early(stream);
  EXPECT_EQ(early.seek(3), 0u);  // no refresh before frame 4
}

// Frames are hashed in batches after they are handed out: every group
// size, below, at and above a batch, checks every frame as decoded.
TEST(Bfs3d, EveryHashGroupSizeChecksTheFramesAsDecoded) {
  const MeshSequence s = test_sequence(40, 9);
  for (const uint32_t group : {1u, 3u, 16u, 17u, 40u}) {
    Encode3dOptions options;
    options.hash_group = group;
    const std::vector<uint8_t> stream = encode_mesh3d(s, options).stream;
    Mesh3dDecoder decoder(stream, verifying());
    std::vector<std::vector<Float3>> handed_out;
    while (decoder.next_frame()) handed_out.push_back(decoder.positions());
    ASSERT_EQ(handed_out.size(), s.frames.size());
    for (uint32_t f = 0; f < s.frames.size(); ++f) EXPECT_TRUE(decoder.hash_result(f).value_or(false)) << "group " << group << ", frame " << f;
    Decode3dOptions unhashed;
    unhashed.hashes = HashCheck::kSkip;
    Mesh3dDecoder plain(stream, unhashed);
    for (uint32_t f = 0; plain.next_frame(); ++f) EXPECT_EQ(handed_out[f], plain.positions()) << "group " << group << ", frame " << f;
  }
}

TEST(Bfs3d, EncoderIsDeterministicAndHashesCatchChanges) {
  const MeshSequence s = test_sequence(4, 7);
  const std::vector<uint8_t> stream = encode_mesh3d(s).stream;
  EXPECT_EQ(encode_mesh3d(s).stream, stream);
  // The same units under a header whose grid origin moved by one binary32 step:
  // the stream still decodes, but no frame matches its hash any more.
  const ContainerParts parts = split_container(stream);
  auto [header, codec] = read_headers<Bfs3dHeader>(parts);
  codec.origin[0] += 1;
  BitWriter writer;
  syntax::WriteIO out(writer);
  syntax::describe(out, header);
  syntax::describe(out, codec);
  ContainerWriter moved;
  moved.object(writer.take_bytes());
  for (const ContainerUnit& unit : parts.units) moved.unit(unit.payload);
  const std::vector<uint8_t> moved_stream = moved.finish();
  Mesh3dDecoder decoder(moved_stream, verifying());
  int mismatches = 0;
  while (decoder.next_frame()) {
  }
  for (uint32_t f = 0; f < s.frames.size(); ++f) mismatches += !decoder.hash_result(f).value_or(true);
  EXPECT_EQ(mismatches, 4);
}

TEST(Bfs3d, CorruptAndTruncatedStreamsFailCleanly) {
  const MeshSequence s = test_sequence(3, 8);
  test::decode_damaged_mesh3d(encode_mesh3d(s).stream, 7, 8);
}

const fs::path kData = fs::path(M4MESH_SOURCE_DIR) / ".." / "shared" / "data";

TEST(RealData, CowAt12BitsBeatsDracoPerFrameWithSmallKgError) {
  if (!fs::exists(kData / "pcow")) GTEST_SKIP() << "../shared/data/pcow is absent";
  MeshSequence cow = load_sequence((kData / "pcow").string());
  cow.frames.resize(20);
  Encode3dOptions options;
  const Encode3dResult encoded = encode_mesh3d(cow, options);
  const MeshSequence decoded = decode_mesh3d(encoded.stream);
  EXPECT_LE(kg_error(cow, decoded), 0.05);
  const double ours = 8.0 * static_cast<double>(encoded.frame_bytes()) / (cow.vertex_count * 19.0);
  double draco = 0;
  for (size_t f = 1; f < cow.frames.size(); ++f) {
    std::vector<std::array<float, 3>> p;
    for (const Vec3& v : cow.frames[f]) p.push_back({static_cast<float>(v.x), static_cast<float>(v.y), static_cast<float>(v.z)});
    draco += 8.0 * static_cast<double>(draco_frame_size(cow.faces, p, 12)) / cow.vertex_count;
  }
  draco /= 19.0;
  EXPECT_LT(ours, draco) << "bfs3d " << ours << " bits/vertex/frame, Draco " << draco;
}

}  // namespace
}  // namespace m4mesh
