// The bfs3d streams (docs/codec_bfs3d.md) and those to reject.
#include <algorithm>
#include <sstream>
#include <string_view>

#include "conformance/suite3d/cases.h"
#include "conformance/suite3d/inputs.h"
#include "conformance/suite3d/stream_edits.h"
#include "decoder/mesh3d/container_decoder.h"
#include "mesh3d/bfs3d.h"
#include "syntax/mesh3d/bfs3d.h"
#include "syntax/mesh3d/entropy_io.h"

namespace m4mesh::suite3d {

namespace {

// A bfs3d frame unit's payload with a zero byte after its section k (0 bins
// x, 1 raw x, …, 5 raw z), whose length field grows by one.
std::vector<uint8_t> with_extra_byte(std::vector<uint8_t> payload, int k) {
  static const char* const kLengths[6] = {"arithmetic_bytes_x", "raw_bytes_x", "arithmetic_bytes_y", "raw_bytes_y", "arithmetic_bytes_z", "raw_bytes_z"};
  uint64_t end = unit_field<Bfs3dFrame>(syntax::kAxisBins[0]).first;
  for (int i = 0; i <= k; ++i) end += field_value(payload, unit_field<Bfs3dFrame>(kLengths[i]));
  payload.insert(payload.begin() + static_cast<std::ptrdiff_t>(end), 0x00);
  const FieldBytes length = unit_field<Bfs3dFrame>(kLengths[k]);
  put_field(payload, length, field_value(payload, length) + 1);
  return payload;
}

// Writes bins as EntropyWriteIO does, but every prefix bin as 1, so that a
// residual's prefix never ends; stops where a decoder must fail.
class EndlessPrefixIO {
 public:
  static constexpr bool kReading = false;
  struct Stop {};
  explicit EndlessPrefixIO(syntax::EntropyWriteIO<false>& io) : io_(io) {}
  void bin(const char* name, BinContext& state, int context, bool& value) {
    if (std::string_view(name).ends_with("_prefix")) value = true;
    io_.bin(name, state, context, value);
  }
  void raw(const char* name, int bits, uint32_t& value) { io_.raw(name, bits, value); }
  [[noreturn]] void fail(ErrorKind, const char*, const std::string&) const { throw Stop{}; }

