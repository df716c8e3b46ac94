// The cloth codec's streams (docs/codec_lcc.md) and those to reject.
#include <algorithm>
#include <cmath>
#include <filesystem>

#include "common/bit_cast.h"
#include "conformance/suite3d/cases.h"
#include "conformance/suite3d/inputs.h"
#include "conformance/suite3d/stream_edits.h"
#include "decoder/mesh3d/container_decoder.h"
#include "mesh3d/lcc.h"
#include "syntax/mesh3d/entropy_io.h"
#include "syntax/mesh3d/lcc.h"

namespace m4mesh::suite3d {

namespace {

// An lcc frame unit (stream mode) with its header and the symbols of
// `residuals`, an anchor's or a predicted frame's, written with the
// residual limit `rh_limit` (the header's, or more to write a value
// beyond it).
std::vector<uint8_t> lcc_unit(const LccHeader& header, bool predicted, LccIndices residuals, int32_t rh_limit,
                              std::vector<uint8_t> unit_header, int32_t theta_limit = 0) {
  syntax::ResidualCoder<syntax::kLccChannels> coder;
  syntax::EntropyWriteIO<false> symbols(syntax::SectionPlace{});
  syntax::describe_symbols(symbols, coder, predicted, residuals.direct, residuals.steps,
                           theta_limit ? theta_limit : int32_t{1} << header.theta_bits, rh_limit);
  const std::vector<uint8_t> bins = symbols.finish_bins(), raw = symbols.finish_raw();
  LccFrameData data{static_cast<uint32_t>(bins.size()), bins, raw};
  return unit_with(std::move(unit_header), data);
}

// An lcc frame unit of `stream` (stream mode), an anchor or a frame
// predicted between two, whose residuals are 0 but every rho's, `times`
// 2^rh_bits + `extra` (written even beyond what the syntax allows).
std::vector<uint8_t> lcc_rho_unit(const std::vector<uint8_t>& stream, std::vector<uint8_t> unit_header, bool predicted, int32_t times,
                                  int32_t extra) {
  const auto [object, header] = read_headers<LccHeader>(split_container(stream));
  const LccOrder order = lcc_order(decode_mesh3d(stream).faces, object.vertex_count);
  LccIndices residuals{std::vector<int32_t>(3 * order.direct.size()), std::vector<int32_t>(3 * order.steps.size())};
  const int32_t rho = times * (int32_t{1} << header.rh_bits) + extra;
  for (size_t i = 1; i < residuals.steps.size(); i += 3) residuals.steps[i] = rho;
  // The writer's limit, raised to let rho through (a predicted frame's residuals may reach twice the limit).
  const int32_t limit = std::max(int32_t{1} << header.rh_bits, predicted ? (rho + 1) / 2 : rho);
  return lcc_unit(header, predicted, std::move(residuals), limit, std::move(unit_header));
}

// An lcc stream (stream mode, temporal prediction with gop 2: the even
// frames but the last predicted, no hash units) of a strip of two quads at
// rest over `frames` frames, every frame unit written symbol by symbol:
// its residuals zero but where `fill(frame, predicted, residuals)` sets
// them, written whatever their range.
template <class Fill>
std::vector<uint8_t> lcc_strip_stream(uint32_t frames, int theta_bits, int rh_bits, Fill fill) {
  MeshSequence strip;
  strip.faces = sheet_faces(2, 1);
  strip.vertex_count = 6;
  for (uint32_t f = 0; f < frames; ++f) strip.frames.push_back({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 0, 1}, {1, 0.25, 1}, {2, 0, 1}});
  Encode3dOptions o = lcc({{"theta-bits", std::to_string(theta_bits)}, {"rh-bits", std::to_string(rh_bits)}, {"temporal", "1"}, {"gop", "2"}});
  o.hashes = false;
  const std::vector<uint8_t> encoded = encode_mesh3d(strip, o).stream;
  const LccHeader header = read_headers<LccHeader>(split_container(encoded)).second;
  const LccOrder order = lcc_order(strip.faces, strip.vertex_count);
  return edited(encoded, [&](ContainerParts& p) {
    for (ContainerUnit& unit : p.units) {
      const UnitHeader unit_header = unit_header_of(unit.payload);
      if (unit_header.type() != UnitType::kFrame) continue;
      const uint32_t frame = unit_header.frame_index;
      const bool predicted = frame % 2 == 0 && frame + 1 < frames;
      LccIndices residuals{std::vector<int32_t>(3 * order.direct.size()), std::vector<int32_t>(3 * order.steps.size())};
      fill(frame, predicted, residuals);
      // The writer's limits, four times the header's: the decoder checks.
      unit.payload = lcc_unit(header, predicted, std::move(residuals), 4 << header.rh_bits, unit_header_bytes(unit.payload), 4 << header.theta_bits);
    }
  });
}

// lcc_strip_stream() at b_θ 15, b_rh 20: per pattern p of
// for_each_prefix_pattern(), the anchor at frame 2p + 1 and the frame
// predicted at 2p + 2 take the pattern's values as the residuals of their
// first two steps' θ, ρ and ζ.
std::vector<uint8_t> lcc_written_stream() {
  std::vector<std::pair<int32_t, int32_t>> patterns;
  for_each_prefix_pattern(13, [&](int32_t first, int32_t second) { patterns.emplace_back(first, second); });
  return lcc_strip_stream(static_cast<uint32_t>(2 * patterns.size() + 2), 15, 20, [&](uint32_t frame, bool predicted, LccIndices& residuals) {
    const size_t pattern = predicted ? frame / 2 - 1 : (frame - 1) / 2;
    if (pattern < patterns.size())
      for (size_t i = 0; i < 3; ++i) {
        residuals.steps[i] = patterns[pattern].first;
        residuals.steps[3 + i] = patterns[pattern].second;
      }
  });
}

// lcc_strip_stream() at b_θ 6, b_rh 4 over frames 0 … 3 with its values at
// their limits: anchors 1 and 3 alike, their first step's θ, ρ and ζ at
// the lowest (−2^b_θ, −2^b_rh), their second's at the highest (2^b_θ − 1,
// 2^b_rh); frame 2, predicted from them, moves ρ and ζ to the other end by
// residuals ±2^(b_rh+1) and θ by the extreme residuals again. `edit` may
// change a frame's residuals afterwards.
template <class Edit>
std::vector<uint8_t> lcc_limits_stream(Edit edit) {
  constexpr int kThetaBits = 6, kRhBits = 4;
  constexpr int32_t kTheta = 1 << kThetaBits, kRh = 1 << kRhBits;
  return lcc_strip_stream(4, kThetaBits, kRhBits, [&](uint32_t frame, bool predicted, LccIndices& residuals) {
    const int32_t rh = predicted ? 2 * kRh : kRh;
    for (size_t i = 0; i < 3; ++i) {
      residuals.steps[i] = i == 0 ? -kTheta : predicted ? rh : -rh;
      residuals.steps[3 + i] = i == 0 ? kTheta - 1 : predicted ? -rh : rh;
    }
    edit(frame, residuals);
  });
}

// An lcc stream (b_θ 12, b_rh 20, σ 2^14, a 24-bit grid of unit steps, no
// hash units) whose frame 1 is written symbol by symbol: per angle entry
// from 7/8 to 9/8 of the first octant (where a sine or cosine series cut
// short errs first), a quad whose directly coded triangle, axis-aligned,
// moves so that the vertex placed from it at that angle lands within
// 2^−29 of its distance from the triangle of the planes x = 0 and z = 0:
// its binary32 x and z then follow the last bit of the entry's cosine and
// sine.
std::vector<uint8_t> lcc_rounding_edges_stream() {
  constexpr int kThetaBits = 12, kRhBits = 20;
  constexpr uint32_t kFirstEntry = 896, kLastEntry = 1152;  // the first octant ends at entry 1024
  constexpr double kMiddle = 1 << 23, kEdge = 1 << 10;
  MeshSequence quads;
  std::vector<Vec3> frame;
  for (uint32_t m = kFirstEntry; m <= kLastEntry; ++m) {
    const NodeIndex a = static_cast<NodeIndex>(frame.size());
    quads.faces.push_back({{a, a + 1, a + 2}});
    quads.faces.push_back({{a + 2, a + 1, a + 3}});
    frame.push_back({kMiddle - kEdge, kMiddle, kMiddle});
    frame.push_back({kMiddle, kMiddle, kMiddle});
    frame.push_back({kMiddle, kMiddle + kEdge, kMiddle});
    frame.push_back({kMiddle + kEdge, kMiddle + kEdge / 2, kMiddle});  // in the plane, across the edge: height 0
  }
  frame.push_back({0, 0, 0});  // the box of a grid step 1
  frame.push_back({(1 << 24) - 1, (1 << 24) - 1, (1 << 24) - 1});
  quads.vertex_count = static_cast<uint32_t>(frame.size());
  quads.frames = {frame, frame};
  Encode3dOptions o = lcc({{"theta-bits", std::to_string(kThetaBits)}, {"rh-bits", std::to_string(kRhBits)}, {"bits", "24"}});
  o.hashes = false;
  std::vector<uint8_t> stream = encode_mesh3d(quads, o).stream;
  const FieldBytes rh_range = object_field<LccHeader>(stream, "rh_range");
  stream = edited(stream, [&](ContainerParts& p) {
    const uint32_t sigma = bit_cast<uint32_t>(16384.0f);  // radii up to 2^14 edge lengths
    put_field(p.object_payload, rh_range, sigma);
  });
  const LccHeader header = read_headers<LccHeader>(split_container(stream)).second;
  const std::vector<Triangle> faces = decode_mesh3d(stream).faces;
  const LccModel model(faces, frame, kThetaBits, kRhBits, header.rh_range_value());
  const LccOrder& order = model.order();
  LccIndices residuals{std::vector<int32_t>(3 * order.direct.size()), std::vector<int32_t>(3 * order.steps.size())};
  std::vector<size_t> direct_slot(frame.size());
  for (size_t i = 0; i < order.direct.size(); ++i) direct_slot[order.direct[i]] = i;
  for (size_t k = 0; k < order.steps.size(); ++k) {
    const LccStep& step = order.steps[k];
    const int32_t theta = static_cast<int32_t>(kFirstEntry + step.d / 4) - (int32_t{1} << kThetaBits);
    std::vector<Vec3> moved = frame;
    for (int32_t rho = int32_t{1} << kRhBits;; --rho) {
      const Vec3 far = model.place(k, frame, theta, rho, 0);
      const Vec3 shift{-std::nearbyint(far.x), 0, -std::nearbyint(far.z)};
      for (NodeIndex v : {step.a, step.b, step.c}) moved[v] = {frame[v].x + shift.x, frame[v].y, frame[v].z + shift.z};
      const Vec3 near = model.place(k, moved, theta, rho, 0);
      const double origin_x = frame[step.b].x, origin_z = frame[step.b].z;  // the edge's middle, before the move
      if (std::fabs(near.x) > std::ldexp(std::fabs(far.x - origin_x), -29) || std::fabs(near.z) > std::ldexp(std::fabs(far.z - origin_z), -29))
        continue;
      for (NodeIndex v : {step.a, step.b, step.c}) {
        residuals.direct[3 * direct_slot[v]] = static_cast<int32_t>(shift.x);
        residuals.direct[3 * direct_slot[v] + 2] = static_cast<int32_t>(shift.z);
      }
      residuals.steps[3 * k] = theta;
      residuals.steps[3 * k + 1] = rho;
      break;
    }
  }
  return edited(stream, [&](ContainerParts& p) {
    ContainerUnit& unit = unit_of(p, UnitType::kFrame, 1);
    unit.payload = lcc_unit(header, false, std::move(residuals), int32_t{1} << kRhBits, unit_header_bytes(unit.payload));
  });
}

}  // namespace

