// A codec added through the registry alone: a toy progressive codec whose
// two refinement units each refine every frame. It round-trips through the
// container, the command line and the conformance runner with no other
// change to m4mesh.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <sstream>

#include "cli/app.h"
#include "codecs3d/registry.h"
#include "common/atomic_file.h"
#include "conformance/suite_files.h"
#include "conformance/runner.h"
#include "decoder/mesh3d/codec_decoders.h"
#include "decoder/mesh3d/container_decoder.h"
#include "encoder/mesh3d/codec_encoders.h"
#include "encoder/mesh3d/container_encoder.h"
#include "mesh3d/frame_hash.h"
#include "tests/test_util.h"

namespace m4mesh {
namespace {

namespace fs = std::filesystem;

constexpr uint32_t kToyId = 200;

// The toy's syntax: a refinement unit carries its level, then one byte per
// frame, vertex and axis: the high byte of a 16-bit position (level 0) or
// the low byte (level 1).
struct ToyRefinement {
  uint32_t level = 0;
  std::vector<uint32_t> bytes;
};

template <class IO>
void describe(IO& io, ToyRefinement& r, uint32_t count) {
  io.field_in("toy_level", 8, r.level, 0, 1);
  io.resize(r.bytes, count, "toy_byte", 8);
  for (uint32_t& b : r.bytes) io.field(r.level == 0 ? "toy_high_byte" : "toy_low_byte", 8, b);
}

uint32_t toy_quantized(double x) { return static_cast<uint32_t>(std::clamp(std::lround(x * 256) + 32768, 0L, 65535L)); }
float toy_position(uint32_t q) { return static_cast<float>(static_cast<int32_t>(q) - 32768) / 256.0f; }

class ToyDecoder final : public CodecDecoder3d {
 public:
  explicit ToyDecoder(const ObjectHeader& header) : header_(header) {}

  void decode_unit(const UnitHeader& unit, syntax::ReadIO& io, std::vector<uint32_t>& decoded) override {
    if (unit.type() == UnitType::kBaseMesh) {
      faces_ = read_base_mesh(io, header_, trace_).faces;
      q_.assign(size_t{header_.frame_count} * header_.vertex_count * 3, 0);
      return;
    }
    ToyRefinement r;
    describe(io, r, static_cast<uint32_t>(q_.size()));
    if (r.level != levels_) io.fail(ErrorKind::kStructure, "toy_level", "levels come in order");
    ++levels_;
    for (size_t i = 0; i < q_.size(); ++i) q_[i] = r.level == 0 ? r.bytes[i] << 8 : (q_[i] & 0xFF00) | r.bytes[i];
    for (uint32_t f = 0; f < header_.frame_count; ++f) decoded.push_back(f);
  }
  const std::vector<Triangle>& faces() const override { return faces_; }
  void frame(uint32_t index, std::span<Float3> positions) const override {
    for (size_t v = 0; v < positions.size(); ++v)
      for (int axis = 0; axis < 3; ++axis) positions[v][axis] = toy_position(q_[(size_t{index} * header_.vertex_count + v) * 3 + axis]);
  }
  bool holds_frames() const override { return true; }
  uint32_t frames_decoded() const override { return levels_ > 0 ? header_.frame_count : 0; }

 private:
  ObjectHeader header_;
  std::vector<Triangle> faces_;
  std::vector<uint32_t> q_;
  uint32_t levels_ = 0;
};

class ToyEncoder final : public CodecEncoder3d {
 public:
  ToyEncoder(int levels, const BaseMeshCoding& base_mesh) : levels_(static_cast<uint32_t>(levels)), base_mesh_(base_mesh) {}
  void write_header(syntax::WriteIO&) override {}
  void encode(const FrameSource& s, UnitSink& sink) override {
    const std::vector<IntPoint3> zeros(s.vertex_count(), IntPoint3{0, 0, 0});
    sink.unit(UnitType::kBaseMesh, 0, [&](syntax::WriteIO& io) { write_base_mesh(io, s.faces(), zeros, base_mesh_); });
    std::vector<uint32_t> q;
    FrameReader reader(s);
    for (uint32_t f = 0; f < s.frame_count(); ++f)
      for (const Vec3& p : reader.get(f))
        for (double c : {p.x, p.y, p.z}) q.push_back(toy_quantized(c));
    for (uint32_t level = 0; level < levels_; ++level)
      sink.unit(UnitType::kRefinement, 0, [&](syntax::WriteIO& io) {
        ToyRefinement r{level, {}};
        for (uint32_t v : q) r.bytes.push_back(level == 0 ? v >> 8 : v & 0xFF);
        describe(io, r, static_cast<uint32_t>(q.size()));
      });
    std::vector<Float3> decoded(s.vertex_count());
    for (uint32_t f = 0; f < s.frame_count(); ++f) {
      for (size_t v = 0; v < decoded.size(); ++v)
        for (int axis = 0; axis < 3; ++axis) {
          const uint32_t value = q[(f * decoded.size() + v) * 3 + static_cast<size_t>(axis)];
          decoded[v][axis] = toy_position(levels_ == 2 ? value : value & 0xFF00);
        }
      sink.decoded(f, decoded);
    }
  }

