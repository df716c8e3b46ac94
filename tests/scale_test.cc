// Sequences of any length: frame sources that read files frame by frame,
// streams written and read unit by unit, cpca-wpt's segments, quality
// targets searched on a sample of a long sequence.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "common/md5.h"
#include "decoder/mesh3d/container_decoder.h"
#include "encoder/mesh3d/container_encoder.h"
#include "encoder/mesh3d/quality_target.h"
#include "mesh3d/frame_source.h"
#include "mesh3d/metrics.h"
#include "tests/test_util.h"

namespace m4mesh {
namespace {

namespace fs = std::filesystem;

Encode3dOptions codec(const std::string& name, CodecOptionValues values = {}) {
  Encode3dOptions o;
  o.codec = name;
  o.codec_options = std::move(values);
  return o;
}

TEST(FrameSources, FilesReadFrameByFrameGiveTheFramesLoadSequenceGives) {
  const MeshSequence s = test::test_sequence(7, 3);
  const test::TempDir dir;
  const fs::path m4seq = dir / "s.m4seq", pc2 = dir / "s.pc2", folder = dir / "frames";
  write_binary_sequence(s, m4seq.string());
  write_pc2_sequence(s, pc2.string());
  write_obj_frames(s, folder.string());
  for (const fs::path& path : {m4seq, pc2, folder}) {
    const MeshSequence whole = load_sequence(path.string());
    // An in-memory budget of 0 reads every frame from the file as it is asked for.
    const std::unique_ptr<FrameSource> frames = open_sequence(path.string(), false, 0);
    EXPECT_EQ(dynamic_cast<const SequenceSource*>(frames.get()), nullptr) << path;
    EXPECT_EQ(read_all_frames(*frames).frames, whole.frames) << path;
    EXPECT_TRUE(same_faces(frames->faces(), whole.faces)) << path;
    EXPECT_NE(dynamic_cast<const SequenceSource*>(open_sequence(path.string()).get()), nullptr) << path << ": small, read whole";
  }
}

TEST(FrameSources, AFrameFileOfOtherConnectivityIsNamedWhenItIsRead) {
  MeshSequence s = test::test_sequence(3, 1);
  const test::TempDir dir;
  const fs::path folder = dir / "mismatch";
  write_obj_frames(s, folder.string());
  std::vector<Triangle> fewer(s.faces.begin(), s.faces.end() - 1);
  write_obj_frame(s.frames[2], fewer, (folder / obj_frame_name(2)).string());
  const std::unique_ptr<FrameSource> frames = open_sequence(folder.string(), false, 0);
  try {
    frames->scan();
    FAIL() << "a frame of other faces accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(obj_frame_name(2)), std::string::npos) << e.what();
  }
}

TEST(FrameSources, ScanRefusesWhatCheckSequenceRefused) {
  MeshSequence s = test::test_sequence(2, 5);
  s.frames[1][4].y = NAN;
  try {
    SequenceSource(s).scan();
    FAIL() << "a position that is not finite accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("frame 1, vertex 4"), std::string::npos) << e.what();
  }
}

TEST(StreamingContainers, AnOutputGetsTheStreamUnitByUnitAndAFileDecodesAsMemoryDoes) {
  const MeshSequence s = test::test_sequence(9, 2);
  for (const Encode3dOptions& base : {codec("bfs3d"), codec("cpca-wpt", {{"segment-frames", "4"}, {"clusters", "3"}})}) {
    Encode3dOptions o = base;
    const std::vector<uint8_t> whole = encode_mesh3d(s, o).stream;
    std::vector<uint8_t> streamed;
    size_t pieces = 0;
    o.output = [&](std::span<const uint8_t> bytes) {
      streamed.insert(streamed.end(), bytes.begin(), bytes.end());
      ++pieces;
    };
    const Encode3dResult result = encode_mesh3d(s, o);
    EXPECT_TRUE(result.stream.empty());
    EXPECT_EQ(result.stream_bytes, whole.size());
    EXPECT_EQ(streamed, whole) << base.codec;
    EXPECT_GT(pieces, 3u);
    const test::TempDir dir;
    const fs::path file = dir / "stream.m4m";
    std::ofstream(file, std::ios::binary).write(reinterpret_cast<const char*>(whole.data()), static_cast<std::streamsize>(whole.size()));
    Mesh3dDecoder from_file(ContainerSource::open_file(file.string()), test::verifying());
    MeshSequence decoded;
    while (from_file.next_frame()) {
      std::vector<Vec3> frame;
      for (const Float3& p : from_file.positions()) frame.push_back({p[0], p[1], p[2]});
      decoded.frames.push_back(std::move(frame));
    }
    EXPECT_EQ(decoded.frames, decode_mesh3d(whole).frames) << base.codec;
    EXPECT_FALSE(from_file.first_mismatch().has_value());
  }
}

TEST(StreamingContainers, AFileReportsTheFramingErrorsMemoryReports) {
  std::vector<uint8_t> stream = encode_mesh3d(test::test_sequence(3, 4), codec("bfs3d")).stream;
  stream.push_back(0x42);  // after the end code
  const test::TempDir dir;
  const fs::path file = dir / "trailing.m4m";
  std::ofstream(file, std::ios::binary).write(reinterpret_cast<const char*>(stream.data()), static_cast<std::streamsize>(stream.size()));
  const auto error_of = [](const auto& make) -> Error {
    try {
      make();
    } catch (const Error& e) {
      return e;
    }
    return Error(ErrorKind::kStructure, "none", kNoPlane, kNoOffset, "no error");
  };
  const Error in_memory = error_of([&] { Mesh3dDecoder decoder(stream); });
  const Error from_file = error_of([&] { Mesh3dDecoder decoder(ContainerSource::open_file(file.string())); });
  EXPECT_EQ(in_memory.kind(), ErrorKind::kTrailingData);
  EXPECT_EQ(from_file.kind(), in_memory.kind());
  EXPECT_EQ(from_file.bit_offset(), in_memory.bit_offset());
}

TEST(CpcaSegments, EachSegmentMeetsTheTargetAndReleasesItsFramesInOrder) {
  const MeshSequence s = test::test_sequence(14, 6);
  Encode3dOptions o = codec("cpca-wpt", {{"segment-frames", "5"}, {"clusters", "3"}, {"target-kg", "0.5"}});
  o.measure = true;
  const Encode3dResult result = encode_mesh3d(s, o);
  EXPECT_LE(result.kg, 0.5);
  EXPECT_DOUBLE_EQ(kg_error(s, decode_mesh3d(result.stream)), result.kg);
  // Units of segments 0, 5 and 10, in order; each later segment releases the frames before it.
  Mesh3dDecoder decoder(result.stream);
  std::vector<uint32_t> released, segments;
  while (decoder.next_unit()) {
    released.insert(released.end(), decoder.unit().released.begin(), decoder.unit().released.end());
    if (decoder.unit().header.type() == UnitType::kRefinement &&
        (segments.empty() || segments.back() != decoder.unit().header.frame_index))
      segments.push_back(decoder.unit().header.frame_index);
  }
  EXPECT_EQ(segments, (std::vector<uint32_t>{0, 5, 10}));
  EXPECT_EQ(released, (std::vector<uint32_t>{0, 1, 2, 3, 4, 5, 6, 7, 8, 9}));
}

TEST(CpcaSegments, LongerSequencesThanOneSegmentHoldsAreCoded) {
  // 2^22 vertex-frames a segment: 98 vertices take 42,799 frames in one; a segment of 3 over 10 frames here.
  const MeshSequence s = test::test_sequence(10, 7);
  EXPECT_THROW(encode_mesh3d(s, codec("cpca-wpt", {{"segment-frames", "100000"}})), Error);
  const Encode3dResult r = encode_mesh3d(s, codec("cpca-wpt", {{"segment-frames", "3"}}));
  EXPECT_EQ(decode_mesh3d(r.stream).frames.size(), 10u);
}

TEST(QualityTargets, ALongSequenceIsSearchedOnASampleThenCodedWhole) {
  // 98 vertices × 10,800 frames: above the whole search's 2^20 vertex-frames.
  const MeshSequence base = test::test_sequence(24, 8);
  MeshSequence s = base;
  s.frames.clear();
  for (uint32_t f = 0; f < 10800; ++f) s.frames.push_back(base.frames[f % base.frames.size()]);
  std::vector<TargetTrial> trials;
  const Encode3dResult r = encode_to_target(s, codec("bfs3d"), {.kg = 1.0}, [&](const TargetTrial& t) { trials.push_back(t); });
  ASSERT_FALSE(trials.empty());
  for (size_t i = 0; i + 1 < trials.size(); ++i) EXPECT_NE(trials[i].note.find("on a sample of"), std::string::npos) << trials[i].note;
  EXPECT_EQ(trials.back().note, "the whole sequence");
  EXPECT_TRUE(trials.back().meets);
  EXPECT_LE(kg_error(s, decode_mesh3d(r.stream)), 1.0);
  EXPECT_LT(trials.front().vertex_frames, static_cast<double>(kSampleVertexFrames) + 1);
}

TEST(QualityTargets, SampleFramesAreRunsSpreadOverTheSequence) {
  const std::vector<uint32_t> frames = sample_frames(1000, 100000);
  EXPECT_EQ(frames.size(), kSampleVertexFrames / 1000);
  EXPECT_EQ(frames.front(), 0u);
  EXPECT_EQ(frames.back(), 99999u);
  EXPECT_EQ(sample_frames(1000, 20), std::vector<uint32_t>({0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19}));
}

// A wavy sheet of 72 × 72 vertices: frames large enough to decode on two threads.
MeshSequence large_sheet(int frames) {
  constexpr int n = 71;
  MeshSequence s;
  auto at = [](int i, int j) { return static_cast<NodeIndex>(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      s.faces.push_back({{at(i, j), at(i + 1, j), at(i + 1, j + 1)}});
      s.faces.push_back({{at(i, j), at(i + 1, j + 1), at(i, j + 1)}});
    }
  s.vertex_count = (n + 1) * (n + 1);
  for (int f = 0; f < frames; ++f) {
    std::vector<Vec3> frame;
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) frame.push_back({i * 0.1, 0.3 * std::sin(0.2 * i + 0.5 * f) * std::cos(0.15 * j), j * 0.1});
    s.frames.push_back(std::move(frame));
  }
  return s;
}

// Every frame's MD5, or the error, of a decoding with or without a trace.
std::string decoding(std::span<const uint8_t> stream, bool traced) {
  std::ostream nowhere(nullptr);
  Trace trace(nowhere);
  Decode3dOptions options;
  if (traced) options.trace = &trace;
  std::string out;
  try {
    Mesh3dDecoder decoder(stream, options);
    while (decoder.next_frame()) {
      const std::vector<Float3>& positions = decoder.positions();
      out += md5_hex(std::string_view(reinterpret_cast<const char*>(positions.data()), positions.size() * sizeof(Float3))) + " ";
    }
  } catch (const Error& e) {
    out += e.what();
  }
  return out;
}

// A large frame decodes its sections side by side (bfs3d's axes; lcc's
// symbols beside its vertices); traced, one after the other. Both give
// the same frames and, on damaged streams, the same first error.
TEST(LargeFrames, DecodeSideBySideAsOneAfterTheOther) {
  const MeshSequence s = large_sheet(4);
  for (const Encode3dOptions& o : {codec("bfs3d"), codec("lcc"), codec("lcc", {{"mode", "download"}, {"temporal", "1"}, {"gop", "2"}})}) {
    const std::vector<uint8_t> stream = encode_mesh3d(s, o).stream;
    EXPECT_EQ(decoding(stream, false), decoding(stream, true)) << o.codec;
    test::Random random(17);
    int rejected = 0;
    for (int trial = 0; trial < 40; ++trial) {
      std::vector<uint8_t> bad = stream;
      // Past the base mesh, in the frames' symbols.
      const size_t at = stream.size() / 3 + static_cast<size_t>(random.uniform(0, static_cast<int32_t>(stream.size() * 2 / 3) - 1));
      bad[at] ^= static_cast<uint8_t>(1 << random.uniform(0, 7));
      const std::string alone = decoding(bad, false);
      EXPECT_EQ(alone, decoding(bad, true)) << o.codec << ", byte " << at;
      rejected += alone.find(" at ") != std::string::npos;
    }
    EXPECT_GT(rejected, 10) << o.codec;
  }
}

}  // namespace
}  // namespace m4mesh