// The cloth codec's streams: both modes, a rest-shape reference, the
// smallest and largest bit counts, a degenerate triangle on the path,
// temporal prediction in both modes.
std::vector<SuiteCase> lcc_cases(bool traced) {
  const MeshSequence flag = waving_flag(6, 8, false);
  MeshSequence moving = flag;
  moving.frames.erase(moving.frames.begin());  // frame 0 waves already: coded against itself as the reference
  const std::string rest = rest_shape_file(flag);
  std::vector<SuiteCase> suite;
  suite.push_back(valid("lcc-01-stream", "lcc, stream mode, b_θ 6, b_rh from Eq. 1", {"container", "lcc"}, moving, lcc({}), traced));
  suite.push_back(valid("lcc-02-download", "lcc, download mode: contexts and direct vertices carried across frames", {"lcc"}, moving,
                        lcc({{"mode", "download"}}), traced));
  suite.push_back(valid("lcc-03-rest-shape", "lcc against a rest shape that is not a frame: frame 0 coded too", {"lcc"}, flag,
                        lcc({{"reference", rest}, {"theta-bits", "5"}}), traced));
  suite.push_back(valid("lcc-04-fewest-bits", "b_θ 2, b_rh 1", {"lcc"}, moving, lcc({{"theta-bits", "2"}, {"rh-bits", "1"}, {"bits", "4"}}), traced));
  suite.push_back(valid("lcc-05-most-bits", "b_θ 15, b_rh 20, a 16-bit grid", {"lcc"}, moving,
                        lcc({{"theta-bits", "15"}, {"rh-bits", "20"}, {"bits", "16"}}), traced));
  suite.push_back(valid("lcc-06-degenerate", "a triangle on the coding path with a zero edge", {"lcc"}, waving_flag(4, 6, true), lcc({}), traced));
  MeshSequence longer = waving_flag(13, 8, false);
  suite.push_back(valid("lcc-07-temporal-stream", "lcc, stream mode, temporal prediction: anchors every 4 frames and the last, midpoints between",
                        {"lcc", "lcc-temporal"}, MeshSequence{longer.vertex_count, longer.faces, {longer.frames.begin() + 1, longer.frames.end()}},
                        lcc({{"temporal", "1"}, {"gop", "4"}}), traced));
  suite.push_back(valid("lcc-08-temporal-download", "lcc, download mode, temporal prediction every 8 frames against a rest shape",
                        {"lcc", "lcc-temporal"}, longer, lcc({{"temporal", "1"}, {"gop", "8"}, {"mode", "download"}, {"reference", rest}}),
                        traced));
  // A 1-ulp difference in an angle or a frame axis moves a decoded binary64
  // position by far less than a binary32 step: it shows in the output only
  // after a long chain of steps, and then in a few coordinates.
  suite.push_back(valid("lcc-11-spikes", "vertices that jump by 2^−2 … 2^−23 of the box on a 24-bit grid, b_θ 15, b_rh 20", {"lcc"},
                        spiky_sheet(8, 16, 100, 44, 40), lcc({{"theta-bits", "15"}, {"rh-bits", "20"}, {"bits", "24"}}), traced));
  suite.push_back(valid("lcc-12-spikes-temporal", "lcc-11's jumps under temporal prediction, an anchor every 4 frames", {"lcc", "lcc-temporal"},
                        spiky_sheet(9, 16, 100, 45, 40), lcc({{"theta-bits", "15"}, {"rh-bits", "20"}, {"bits", "24"}, {"temporal", "1"}, {"gop", "4"}}),
                        traced));
  {
    // The first face, coded directly, on a line parallel to z in the last
    // frame: the steps from it take the tie rule's axis x.
    MeshSequence line = waving_flag(4, 6, false);
    std::vector<Vec3>& last = line.frames.back();
    for (int k = 0; k < 3; ++k) last[line.faces[0].v[static_cast<size_t>(k)]] = {0.5, 0.25, 0.25 * k};
    suite.push_back(valid("lcc-13-vertical-line", "a triangle on a line parallel to z: the degenerate frame's axis by the tie rule", {"lcc"}, line,
                          lcc({}), traced));
  }
  {
    // The first face's v1 and v2, coded directly, at one point in the
    // reference and in the last frame: the step across their edge takes
    // the zero edge's axis x, for the reference's radius and height and for
    // the frame's reconstruction.
    MeshSequence zero_edge = waving_flag(4, 6, false);
    const Triangle& first = zero_edge.faces[0];
    for (std::vector<Vec3>* frame : {&zero_edge.frames.front(), &zero_edge.frames.back()}) (*frame)[first.v[2]] = (*frame)[first.v[1]];
    suite.push_back(valid("lcc-21-zero-edge", "a step whose edge b c has length 0 in the reference and in a frame: the axis x as its z", {"lcc"},
                          zero_edge, lcc({}), traced));
  }
  suite.push_back(valid("lcc-22-one-frame-temporal", "one frame, reference_mode 0, temporal_gop 4: the base mesh is frame 0, and no frame unit follows",
                        {"lcc", "lcc-temporal"}, MeshSequence{longer.vertex_count, longer.faces, {longer.frames.front()}},
                        lcc({{"temporal", "1"}, {"gop", "4"}}), traced));
  {
    // Directly coded vertices whose residuals follow prefix_schedule(), in
    // stream mode (contexts reset per frame, residuals against the
    // reference), then under temporal prediction: anchors at odd frames
    // (frame 0 is the reference), midpoints at even frames whose residual
    // is their offset less the mean of their anchors'.
    const std::vector<int32_t> schedule = prefix_schedule();
    constexpr int kLoose = 429;  // 10 frames of the schedule
    const int per_frame = static_cast<int>(schedule.size() + kLoose - 1) / kLoose;
    auto at = [&](int j, int v) { return static_cast<size_t>(j * kLoose + v) < schedule.size() ? schedule[static_cast<size_t>(j * kLoose + v)] : 0; };
    suite.push_back(valid("lcc-14-direct-prefixes", "vertices in no face whose grid residuals take every prefix length 0 … 13 after each class",
                          {"lcc"}, designed_loose(per_frame + 1, kLoose, [&](int f, int v) { return at(f - 1, v); }), lcc({{"bits", "16"}}),
                          traced));
    auto anchor = [&](int f, int v) { return at((f - 1) / 2, v); };
    auto temporal = [&](int f, int v) {
      return f % 2 ? anchor(f, v) : static_cast<int32_t>((int64_t{anchor(f - 1, v)} + anchor(f + 1, v)) >> 1) + at(f / 2 - 1, v);
    };
    suite.push_back(valid("lcc-15-direct-prefixes-temporal", "lcc-14's residuals at anchors and again at the midpoints between them, gop 2",
                          {"lcc", "lcc-temporal"}, designed_loose(2 * per_frame + 2, kLoose, temporal),
                          lcc({{"bits", "16"}, {"temporal", "1"}, {"gop", "2"}}), traced));
  }
  suite.push_back(written_case("lcc-16-written", "a stream written symbol by symbol: θ, ρ and ζ residuals of every prefix length 0 … 13 "
                              "after each class, at anchors and at frames predicted between them", {"lcc", "lcc-temporal"}, lcc_written_stream()));
  suite.push_back(written_case("lcc-17-rounding-edges", "vertices whose binary32 x and z follow the last bit of the cosine and sine of "
                               "the angle entries around the first octant's end (written symbol by symbol)", {"lcc"},
                               lcc_rounding_edges_stream()));
  suite.push_back(valid("lcc-09-long-chains", "a 200 × 3 strip at b_θ 12: chains of 600 steps, where a 1-ulp angle or axis changes the output",
                        {"lcc"}, waving_strip(6, 200, 3), lcc({{"theta-bits", "12"}}), traced));
  suite.push_back(valid("lcc-10-long-chains-coarse", "a 400 × 3 strip at b_θ 2: every angle a multiple of π/4, the table's octant ends",
                        {"lcc"}, waving_strip(6, 400, 3), lcc({{"theta-bits", "2"}}), traced));
  suite.push_back(written_case("lcc-19-limits", "θ, ρ and ζ at both ends of their ranges in anchors, and ρ and ζ residuals of ±2^(b_rh+1) "
                               "in a predicted frame, written symbol by symbol", {"lcc", "lcc-temporal"},
                               lcc_limits_stream([](uint32_t, LccIndices&) {})));
  suite.push_back(written_case("lcc-20-direct-limits", "lcc-19 with frame 1's first directly coded vertex, at the grid's origin, moved to "
                               "2^26 on x and −2^26 on y", {"lcc"}, lcc_limits_stream([](uint32_t frame, LccIndices& r) {
                                 if (frame == 1) {
                                   r.direct.at(0) = 1 << 26;
                                   r.direct.at(1) = -(1 << 26);
                                 }
                               })));
  suite.push_back(valid("lcc-18-gop-64", "temporal prediction over the longest group, temporal_gop 64: anchors 0, 64 and 65, midpoints between",
                        {"lcc-temporal"}, waving_flag(66, 4, false), lcc({{"temporal", "1"}, {"gop", "64"}}), traced));
  std::filesystem::remove(rest);
  return suite;
}