 private:
  uint32_t levels_;
  BaseMeshCoding base_mesh_;
};

// A codec that decodes frames out of display order: after the base mesh
// (frame 0), the last frame, then the others; each frame unit carries every
// position as 16 bits, and the decoder keeps only the frame it decoded last.
template <class IO>
void describe_toy_frame(IO& io, std::vector<uint32_t>& q, uint32_t count) {
  io.resize(q, count, "toy_position", 16);
  for (uint32_t& v : q) io.field("toy_position", 16, v);
}

class ReorderedDecoder final : public CodecDecoder3d {
 public:
  explicit ReorderedDecoder(const ObjectHeader& header) : header_(header) {}
  void decode_unit(const UnitHeader& unit, syntax::ReadIO& io, std::vector<uint32_t>& decoded) override {
    if (unit.type() == UnitType::kBaseMesh) {
      const BaseMesh base = read_base_mesh(io, header_, trace_);
      faces_ = base.faces;
      q_.clear();
      for (const IntPoint3& p : base.positions)
        for (int32_t c : p) q_.push_back(static_cast<uint32_t>(c));
    } else {
      describe_toy_frame(io, q_, header_.vertex_count * 3);
    }
    decoded.push_back(unit.frame_index);
  }
  const std::vector<Triangle>& faces() const override { return faces_; }
  void frame(uint32_t, std::span<Float3> positions) const override {
    for (size_t v = 0; v < positions.size(); ++v)
      for (int axis = 0; axis < 3; ++axis) positions[v][axis] = toy_position(q_[v * 3 + static_cast<size_t>(axis)]);
  }

 private:
  ObjectHeader header_;
  std::vector<Triangle> faces_;
  std::vector<uint32_t> q_;
};

class ReorderedEncoder final : public CodecEncoder3d {
 public:
  explicit ReorderedEncoder(const BaseMeshCoding& base_mesh) : base_mesh_(base_mesh) {}
  void write_header(syntax::WriteIO&) override {}
  void encode(const FrameSource& s, UnitSink& sink) override {
    std::vector<uint32_t> order{0};
    if (s.frame_count() > 1) order.push_back(s.frame_count() - 1);
    for (uint32_t f = 1; f + 1 < s.frame_count(); ++f) order.push_back(f);
    FrameReader reader(s);
    for (uint32_t f : order) {
      std::vector<uint32_t> q;
      std::vector<IntPoint3> grid;
      std::vector<Float3> decoded;
      for (const Vec3& p : reader.get(f)) {
        grid.push_back({static_cast<int32_t>(toy_quantized(p.x)), static_cast<int32_t>(toy_quantized(p.y)), static_cast<int32_t>(toy_quantized(p.z))});
        decoded.push_back({toy_position(toy_quantized(p.x)), toy_position(toy_quantized(p.y)), toy_position(toy_quantized(p.z))});
        for (int32_t c : grid.back()) q.push_back(static_cast<uint32_t>(c));
      }
      if (f == 0)
        sink.unit(UnitType::kBaseMesh, 0, [&](syntax::WriteIO& io) { write_base_mesh(io, s.faces(), grid, base_mesh_); });
      else
        sink.unit(UnitType::kFrame, f, [&](syntax::WriteIO& io) { describe_toy_frame(io, q, static_cast<uint32_t>(q.size())); });
      sink.decoded(f, decoded);
    }
  }

