// The 3D half: container, arithmetic coding, traversal, bfs3d, metrics, sequence files.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <set>

#include "bitstream/arithmetic.h"
#include "bitstream/emulation.h"
#include "common/bit_cast.h"
#include "common/error.h"
#include "decoder/mesh3d/container_decoder.h"
#include "encoder/mesh3d/container_encoder.h"
#include "anchors/draco_reference.h"
#include "mesh3d/metrics.h"
#include "mesh3d/quantization.h"
#include "mesh3d/sequence.h"
#include "mesh3d/bfs3d.h"
#include "syntax/mesh3d/bfs3d.h"
#include "syntax/mesh3d/entropy_io.h"
#include "syntax/mesh3d/residual.h"
#include "syntax/mesh3d/container.h"
#include "tests/test_util.h"

namespace m4mesh {
namespace {

namespace fs = std::filesystem;

using test::test_sequence;
using test::verifying;

TEST(Emulation, EscapedPayloadsNeverHoldAStartCodePrefix) {
  test::Random random(1);
  for (int trial = 0; trial < 500; ++trial) {
    std::vector<uint8_t> payload(static_cast<size_t>(random.uniform(0, 64)));
    for (uint8_t& b : payload) b = static_cast<uint8_t>(random.uniform(0, 3) == 0 ? random.uniform(0, 255) : random.uniform(0, 3));
    const std::vector<uint8_t> escaped = escape_payload(payload);
    for (size_t i = 0; i + 2 < escaped.size(); ++i)
      ASSERT_FALSE(escaped[i] == 0 && escaped[i + 1] == 0 && escaped[i + 2] <= 2);
    if (escaped.size() >= 2) {
      ASSERT_FALSE(escaped[escaped.size() - 1] == 0 && escaped[escaped.size() - 2] == 0);
    }
    ASSERT_EQ(unescape_payload(escaped), payload);
  }
  EXPECT_EQ(escape_payload(std::vector<uint8_t>{0, 0, 1}), (std::vector<uint8_t>{0, 0, 3, 1}));
  EXPECT_EQ(escape_payload(std::vector<uint8_t>{0, 0, 3}), (std::vector<uint8_t>{0, 0, 3, 3}));
  EXPECT_EQ(escape_payload(std::vector<uint8_t>{5, 0, 0}), (std::vector<uint8_t>{5, 0, 0, 3}));
  EXPECT_EQ(escape_payload(std::vector<uint8_t>{0, 0, 4}), (std::vector<uint8_t>{0, 0, 4}));
}

TEST(Container, SplitsObjectUnitsAndEndCode) {
  ContainerWriter writer;
  writer.object(std::vector<uint8_t>{1, 2, 0, 0});
  writer.unit(std::vector<uint8_t>{0, 0, 1, 7});
  writer.unit(std::vector<uint8_t>{});
  const std::vector<uint8_t> stream = writer.finish();
  const ContainerParts parts = split_container(stream);
  EXPECT_EQ(parts.object_payload, (std::vector<uint8_t>{1, 2, 0, 0}));
  ASSERT_EQ(parts.units.size(), 2u);
  EXPECT_EQ(parts.units[0].payload, (std::vector<uint8_t>{0, 0, 1, 7}));
  EXPECT_TRUE(parts.has_end_code);
  std::vector<uint8_t> trailing = stream;
  trailing.push_back(9);
  EXPECT_THROW(split_container(trailing), Error);
  std::vector<uint8_t> no_end(stream.begin(), stream.end() - 4);
  EXPECT_FALSE(split_container(no_end).has_end_code);
  EXPECT_THROW(split_container(std::vector<uint8_t>{0, 0, 1, 0xC5}), Error);
}

TEST(Arithmetic, RoundTripsBins) {
  test::Random random(2);
  std::vector<std::pair<int, int>> bins;  // (context, value)
  ArithmeticEncoder encoder;
  std::vector<BinContext> contexts(4);
  for (int i = 0; i < 20000; ++i) {
    const int context = random.uniform(0, 3);
    const int bin = random.uniform(0, 9) < context * 3 ? 1 : 0;
    bins.push_back({context, bin});
    encoder.encode(contexts[context], bin);
  }
  const std::vector<uint8_t> data = encoder.finish();
  EXPECT_LT(data.size(), 20000u / 8);  // skewed bins cost less than a bit each
  ArithmeticDecoder decoder(data);
  std::vector<BinContext> decoding(4);
  for (const auto& [context, bin] : bins) ASSERT_EQ(decoder.decode(decoding[context]), bin);
  EXPECT_EQ(decoder.overrun(), 0u);
  EXPECT_EQ(decoder.position(), data.size());
  ArithmeticDecoder truncated(std::span<const uint8_t>(data).first(data.size() / 2));
  for (const auto& [context, bin] : bins) truncated.decode(decoding[context]);
  EXPECT_GT(truncated.overrun(), 0u);
}

// The decoder renormalizes by at most one byte per bin; the least likely
// bins at both probability limits (31 and 2017 of 2048) must still decode.
TEST(Arithmetic, LeastLikelyBinsAtTheProbabilityLimitsRoundTrip) {
  std::vector<int> bins;
  for (int run = 0; run < 40; ++run) {
    const int likely = run % 2;
    bins.insert(bins.end(), 300 + 7 * run, likely);
    bins.insert(bins.end(), 1 + run % 3, 1 - likely);
  }
  ArithmeticEncoder encoder;
  BinContext context;
  for (int bin : bins) encoder.encode(context, bin);
  const std::vector<uint8_t> data = encoder.finish();
  ArithmeticDecoder decoder(data);
  BinContext decoding;
  uint16_t lowest = decoding.p0, highest = decoding.p0;
  for (size_t i = 0; i < bins.size(); ++i) {
    lowest = std::min(lowest, decoding.p0);
    highest = std::max(highest, decoding.p0);
    ASSERT_EQ(decoder.decode(decoding), bins[i]) << "bin " << i;
  }
  EXPECT_EQ(lowest, 31);
  EXPECT_EQ(highest, 2017);
  EXPECT_EQ(decoder.overrun(), 0u);
  EXPECT_EQ(decoder.position(), data.size());
}

TEST(Arithmetic, ResidualsOfEverySizeRoundTrip) {
  std::vector<int32_t> values{0, 1, -1, 2, -2, 3, 100, -100, 65535, -65536, (1 << 29), -(1 << 29), (1 << 30) + 7};
  test::Random random(3);
  for (int i = 0; i < 3000; ++i) values.push_back(random.uniform(-3000, 3000) >> random.uniform(0, 10));
  const syntax::SectionPlace place;
  syntax::EntropyWriteIO<false> writer(place);
  syntax::ResidualCoder<3> model;
  for (size_t i = 0; i < values.size(); ++i) model.describe(writer, static_cast<int>(i % 3), values[i], syntax::kMotionResidual);
  const std::vector<uint8_t> data = writer.finish_bins();
  const std::vector<uint8_t> raw_bytes = writer.finish_raw();
  syntax::EntropyReadIO<false> reader(data, raw_bytes, place);
  syntax::ResidualCoder<3> decoding;
  for (size_t i = 0; i < values.size(); ++i) {
    int32_t r = 0;
    decoding.describe(reader, static_cast<int>(i % 3), r, syntax::kMotionResidual);
    ASSERT_EQ(r, values[i]);
  }
  EXPECT_NO_THROW(reader.finish("motion_residual"));
}

// After the last symbol: no bin bytes left over, zero padding, no raw bytes left over.
TEST(Arithmetic, SectionsEndExactly) {
  const syntax::SectionPlace place;
  syntax::EntropyWriteIO<false> writer(place);
  syntax::ResidualCoder<1> model;
  std::vector<int32_t> values{5, -3, 0, 17};
  for (int32_t& v : values) model.describe(writer, 0, v, syntax::kMotionResidual);
  const std::vector<uint8_t> bins = writer.finish_bins(), raw = writer.finish_raw();
  auto decode = [&](const std::vector<uint8_t>& b, const std::vector<uint8_t>& r) {
    syntax::EntropyReadIO<false> reader(b, r, place);
    syntax::ResidualCoder<1> decoding;
    for (int32_t expected : values) {
      int32_t v = 0;
      decoding.describe(reader, 0, v, syntax::kMotionResidual);
      EXPECT_EQ(v, expected);
    }
    reader.finish("motion_residual");
  };
  EXPECT_NO_THROW(decode(bins, raw));
  std::vector<uint8_t> more_bins = bins;
  more_bins.push_back(0);
  EXPECT_THROW(decode(more_bins, raw), Error);
  std::vector<uint8_t> more_raw = raw;
  more_raw.push_back(0);
  EXPECT_THROW(decode(bins, more_raw), Error);
  std::vector<uint8_t> padded = raw;
  padded.back() |= 1;  // the raw bits do not fill their last byte: its last bit is padding
  try {
    decode(bins, padded);
    FAIL() << "nonzero padding accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.element(), "raw_padding");
  }
}

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

// ---- metrics ----------------------------------------------------------------

MeshSequence one_triangle(std::vector<std::vector<Vec3>> frames) {
  MeshSequence s;
  s.vertex_count = 3;
  s.faces = {{{0, 1, 2}}};
  s.frames = std::move(frames);
  return s;
}

TEST(Metrics, HandComputedValues) {
  // One frame: (0,0,0) (3,0,0) (0,4,0); the decoded moves vertex 1 by 0.3 in x.
  const MeshSequence a = one_triangle({{{0, 0, 0}, {3, 0, 0}, {0, 4, 0}}});
  const MeshSequence b = one_triangle({{{0, 0, 0}, {3.3, 0, 0}, {0, 4, 0}}});
  const SequenceMetrics m = compare_sequences(a, b);
  // Mean (1, 4/3, 0); spread Σ|v − mean|² = (1 + 16/9) + (4 + 16/9) + (1 + 64/9) = 50/3; error 0.09.
  EXPECT_NEAR(m.kg_error, 100 * std::sqrt(0.09) / std::sqrt(50.0 / 3), 1e-12);
  EXPECT_NEAR(m.rmse, std::sqrt(0.09 / 3), 1e-12);
  EXPECT_NEAR(m.max_error, 0.3, 1e-12);
  // dmax = diagonal of the box 3×4×0 = 5; AVGMSE = 0.03.
  EXPECT_NEAR(m.psnr, 10 * std::log10(25 / 0.03), 1e-9);
  // Edges 0-1 (3 → 3.3: ed 0.1), 1-2 (5 → √(3.3² + 16) : ed (√26.89 − 5)/5), 2-0 (4: ed 0).
  // Every vertex's neighbourhood holds all three edges (d = 1).
  const double e12 = (std::sqrt(26.89) - 5) / 5;
  const double mean = (0.1 * 3 + e12 * 5 + 0 * 4) / 12;
  const double deviation = std::sqrt(((0.1 - mean) * (0.1 - mean) * 3 + (e12 - mean) * (e12 - mean) * 5 + mean * mean * 4) / 12);
  EXPECT_NEAR(m.sted_spatial, deviation, 1e-12);
  EXPECT_EQ(m.sted_temporal, 0);  // one frame
  EXPECT_NEAR(m.sted, deviation, 1e-12);
}

TEST(Metrics, DiameterIsTheLargestPairwiseDistance) {
  test::Random random(77);
  auto brute = [](const std::vector<Vec3>& p) {
    double best = 0;
    for (size_t i = 0; i < p.size(); ++i)
      for (size_t j = i + 1; j < p.size(); ++j)
        best = std::max(best, std::sqrt((p[i].x - p[j].x) * (p[i].x - p[j].x) + (p[i].y - p[j].y) * (p[i].y - p[j].y) +
                                        (p[i].z - p[j].z) * (p[i].z - p[j].z)));
    return best;
  };
  for (int shape = 0; shape < 3; ++shape)
    for (int trial = 0; trial < 20; ++trial) {
      std::vector<Vec3> points;
      for (int i = 0; i < 300; ++i) {
        const double u = random.uniform(-1000, 1000) / 1000.0, v = random.uniform(-1000, 1000) / 1000.0, w = random.uniform(-1000, 1000) / 1000.0;
        const double n = std::sqrt(u * u + v * v + w * w) + 1e-9;
        points.push_back(shape == 0 ? Vec3{u, v, w} : shape == 1 ? Vec3{u / n, v / n, w / n} : Vec3{3 * u, v, 0});  // cube, sphere, flat
      }
      EXPECT_DOUBLE_EQ(diameter(points), brute(points)) << shape;
    }
  EXPECT_EQ(diameter(std::vector<Vec3>{}), 0);
  EXPECT_EQ(diameter(std::vector<Vec3>{{1, 2, 3}}), 0);
}

TEST(Metrics, TemporalStedByHand) {
  // Two frames; vertex 0 moves by 0.5 in the original and by 0.6 in the decoded; ld = 5.
  const MeshSequence a = one_triangle({{{0, 0, 0}, {3, 0, 0}, {0, 4, 0}}, {{0.5, 0, 0}, {3, 0, 0}, {0, 4, 0}}});
  const MeshSequence b = one_triangle({{{0, 0, 0}, {3, 0, 0}, {0, 4, 0}}, {{0.6, 0, 0}, {3, 0, 0}, {0, 4, 0}}});
  double spatial, temporal, combined;
  StedParams p;
  sted(a, b, p, spatial, temporal, combined);
  const double tel_a = std::sqrt(0.1 * 0.1 + p.dt * p.dt), tel_b = std::sqrt(0.12 * 0.12 + p.dt * p.dt);
  // ted = |tel − tel'| / s with s = tel (the window holds one frame); static vertices add 0.
  EXPECT_NEAR(temporal, (std::abs(tel_a - tel_b) / tel_a) / 3, 1e-12);
  EXPECT_NEAR(combined, std::sqrt(spatial * spatial + p.c * p.c * temporal * temporal), 1e-15);
}

TEST(Metrics, StedIgnoresRigidMotionAndUniformScaling) {
  const MeshSequence original = test_sequence(5, 9);
  MeshSequence decoded = original;
  test::Random random(9);
  for (auto& frame : decoded.frames)
    for (Vec3& v : frame) v.x += 1e-3 * random.uniform(-10, 10);
  double s0, t0, c0;
  sted(original, decoded, {}, s0, t0, c0);
  ASSERT_GT(c0, 0);
  const double kg0 = kg_error(original, decoded);
  auto transformed = [](MeshSequence s, double scale) {
    const double angle = 0.7;
    for (auto& frame : s.frames)
      for (Vec3& v : frame) {
        const double x = std::cos(angle) * v.x - std::sin(angle) * v.z, z = std::sin(angle) * v.x + std::cos(angle) * v.z;
        v = {scale * x + 5, scale * v.y - 2, scale * z + 1};
      }
    return s;
  };
  for (double scale : {1.0, 3.5}) {
    double s1, t1, c1;
    sted(transformed(original, scale), transformed(decoded, scale), {}, s1, t1, c1);
    EXPECT_NEAR(s1, s0, 1e-9 * s0);
    EXPECT_NEAR(t1, t0, 1e-9 * t0);
    EXPECT_NEAR(c1, c0, 1e-9 * c0);
    EXPECT_NEAR(kg_error(transformed(original, scale), transformed(decoded, scale)), kg0, 1e-9 * kg0);
  }
}

// ---- sequence files ------------------------------------------------------------

TEST(SequenceFiles, ObjOffAndBinaryAgree) {
  const fs::path dir = fs::temp_directory_path() / "m4mesh-seq-test";
  fs::remove_all(dir);
  const MeshSequence s = test_sequence(3, 10);
  write_obj_frames(s, (dir / "obj").string());
  const MeshSequence from_obj = load_sequence((dir / "obj").string());
  EXPECT_EQ(from_obj.faces, s.faces);
  ASSERT_EQ(from_obj.frames.size(), 3u);
  EXPECT_NEAR(from_obj.frames[2][5].x, s.frames[2][5].x, 1e-8);
  write_binary_sequence(from_obj, (dir / "s.m4seq").string());
  const MeshSequence binary = load_sequence((dir / "s.m4seq").string());
  EXPECT_EQ(binary.faces, s.faces);
  EXPECT_EQ(binary.frames[1][3].y, static_cast<double>(static_cast<float>(from_obj.frames[1][3].y)));
  std::ofstream(dir / "a1.off") << "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n";
  std::ofstream(dir / "a2.off") << "OFF\n# moved\n4 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n4 0 1 2 3\n";
  std::ofstream(dir / "a10.off") << "OFF\n3 1 0\n0 0 0\n1 0 0\n1 1 0\n3 0 1 2\n";
  try {
    load_sequence((dir / "a*.off").string());
    ADD_FAILURE() << "a changed vertex count was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("a10.off"), std::string::npos) << e.what();
  }
  fs::remove(dir / "a10.off");
  const MeshSequence off = load_sequence((dir / "a*.off").string());
  EXPECT_EQ(off.frames.size(), 2u);
  EXPECT_EQ(off.faces.size(), 2u);
  EXPECT_EQ(off.frames[1][2].z, 1.0);
  fs::remove_all(dir);
}

// A PC2 file of `samples` frames of `points` points: point i of frame f at (i, f, 0.5).
std::string pc2_bytes(uint32_t points, uint32_t samples, const char* signature = "POINTCACHE2") {
  std::string out(signature, 11);
  out += '\0';
  auto put = [&](uint32_t v) {
    for (int i = 0; i < 4; ++i) out += static_cast<char>((v >> (8 * i)) & 0xFF);
  };
  auto put_float = [&](float f) { put(bit_cast<uint32_t>(f)); };
  put(1);
  put(points);
  put_float(0);
  put_float(25);
  put(samples);
  for (uint32_t f = 0; f < samples; ++f)
    for (uint32_t i = 0; i < points; ++i) {
      put_float(static_cast<float>(i));
      put_float(static_cast<float>(f));
      put_float(0.5f);
    }
  return out;
}

TEST(SequenceFiles, Pc2WithTheObjBesideIt) {
  const fs::path dir = fs::temp_directory_path() / "m4mesh-pc2-test";
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "sheet.obj") << "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n";
  std::ofstream(dir / "sheet.pc2", std::ios::binary) << pc2_bytes(4, 3);
  const MeshSequence s = load_sequence((dir / "sheet.pc2").string());
  EXPECT_EQ(s.vertex_count, 4u);
  EXPECT_EQ(s.faces.size(), 2u);
  ASSERT_EQ(s.frames.size(), 3u);
  EXPECT_EQ(s.frames[2][3], (Vec3{3, 2, 0.5}));
  auto rejected = [&](const std::string& bytes, const char* words) {
    std::ofstream(dir / "sheet.pc2", std::ios::binary | std::ios::trunc) << bytes;
    try {
      load_sequence((dir / "sheet.pc2").string());
      ADD_FAILURE() << "accepted: " << words;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
  };
  rejected(pc2_bytes(5, 3), "5 points where");
  rejected(pc2_bytes(4, 3).substr(0, 60), "truncated PC2");
  rejected(pc2_bytes(4, 3, "POINTCACHE3"), "not a PC2 file");
  rejected(pc2_bytes(4, 3) + "x", "bytes after the last sample");
  std::string huge = pc2_bytes(4, 1);
  huge[28] = '\x7f';  // a sample count of about 2^31 with one sample's data: refused before allocating
  rejected(huge, "truncated PC2");
  fs::remove(dir / "sheet.obj");
  rejected(pc2_bytes(4, 3), "which is missing");
  fs::remove_all(dir);
}

// ---- real sequences (../shared/data) -----------------------------------------

const fs::path kData = fs::path(M4MESH_SOURCE_DIR) / ".." / "shared" / "data";

TEST(RealData, ClothFlagPc2) {
  if (!fs::exists(kData / "cloth" / "flag")) GTEST_SKIP() << "../shared/data/cloth/flag is absent";
  const MeshSequence flag = load_sequence((kData / "cloth" / "flag" / "flag.pc2").string());
  EXPECT_EQ(flag.vertex_count, 4225u);
  EXPECT_EQ(flag.faces.size(), 8192u);
  EXPECT_EQ(flag.frames.size(), 300u);
  const MeshSequence obj = load_sequence((kData / "cloth" / "flag" / "flag.obj").string());
  for (uint32_t i = 0; i < flag.vertex_count; ++i)
    ASSERT_EQ(flag.frames[0][i].x, static_cast<double>(static_cast<float>(obj.frames[0][i].x))) << "vertex " << i;
}

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
