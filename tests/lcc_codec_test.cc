// The cloth codec (codec_id 3) through the container: quality, modes,
// a rest-shape reference, the quality target, damaged streams.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <optional>

#include "common/parallel.h"
#include "decoder/mesh3d/container_decoder.h"
#include "encoder/mesh3d/container_encoder.h"
#include "mesh3d/lcc.h"
#include "mesh3d/metrics.h"
#include "tests/test_util.h"

namespace m4mesh {
namespace {

namespace fs = std::filesystem;

// A sheet whose rows roll up a little more every frame: nearly isometric.
MeshSequence rolling_sheet(int frames, int n) {
  MeshSequence s;
  auto at = [n](int i, int j) { return static_cast<NodeIndex>(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      s.faces.push_back({{at(i, j), at(i + 1, j), at(i + 1, j + 1)}});
      s.faces.push_back({{at(i, j), at(i + 1, j + 1), at(i, j + 1)}});
    }
  s.vertex_count = static_cast<uint32_t>((n + 1) * (n + 1));
  for (int f = 0; f < frames; ++f) {
    const double curvature = 0.4 * f;  // radius 1 / curvature
    std::vector<Vec3> frame;
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) {
        const double u = static_cast<double>(i) / n * 2, v = static_cast<double>(j) / n * 2;
        frame.push_back(curvature == 0 ? Vec3{u, 0, v}
                                       : Vec3{std::sin(u * curvature) / curvature, (1 - std::cos(u * curvature)) / curvature, v});
      }
    s.frames.push_back(std::move(frame));
  }
  return s;
}

Encode3dOptions lcc(CodecOptionValues values = {}) {
  Encode3dOptions options;
  options.codec = "lcc";
  options.codec_options = std::move(values);
  return options;
}

TEST(LccCodec, RoundTripsWithASmallKgErrorThatFallsWithMoreBits) {
  const MeshSequence s = rolling_sheet(8, 16);
  double previous = 1e9;
  for (const char* bits : {"4", "7", "10"}) {
    const MeshSequence decoded = decode_mesh3d(encode_mesh3d(s, lcc({{"theta-bits", bits}})).stream);
    const double kg = kg_error(s, decoded);
    EXPECT_LT(kg, previous) << bits << " angle bits";
    previous = kg;
  }
  EXPECT_LT(previous, 0.05);
}

TEST(LccCodec, TheTargetIsReachedAndPrinted) {
  const MeshSequence s = rolling_sheet(6, 12);
  for (double target : {0.5, 0.05}) {
    const Encode3dResult r = encode_mesh3d(s, lcc({{"target-kg", std::to_string(target)}}));
    EXPECT_LE(kg_error(s, decode_mesh3d(r.stream)), target);
    EXPECT_EQ(r.statistics.back().first, "KG error of the closed loop");
    EXPECT_DOUBLE_EQ(r.statistics.back().second, kg_error(s, decode_mesh3d(r.stream)));
  }
}

// Stream mode: a frame unit decodes from the reference alone, so a stream
// of the base mesh and frame k's unit (relabelled frame 1) gives frame k.
TEST(LccCodec, StreamModeFramesDecodeAlone) {
  const MeshSequence s = rolling_sheet(5, 10);
  for (const char* mode : {"stream", "download"}) {
    Encode3dOptions options = lcc({{"mode", mode}});
    options.hashes = false;
    const std::vector<uint8_t> stream = encode_mesh3d(s, options).stream;
    const MeshSequence all = decode_mesh3d(stream);
    ContainerParts parts = split_container(stream);
    parts.object_payload[13] = 2;  // frame_count (u32 at byte 10) = 2
    std::vector<uint8_t> unit = parts.units[4].payload;
    unit[4] = 1;
    ContainerWriter writer;
    writer.object(parts.object_payload);
    writer.unit(parts.units[0].payload);
    writer.unit(unit);
    const std::vector<uint8_t> cut = writer.finish();
    if (std::string(mode) == "stream") {
      EXPECT_EQ(decode_mesh3d(cut).frames[1], all.frames[4]);
    } else {  // the contexts of frames 1 … 3 are missing: an error, or another frame
      try {
        EXPECT_NE(decode_mesh3d(cut).frames[1], all.frames[4]);
      } catch (const Error&) {
      }
    }
  }
}

TEST(LccCodec, RestShapeReferenceCodesFrameZeroToo) {
  MeshSequence s = rolling_sheet(4, 8);
  MeshSequence rolled = s;
  rolled.frames.erase(rolled.frames.begin());
  const fs::path rest = fs::temp_directory_path() / "m4mesh-lcc-rest.m4seq";
  MeshSequence flat = s;
  flat.frames.resize(1);
  write_binary_sequence(flat, rest.string());
  const Encode3dResult r = encode_mesh3d(rolled, lcc({{"reference", rest.string()}, {"theta-bits", "9"}}));
  fs::remove(rest);
  const MeshSequence decoded = decode_mesh3d(r.stream);
  ASSERT_EQ(decoded.frames.size(), rolled.frames.size());
  EXPECT_LT(kg_error(rolled, decoded), 0.1);
  Mesh3dDecoder decoder(r.stream);
  ASSERT_TRUE(decoder.next_unit());
  EXPECT_TRUE(decoder.unit().frames.empty());  // the rest shape is no frame
}

// Temporal prediction changes the residuals, not the quantized values: the
// decoded frames are those without it, bit for bit, from fewer bytes on a
// smooth sequence, and the units come out of display order.
TEST(LccCodec, TemporalPredictionDecodesTheSameFramesFromFewerBytes) {
  const MeshSequence s = rolling_sheet(19, 12);
  for (const char* mode : {"stream", "download"}) {
    const Encode3dResult plain = encode_mesh3d(s, lcc({{"mode", mode}, {"theta-bits", "8"}}));
    const Encode3dResult temporal = encode_mesh3d(s, lcc({{"mode", mode}, {"theta-bits", "8"}, {"temporal", "1"}, {"gop", "8"}}));
    EXPECT_EQ(decode_mesh3d(temporal.stream).frames, decode_mesh3d(plain.stream).frames) << mode;
    EXPECT_LT(temporal.frame_bytes(), plain.frame_bytes()) << mode;
    Mesh3dDecoder decoder(temporal.stream);
    std::vector<uint32_t> unit_frames;
    while (decoder.next_unit())
      for (uint32_t f : decoder.unit().frames) unit_frames.push_back(f);
    EXPECT_EQ(unit_frames, (std::vector<uint32_t>{0, 1, 9, 5, 3, 2, 4, 7, 6, 8, 17, 13, 11, 10, 12, 15, 14, 16, 18}));
  }
}

TEST(LccFrameOrder, AnchorsThenMidpointsEachFrameOnceAfterItsReferences) {
  LccFrameOrder order(1, 12, 4);
  std::vector<uint32_t> frames, seen(12, 0);
  while (!order.done()) {
    const LccCodedFrame coded = order.next();
    if (!coded.anchor()) {
      EXPECT_TRUE(seen[coded.left] && seen[coded.right]) << coded.frame;
      EXPECT_EQ(coded.frame, coded.left + (coded.right - coded.left) / 2);
    }
    seen[coded.frame] = 1;
    frames.push_back(coded.frame);
  }
  EXPECT_EQ(frames, (std::vector<uint32_t>{1, 5, 3, 2, 4, 9, 7, 6, 8, 11, 10}));
  LccFrameOrder plain(0, 3, 0), endless(1, 0, 0);
  for (uint32_t f = 0; f < 3; ++f) EXPECT_EQ(plain.next().frame, f);
  EXPECT_TRUE(plain.done());
  for (uint32_t f = 1; f < 100; ++f) EXPECT_EQ(endless.next().frame, f);
  EXPECT_FALSE(endless.done());
}

// The predictions of the first group of frames: anchors from the reference
// (stream) or the previous anchor (download), midpoints from their two
// frames, θ along the shorter arc.
TEST(LccPredictor, PredictsAnchorsAndMidpoints) {
  const MeshSequence s = rolling_sheet(1, 2);
  const LccOrder order = lcc_order(s.faces, s.vertex_count);
  std::vector<IntPoint3> reference(s.vertex_count, IntPoint3{7, 8, 9});
  auto frame = [&](int32_t direct, int32_t t, int32_t radius) {
    LccIndices indices;
    indices.direct.assign(3 * order.direct.size(), direct);
    for (size_t k = 0; k < order.steps.size(); ++k) indices.steps.insert(indices.steps.end(), {t, radius, -radius});
    return indices;
  };
  for (uint32_t mode : {kLccStreamMode, kLccDownloadMode}) {
    LccHeader header;
    header.theta_bits = 3;  // t in [−8, 8)
    header.mode = mode;
    LccPredictor predictor(header, order, reference);
    const LccCodedFrame first{1}, second{5}, middle{3, 1, 5};
    EXPECT_EQ(predictor.predict(first).direct[0], 7);
    EXPECT_EQ(predictor.predict(first).steps[0], 0);
    predictor.keep(first, frame(100, 7, 3));
    EXPECT_EQ(predictor.predict(second).direct[1], mode == kLccDownloadMode ? 100 : 8);
    predictor.keep(second, frame(103, -7, -2));
    const LccIndices& p = predictor.predict(middle);
    EXPECT_EQ(p.direct[0], 101);  // ⌊203 / 2⌋
    EXPECT_EQ(p.steps[0], -8);    // 7 and −7 meet across ±π, not at 0
    EXPECT_EQ(p.steps[1], 0);     // ⌊(3 − 2) / 2⌋
    EXPECT_EQ(p.steps[2], -1);    // ⌊(−3 + 2) / 2⌋
    predictor.keep(middle, frame(0, 0, 0));
    predictor.keep(LccCodedFrame{9}, frame(0, 0, 0));
    EXPECT_EQ(predictor.predict(LccCodedFrame{7, 5, 9}).direct[0], 51);  // frame 5 kept, frames 1 and 3 dropped
    EXPECT_THROW(predictor.predict(LccCodedFrame{2, 1, 3}), Error);
  }
}

TEST(LccCodec, BadOptionsAreUsageErrors) {
  const MeshSequence s = rolling_sheet(2, 4);
  EXPECT_THROW(encode_mesh3d(s, lcc({{"mode", "fast"}})), Error);
  EXPECT_THROW(encode_mesh3d(s, lcc({{"theta-bits", "16"}})), Error);
  EXPECT_THROW(encode_mesh3d(s, lcc({{"reference", "/nonexistent/rest.obj"}})), Error);
}

// Frames of 4096 steps and more place their vertices while their symbols
// are decoded, on two cores; on one, after them: the same positions.
TEST(LccCodec, LargeFramesDecodeTheSameOnOneCore) {
  const std::vector<uint8_t> stream = encode_mesh3d(rolling_sheet(3, 70), lcc()).stream;
  const MeshSequence decoded = decode_mesh3d(stream);
  std::optional<MeshSequence> alone;
  if (!test::on_one_core([&] {
        EXPECT_EQ(available_cores(), 1u);
        alone = decode_mesh3d(stream);
      }))
    GTEST_SKIP() << "no thread affinity here";
  ASSERT_TRUE(alone);
  EXPECT_EQ(alone->frames, decoded.frames);
  EXPECT_GE(decoded.vertex_count, 3 + 4096u);  // the root triangle, then 4096 steps
}

TEST(LccCodec, CorruptAndTruncatedStreamsFailCleanly) {
  EXPECT_GT(test::decode_damaged_mesh3d(encode_mesh3d(rolling_sheet(4, 6), lcc()).stream, 5, 33), 0);
  EXPECT_GT(test::decode_damaged_mesh3d(encode_mesh3d(rolling_sheet(7, 6), lcc({{"temporal", "1"}, {"gop", "4"}})).stream, 5, 33), 0);
}

}  // namespace
}  // namespace m4mesh