 private:
  BaseMeshCoding base_mesh_;
};

void register_toy() {
  static const bool registered = [] {
    register_codec3d({kToyId, "toy-progressive", "a test's progressive codec: 16-bit positions in two refinement units", "tests/registry_test.cc",
                      {UnitType::kBaseMesh, UnitType::kRefinement}});
    register_decoder3d(kToyId, [](const ObjectHeader& h, syntax::ReadIO&) { return std::make_unique<ToyDecoder>(h); });
    register_encoder3d(kToyId, {{{"levels", "toy-progressive: refinement units to send", OptionKind::kInteger, "2", 1, 2}},
                                {"levels", {"1", "2"}, {}},
                                [](const FrameSource&, const CodecSettings& s) { return std::make_unique<ToyEncoder>(s.integer("levels"), s.base_mesh()); }});
    register_codec3d({kToyId + 1, "toy-reordered", "a test's codec that decodes frames out of display order", "tests/registry_test.cc",
                      {UnitType::kBaseMesh, UnitType::kFrame}});
    register_decoder3d(kToyId + 1, [](const ObjectHeader& h, syntax::ReadIO&) { return std::make_unique<ReorderedDecoder>(h); });
    register_encoder3d(kToyId + 1, {{}, {}, [](const FrameSource&, const CodecSettings& s) { return std::make_unique<ReorderedEncoder>(s.base_mesh()); }});
    return true;
  }();
  (void)registered;
}

Encode3dOptions toy_options(int levels) {
  Encode3dOptions options;
  options.codec = "toy-progressive";
  options.codec_options["levels"] = std::to_string(levels);
  return options;
}

// The positions the toy decodes from `s` with `levels` refinements.
std::vector<std::vector<Float3>> expected(const MeshSequence& s, int levels) {
  std::vector<std::vector<Float3>> frames;
  for (const std::vector<Vec3>& frame : s.frames) {
    std::vector<Float3> out;
    for (const Vec3& p : frame) {
      Float3 f;
      const double c[3] = {p.x, p.y, p.z};
      for (int axis = 0; axis < 3; ++axis) f[axis] = toy_position(levels == 2 ? toy_quantized(c[axis]) : toy_quantized(c[axis]) & 0xFF00);
      out.push_back(f);
    }
    frames.push_back(out);
  }
  return frames;
}

std::vector<std::vector<Float3>> decoded_frames(const std::vector<uint8_t>& stream) {
  Mesh3dDecoder decoder(stream, test::verifying());
  std::vector<std::vector<Float3>> frames;
  while (decoder.next_frame()) frames.push_back(decoder.positions());
  EXPECT_FALSE(decoder.first_mismatch().has_value());
  return frames;
}

// The stream cut after unit `units` (a unit boundary), without an end code.
std::vector<uint8_t> prefix(const std::vector<uint8_t>& stream, size_t units) {
  const ContainerParts parts = split_container(stream);
  ContainerWriter writer;
  writer.object(parts.object_payload);
  for (size_t k = 0; k < units; ++k) writer.unit(parts.units[k].payload);
  return writer.finish(false);
}

TEST(Registry, ToyCodecRoundTripsThroughTheContainer) {
  register_toy();
  const MeshSequence s = test::test_sequence(4, 21);
  const std::vector<uint8_t> stream = encode_mesh3d(s, toy_options(2)).stream;
  EXPECT_EQ(decoded_frames(stream), expected(s, 2));

  // Unit by unit: each refinement decodes every frame, coarse then fine.
  Mesh3dDecoder decoder(stream);
  ASSERT_TRUE(decoder.next_unit());
  EXPECT_EQ(decoder.unit().header.type(), UnitType::kBaseMesh);
  for (int level = 1; level <= 2; ++level) {
    ASSERT_TRUE(decoder.next_unit());
    EXPECT_EQ(decoder.unit().header.type(), UnitType::kRefinement);
    ASSERT_EQ(decoder.unit().frames.size(), s.frames.size());
    std::vector<Float3> positions(s.vertex_count);
    decoder.frame(3, positions);
    EXPECT_EQ(positions, expected(s, level)[3]) << "level " << level;
  }
  EXPECT_FALSE(decoder.next_unit());

  // Any prefix that ends at a unit boundary after the first refinement is a valid stream.
  EXPECT_EQ(decoded_frames(prefix(stream, 2)), expected(s, 1));
  EXPECT_THROW(decoded_frames(prefix(stream, 1)), Error);  // the frames were never decoded
  EXPECT_EQ(decoded_frames(encode_mesh3d(s, toy_options(1)).stream), expected(s, 1));
}

TEST(Registry, FramesDecodedOutOfOrderComeOutInDisplayOrder) {
  register_toy();
  const MeshSequence s = test::test_sequence(5, 24);
  Encode3dOptions options;
  options.codec = "toy-reordered";
  const std::vector<uint8_t> stream = encode_mesh3d(s, options).stream;
  EXPECT_EQ(decoded_frames(stream), expected(s, 2));
  Mesh3dDecoder decoder(stream);
  std::vector<uint32_t> unit_frames;
  while (decoder.next_unit()) unit_frames.push_back(decoder.unit().frames.at(0));
  EXPECT_EQ(unit_frames, (std::vector<uint32_t>{0, 4, 1, 2, 3}));
}

TEST(Registry, ToyCodecTracesAlikeAndIsChecked) {
  register_toy();
  const MeshSequence s = test::test_sequence(2, 22);
  std::ostringstream written, read;
  Trace write_trace(written), read_trace(read);
  Encode3dOptions options = toy_options(2);
  options.trace = &write_trace;
  const std::vector<uint8_t> stream = encode_mesh3d(s, options).stream;
  Decode3dOptions decode;
  decode.trace = &read_trace;
  Mesh3dDecoder decoder(stream, decode);
  while (decoder.next_unit()) {
  }
  EXPECT_EQ(written.str(), read.str());
  EXPECT_NE(read.str().find("toy_low_byte"), std::string::npos);
  // A unit type the codec does not use.
  ContainerParts parts = split_container(stream);
  parts.units[1].payload[0] = static_cast<uint8_t>(UnitType::kFrame);
  ContainerWriter writer;
  writer.object(parts.object_payload);
  for (const ContainerUnit& unit : parts.units) writer.unit(unit.payload);
  try {
    decoded_frames(writer.finish());
    FAIL() << "decoded";
  } catch (const Error& e) {
    EXPECT_EQ(e.element(), "unit_type");
    EXPECT_NE(std::string(e.what()).find("not used by toy-progressive"), std::string::npos) << e.what();
  }
}

int cli(std::vector<std::string> args) {
  args.insert(args.begin(), "m4mesh");
  std::vector<const char*> argv;
  for (const std::string& a : args) argv.push_back(a.c_str());
  return run_m4mesh(static_cast<int>(argv.size()), argv.data());
}

TEST(Registry, ToyCodecOnTheCommandLineAndInTheConformanceRunner) {
  register_toy();
  const fs::path folder = fs::temp_directory_path() / "m4mesh-registry-test";
  fs::remove_all(folder);
  fs::create_directories(folder);
  const MeshSequence s = test::test_sequence(3, 23);
  write_binary_sequence(s, (folder / "in.m4seq").string());
  const std::string stream = (folder / "toy.m4m").string(), frames = (folder / "toy.f32").string();
  ASSERT_EQ(cli({"encode3d", (folder / "in.m4seq").string(), "-o", stream, "--codec", "toy-progressive", "--levels", "2"}), 0);
  EXPECT_EQ(cli({"encode3d", (folder / "in.m4seq").string(), "-o", stream, "--codec", "toy-progressive", "--levels", "3"}), 2);  // usage errors exit 2
  EXPECT_EQ(cli({"encode3d", (folder / "in.m4seq").string(), "-o", stream, "--codec", "toy-progressive", "--me", "3"}), 2);
  ASSERT_EQ(cli({"decode3d", stream, "-o", frames, "--verify"}), 0);
  std::vector<uint8_t> expected_bytes;
  for (const std::vector<Float3>& f : expected(s, 2)) {
    const std::vector<uint8_t> b = frame_bytes(f);
    expected_bytes.insert(expected_bytes.end(), b.begin(), b.end());
  }
  EXPECT_EQ(read_file(frames), expected_bytes);
  EXPECT_EQ(cli({"info", stream}), 0);
  EXPECT_EQ(cli({"check", stream}), 0);

  const std::vector<uint8_t> toy = read_file(stream);
  write_suite((folder / "suite").string(), SuiteKind::kMesh3d,
              {decode_case("toy-01-fine", "both refinements", {"container"}, toy),
               decode_case("toy-02-coarse", "the prefix after the first refinement", {"container"}, prefix(toy, 2)),
               reject_case("toy-03-no-refinement", "the prefix before any refinement", {"container"}, prefix(toy, 1), ErrorKind::kTruncated,
                           "mesh3d_unit_start_code", 0)});
  std::ostringstream report;
  const ConformResult result = run_conformance({(folder / "suite").string(), ""}, report);
  EXPECT_EQ(result.passed, 3) << report.str();
  EXPECT_EQ(result.failed, 0) << report.str();
  fs::remove_all(folder);
}

}  // namespace
}  // namespace m4mesh