 private:
  syntax::EntropyWriteIO<false>& io_;
};

// A bfs3d frame unit whose first x residual has a prefix of 31 ones, one
// past the longest code (e + k ≤ 30).
std::vector<uint8_t> bfs3d_endless_prefix_unit(std::vector<uint8_t> unit_header) {
  const syntax::SectionPlace place;
  syntax::EntropyWriteIO<false> symbols(place);
  EndlessPrefixIO endless(symbols);
  syntax::ResidualCoder<1> coder;
  int32_t residual = 1;
  try {
    coder.describe(endless, 0, residual, syntax::kMotionResidual);
  } catch (const EndlessPrefixIO::Stop&) {
  }
  const std::vector<uint8_t> bins = symbols.finish_bins();
  Bfs3dFrame frame;
  frame.arithmetic_bytes[0] = static_cast<uint32_t>(bins.size());
  frame.bins[0] = bins;
  return unit_with(std::move(unit_header), frame);
}

// A bfs3d frame unit whose motion residuals are `residuals`, per axis in
// coding order.
std::vector<uint8_t> bfs3d_unit(std::array<std::vector<int32_t>, 3> residuals, std::vector<uint8_t> unit_header) {
  Bfs3dFrame frame;
  std::array<std::vector<uint8_t>, 3> bins, raw;
  for (int axis = 0; axis < 3; ++axis) {
    syntax::EntropyWriteIO<false> symbols(syntax::SectionPlace{});
    syntax::describe_axis(symbols, std::span<int32_t>(residuals[axis]));
    bins[axis] = symbols.finish_bins();
    raw[axis] = symbols.finish_raw();
    frame.arithmetic_bytes[axis] = static_cast<uint32_t>(bins[axis].size());
    frame.raw_bytes[axis] = static_cast<uint32_t>(raw[axis].size());
    frame.bins[axis] = bins[axis];
    frame.raw[axis] = raw[axis];
  }
  return unit_with(std::move(unit_header), frame);
}

// A triangle with its first corner at the grid's origin (no hash units),
// whose frame 1, written symbol by symbol (average prediction), moves that
// corner by (2^26 + `beyond`, −2^26, 0) grid steps and the others by 0.
std::vector<uint8_t> bfs3d_position_limits_stream(int32_t beyond) {
  MeshSequence triangle;
  triangle.vertex_count = 3;
  triangle.faces = {{{0, 1, 2}}};
  triangle.frames = {{{0, 0, 0}, {1, 0, 0.5}, {0, 1, 0.25}}, {{0, 0, 0}, {1, 0, 0.5}, {0, 1, 0.25}}};
  Encode3dOptions o;
  o.hashes = false;
  const std::vector<uint8_t> base = encode_mesh3d(triangle, o).stream;
  const MotionOrder3d order = bfs3d_order(decode_mesh3d(base).faces, triangle.vertex_count);
  std::vector<std::array<int64_t, 3>> motion(triangle.vertex_count + 1);  // the zero slot last
  motion[0] = {(int64_t{1} << 26) + beyond, -(int64_t{1} << 26), 0};
  std::array<std::vector<int32_t>, 3> residuals;
  for (size_t k = 0; k < order.node.size(); ++k)
    for (size_t axis = 0; axis < 3; ++axis) {
      const int64_t w = (motion[order.pred_a[k]][axis] + motion[order.pred_b[k]][axis] + 1) >> 1;
      residuals[axis].push_back(static_cast<int32_t>(motion[order.node[k]][axis] - w));
    }
  return edited(base, [&](ContainerParts& p) {
    ContainerUnit& unit = unit_of(p, UnitType::kFrame, 1);
    unit.payload = bfs3d_unit(residuals, unit_header_bytes(unit.payload));
  });
}

}  // namespace

// bfs3d streams: both predictions, intra frames.
std::vector<SuiteCase> bfs3d_cases(bool traced) {
  const MeshSequence shape = box_and_sheet(6, 4);
  std::vector<SuiteCase> suite;
  suite.push_back(valid("bfs3d-01-average", "bfs3d with base-edge average prediction", {"container", "bfs3d"}, shape, Encode3dOptions{}, traced));
  {
    Encode3dOptions o;
    o.codec_options = {{"parallelogram", "1"}, {"bits", "10"}, {"intra-period", "4"}};
    suite.push_back(valid("bfs3d-02-parallelogram-intra", "bfs3d, parallelogram prediction, 10 bits, intra every 4 frames",
                          {"bfs3d", "container-units"}, shape, o, traced));
  }
  {
    // bfs3d-01 with frame_count 0 (streaming); its trace is the encoder's with that field's value edited.
    const SuiteCase& counted = suite.front();
    SuiteCase streaming = decode_case("bfs3d-03-streaming", "bfs3d-01 with frame_count 0: a stream of unknown length", {"container", "container-units"},
                                      edited(counted.stream, [&](ContainerParts& p) { put_field(p.object_payload, object_field<Bfs3dHeader>(counted.stream, "frame_count"), 0); }));
    std::istringstream lines(counted.encoder_trace);
    for (std::string line; std::getline(lines, line);) {
      if (line.starts_with("object") && line.find(" frame_count ") != std::string::npos) line = line.substr(0, line.find_last_not_of("0123456789") + 1) + "0";
      streaming.encoder_trace += line + "\n";
    }
    suite.push_back(std::move(streaming));
  }
  {
    Encode3dOptions o;
    o.codec_options = {{"bits", "24"}};
    suite.push_back(valid("bfs3d-04-spikes", "vertices that jump by 2^−2 … 2^−23 of the box on a 24-bit grid: motion residuals of every prefix "
                          "length after each class", {"bfs3d"}, spiky_sheet(16, 16, 0, 41, 60), o, traced));
  }
  {
    Encode3dOptions o;
    o.codec_options = {{"bits", "4"}};
    suite.push_back(valid("bfs3d-05-four-bits", "the coarsest grid, 4 bits", {"bfs3d"}, spiky_sheet(4, 4, 8, 49, 3), o, traced));
  }
  {
    // Vertices in no face, predicted from no motion: each frame's motion
    // of the loose vertices follows prefix_schedule().
    const std::vector<int32_t> schedule = prefix_schedule();
    constexpr int kLoose = 429;  // 10 frames of the schedule
    const int frames = static_cast<int>(schedule.size() + kLoose - 1) / kLoose + 1;
    auto offset = [&](int f, int v) {
      int32_t sum = 0;
      for (size_t i = static_cast<size_t>(v); i < std::min(schedule.size(), static_cast<size_t>(f * kLoose)); i += kLoose) sum += schedule[i];
      return sum;
    };
    Encode3dOptions o;
    o.codec_options = {{"bits", "16"}};
    suite.push_back(valid("bfs3d-06-motion-prefixes", "vertices in no face whose motion takes every prefix length 0 … 13 after each class",
                          {"bfs3d"}, designed_loose(frames, kLoose, offset), o, traced));
  }
  {
    // A stream the encoder wrote (no hash units), its step_x the smallest positive binary32.
    Encode3dOptions o;
    o.hashes = false;
    const std::vector<uint8_t> base = encode_mesh3d(box_and_sheet(3, 4), o).stream;
    const FieldBytes step = object_field<Bfs3dHeader>(base, "step_x");
    suite.push_back(written_case("bfs3d-07-smallest-step", "step_x 2^−149, the smallest positive binary32 (a subnormal)", {"bfs3d"},
                                 edited(base, [&](ContainerParts& p) { put_field(p.object_payload, step, 1); })));
  }
  suite.push_back(written_case("bfs3d-08-position-limits", "a vertex moved from the grid's origin to 2^26 on x and −2^26 on y, the ends "
                               "of the positions' range", {"bfs3d"}, bfs3d_position_limits_stream(0)));
  return suite;
}

// The section lengths, and bytes left over after a section.
std::vector<SuiteCase> bfs3d_rejected(const std::vector<SuiteCase>& valid) {
  std::vector<SuiteCase> suite;
  const std::vector<uint8_t> bfs3d = stream_of(valid, "bfs3d-01-average");
  suite.push_back(invalid("x-10-bfs3d-lengths", "raw_bytes_z longer than the frame", {"bfs3d"},
                          edited(bfs3d, [](ContainerParts& p) { unit_of(p, UnitType::kFrame, 1).payload[unit_field<Bfs3dFrame>("raw_bytes_z").first] = 0x7F; }),
                          ErrorKind::kOutOfRange, "raw_bytes_z", 1));
  suite.push_back(invalid("x-11-bfs3d-trailing", "a byte after the six streams", {"bfs3d"},
                          edited(bfs3d, [](ContainerParts& p) { unit_of(p, UnitType::kFrame, 3).payload.push_back(0x55); }),
                          ErrorKind::kStructure, "raw_bytes_z", 3));
  const struct {
    const char* id;
    const char* purpose;
    int section;
  } left_over[] = {{"x-12-bfs3d-bins-left-over", "a byte after the last bin of bins_x, counted by arithmetic_bytes_x", 0},
                   {"x-13-bfs3d-raw-left-over", "a byte after the last raw bits of raw_y, counted by raw_bytes_y", 3}};
  for (const auto& c : left_over)
    suite.push_back(invalid(c.id, c.purpose, {"bfs3d"},
                            edited(bfs3d,
                                   [&](ContainerParts& p) {
                                     ContainerUnit& unit = unit_of(p, UnitType::kFrame, 2);
                                     unit.payload = with_extra_byte(unit.payload, c.section);
                                   }),
                            ErrorKind::kStructure, "motion_residual", 2));
  return suite;
}

// A residual prefix one past the longest code.
std::vector<SuiteCase> bfs3d_prefix_rejected(const std::vector<SuiteCase>& valid) {
  std::vector<SuiteCase> suite;
  const std::vector<uint8_t> bfs3d = stream_of(valid, "bfs3d-01-average");
  suite.push_back(invalid("x-58-residual-prefix-31", "a residual whose prefix has 31 bins '1': one past the longest code", {"container"},
                          edited(bfs3d,
                                 [](ContainerParts& p) {
                                   ContainerUnit& unit = unit_of(p, UnitType::kFrame, 1);
                                   unit.payload = bfs3d_endless_prefix_unit(unit_header_bytes(unit.payload));
                                 }),
                          ErrorKind::kInvalidCode, "motion_residual", 1));
  return suite;
}

// Frame order, an intra frame's faces, a position one past its range.
std::vector<SuiteCase> bfs3d_rules_rejected(const std::vector<SuiteCase>& valid) {
  std::vector<SuiteCase> suite;
  const std::vector<uint8_t> bfs3d = stream_of(valid, "bfs3d-01-average");
  suite.push_back(invalid("x-109-bfs3d-frame-gap", "frame 2 labelled frame 3", {"bfs3d"},
                          edited(bfs3d, [](ContainerParts& p) { put_field(unit_of(p, UnitType::kFrame, 2).payload, unit_header_field("frame_index"), 3); }),
                          ErrorKind::kStructure, "frame_index", 2));
  suite.push_back(invalid("x-110-bfs3d-intra-other-faces", "an intra base mesh at frame 2 with other faces", {"bfs3d"},
                          with_intra_of_other_faces(bfs3d, Encode3dOptions{}), ErrorKind::kStructure, "base_mesh", 2));
  suite.push_back(invalid("x-111-bfs3d-position-beyond", "a vertex moved from the grid's origin to 2^26 + 1 on x", {"bfs3d"},
                          bfs3d_position_limits_stream(1), ErrorKind::kOutOfRange, "motion_residual", 1));
  return suite;
}

// prediction_mode one past its range.
std::vector<SuiteCase> bfs3d_header_rejected(const std::vector<SuiteCase>& valid) {
  std::vector<SuiteCase> suite;
  const std::vector<uint8_t> bfs3d = stream_of(valid, "bfs3d-01-average");
  const FieldBytes prediction = object_field<Bfs3dHeader>(bfs3d, "prediction_mode");
  suite.push_back(invalid("x-55-bfs3d-prediction-2", "prediction_mode 2", {"bfs3d"},
                          edited(bfs3d, [prediction](ContainerParts& p) { put_field(p.object_payload, prediction, 2); }), ErrorKind::kOutOfRange,
                          "prediction_mode", kNoPlane));
  return suite;
}

}  // namespace m4mesh::suite3d