// Header ranges, a second base mesh, temporal prediction's order and rho's range.
std::vector<SuiteCase> lcc_rejected(const std::vector<SuiteCase>& valid) {
  std::vector<SuiteCase> suite;
  // The lcc header's fields, found by name in the description of the stream's own headers.
  const std::vector<uint8_t> cloth = stream_of(valid, "lcc-01-stream");
  auto lcc_field = [&cloth](const char* name) { return object_field<LccHeader>(cloth, name); };
  suite.push_back(invalid("x-14-lcc-theta-bits", "theta_bits 16", {"lcc"},
                          edited(cloth, [&](ContainerParts& p) { put_field(p.object_payload, lcc_field("theta_bits"), 16); }), ErrorKind::kOutOfRange,
                          "theta_bits", kNoPlane));
  suite.push_back(invalid("x-15-lcc-rh-range-zero", "rh_range 0", {"lcc"},
                          edited(cloth,
                                 [&](ContainerParts& p) { put_field(p.object_payload, lcc_field("rh_range"), 0); }),
                          ErrorKind::kOutOfRange, "rh_range", kNoPlane));
  suite.push_back(invalid("x-16-lcc-second-base-mesh", "a second base mesh unit in place of frame 2", {"lcc"},
                          edited(cloth,
                                 [](ContainerParts& p) {
                                   std::vector<uint8_t> again = unit_of(p, UnitType::kBaseMesh, 0).payload;
                                   again[4] = 2;
                                   unit_of(p, UnitType::kFrame, 2).payload = again;
                                 }),
                          ErrorKind::kStructure, "unit_type", 2));
  const struct {
    const char* id;
    const char* purpose;
    const char* field;
    uint8_t value;
  } lcc_ranges[] = {{"x-17-lcc-quantization-bits", "quantization_bits 25", "quantization_bits", 25},
                    {"x-18-lcc-reference-mode", "reference_mode 2", "reference_mode", 2},
                    {"x-19-lcc-coding-mode", "coding_mode 2", "coding_mode", 2},
                    {"x-20-lcc-rh-bits", "rh_bits 21", "rh_bits", 21},
                    {"x-21-lcc-gop-one", "temporal_gop 1 (no temporal prediction is 0)", "temporal_gop", 1},
                    {"x-22-lcc-gop-65", "temporal_gop 65", "temporal_gop", 65}};
  for (const auto& c : lcc_ranges)
    suite.push_back(invalid(c.id, c.purpose, {"lcc"}, edited(cloth, [&](ContainerParts& p) { put_field(p.object_payload, lcc_field(c.field), c.value); }),
                            ErrorKind::kOutOfRange, c.field, kNoPlane));
  const std::vector<uint8_t> temporal = stream_of(valid, "lcc-07-temporal-stream");
  suite.push_back(invalid("x-23-lcc-temporal-no-frame-count", "temporal prediction with frame_count 0 (unknown)", {"lcc-temporal"},
                          edited(temporal,
                                 [&](ContainerParts& p) { put_field(p.object_payload, lcc_field("frame_count"), 0); }),
                          ErrorKind::kStructure, "temporal_gop", kNoPlane));
  suite.push_back(invalid("x-24-lcc-temporal-display-order", "a unit labelled frame 2 where the order has anchor 9", {"lcc-temporal"},
                          edited(temporal,
                                 [](ContainerParts& p) {
                                   put_field(unit_of(p, UnitType::kFrame, 9).payload, unit_header_field("frame_index"), 2);
                                 }),
                          ErrorKind::kStructure, "frame_index", 9));
  // Frame 3, predicted from frames 1 and 5, with every rho residual
  // 2^(rh_bits+1): prediction plus residual leave the range.
  suite.push_back(invalid("x-25-lcc-rho-beyond-prediction", "predicted frame 3 whose rho residuals push rho beyond ±2^rh_bits",
                          {"lcc-temporal"}, edited(temporal, [&](ContainerParts& p) {
                            ContainerUnit& unit = unit_of(p, UnitType::kFrame, 3);
                            unit.payload = lcc_rho_unit(temporal, unit_header_bytes(unit.payload), true, 2, 0);
                          }),
                          ErrorKind::kOutOfRange, "rho", 3));
  // Frame 1 of a stream without temporal prediction, an anchor, with every
  // rho residual 2^rh_bits + 1: one beyond an anchor's range, within a
  // predicted frame's.
  suite.push_back(invalid("x-56-lcc-anchor-rho", "an anchor whose rho residuals are 2^rh_bits + 1", {"lcc"},
                          edited(cloth, [&](ContainerParts& p) {
                            ContainerUnit& unit = unit_of(p, UnitType::kFrame, 1);
                            unit.payload = lcc_rho_unit(cloth, unit_header_bytes(unit.payload), false, 1, 1);
                          }),
                          ErrorKind::kOutOfRange, "rho", 1));
  // lcc-19 with one value one past its range.
  const struct {
    const char* id;
    const char* purpose;
    uint32_t frame;
    size_t index;  // into the frame's step residuals, or the direct ones when `direct`
    int32_t value;
    const char* element;
    bool direct = false;
  } limits[] = {
      {"x-103-lcc-theta-high", "an anchor's theta residual 2^b_θ, one past the highest", 1, 3, 1 << 6, "theta"},
      {"x-104-lcc-theta-low", "a predicted frame's theta residual −2^b_θ − 1, one past the lowest", 2, 0, -(1 << 6) - 1, "theta"},
      {"x-105-lcc-zeta-anchor", "an anchor's zeta residual 2^b_rh + 1", 3, 5, (1 << 4) + 1, "zeta"},
      {"x-106-lcc-zeta-predicted", "a predicted frame's zeta residual −2^(b_rh+1) − 1", 2, 5, -(1 << 5) - 1, "zeta"},
      {"x-107-lcc-zeta-beyond-prediction", "a predicted frame's zeta residual −1 on a prediction of −2^b_rh: an index one below the lowest", 2, 2,
       -1, "zeta"},
      {"x-108-lcc-direct-beyond", "an anchor's direct_position residual 2^27: a grid index beyond 2^26", 1, 0, 1 << 27, "direct_position", true},
  };
  for (const auto& c : limits)
    suite.push_back(invalid(c.id, c.purpose, {"lcc"}, lcc_limits_stream([&](uint32_t frame, LccIndices& r) {
                              if (frame == c.frame) (c.direct ? r.direct : r.steps).at(c.index) = c.value;
                            }),
                            ErrorKind::kOutOfRange, c.element, c.frame));
  suite.push_back(invalid("x-117-lcc-frame-after-last", "frame 1's unit again after the last frame", {"lcc"},
                          edited(cloth, [](ContainerParts& p) { p.units.push_back(unit_of(p, UnitType::kFrame, 1)); }), ErrorKind::kStructure,
                          "frame_index", 1));
  const FieldBytes length = unit_field<LccFrameData>("arithmetic_bytes");
  suite.push_back(invalid("x-118-lcc-arithmetic-bytes", "arithmetic_bytes longer than the frame", {"lcc"},
                          edited(cloth, [&](ContainerParts& p) { put_field(unit_of(p, UnitType::kFrame, 2).payload, length, 0x7F000000); }),
                          ErrorKind::kOutOfRange, "arithmetic_bytes", 2));
  suite.push_back(invalid("x-119-lcc-bins-left-over", "a byte after the last bin, counted by arithmetic_bytes", {"lcc"},
                          edited(cloth, [&](ContainerParts& p) { add_bins_byte(unit_of(p, UnitType::kFrame, 2).payload, length); }),
                          ErrorKind::kStructure, "theta", 2));
  return suite;
}

}  // namespace m4mesh::suite3d
