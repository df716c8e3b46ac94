// The container's own streams (docs/container3d.md): group hash units, and
// streams that break the container's rules.
#include <cstdio>
#include <utility>

#include "conformance/suite3d/cases.h"
#include "conformance/suite3d/inputs.h"
#include "conformance/suite3d/stream_edits.h"
#include "syntax/mesh3d/affine_octree.h"
#include "syntax/mesh3d/base_mesh.h"
#include "syntax/mesh3d/bfs3d.h"
#include "syntax/mesh3d/entropy_io.h"

namespace m4mesh::suite3d {

// Group hash units: after frame-by-frame units, and after frames decoded
// out of display order.
std::vector<SuiteCase> group_hash_cases(bool traced) {
  std::vector<SuiteCase> suite;
  suite.push_back(valid("hash-01-groups", "bfs3d with a group hash unit per 4 frames, the last group shorter", {"container-hash"},
                        box_and_sheet(10, 3), Encode3dOptions{}, traced, 4));
  const MeshSequence flag = waving_flag(13, 8, false);
  suite.push_back(valid("hash-02-groups-out-of-order", "lcc with temporal prediction and a group hash unit per 3 frames", {"container-hash"},
                        flag, lcc({{"temporal", "1"}, {"gop", "4"}}), traced, 3));
  return suite;
}

// codec_id values no codec has.
std::vector<SuiteCase> container_header_rejected(const std::vector<SuiteCase>& valid) {
  std::vector<SuiteCase> suite;
  const std::vector<uint8_t> base = stream_of(valid, "ao-01-me1-k16");
  const FieldBytes codec_id = object_field<AffineOctreeHeader>(base, "codec_id");
  suite.push_back(invalid("x-01-codec-unknown", "codec_id 5 is not registered", {"container"},
                          edited(base, [&](ContainerParts& p) { put_field(p.object_payload, codec_id, 5); }), ErrorKind::kReservedValue, "codec_id", kNoPlane));
  suite.push_back(invalid("x-02-codec-zero", "codec_id 0 is reserved", {"container"},
                          edited(base, [&](ContainerParts& p) { put_field(p.object_payload, codec_id, 0); }), ErrorKind::kReservedValue, "codec_id", kNoPlane));
  return suite;
}

// Frame units out of order, missing, or an intra base mesh of other faces.
std::vector<SuiteCase> container_unit_rejected(const std::vector<SuiteCase>& valid) {
  std::vector<SuiteCase> suite;
  const std::vector<uint8_t> base = stream_of(valid, "ao-01-me1-k16");
  suite.push_back(invalid("x-07-frame-gap", "frame 2 labelled frame 3", {"container-units"},
                          edited(base, [](ContainerParts& p) { put_field(unit_of(p, UnitType::kFrame, 2).payload, unit_header_field("frame_index"), 3); }),
                          ErrorKind::kStructure, "frame_index", 2));
  suite.push_back(invalid("x-08-missing-frames", "frame_count 6, the stream ends after frame 3", {"container-units"},
                          edited(base, [](ContainerParts& p) {
                            while (unit_header_of(p.units.back().payload).frame_index > 3) p.units.pop_back();
                          }),
                          ErrorKind::kTruncated, "mesh3d_unit_start_code", 4));
  suite.push_back(invalid("x-09-intra-other-faces", "an intra base mesh with other faces", {"container-units"},
                          with_intra_of_other_faces(base, affine("1")), ErrorKind::kStructure, "base_mesh", 2));
  return suite;
}

std::vector<uint8_t> with_intra_of_other_faces(const std::vector<uint8_t>& stream, const Encode3dOptions& o) {
  MeshSequence other = box_and_sheet(6, 4);
  std::swap(other.faces[0], other.faces[1]);
  const std::vector<uint8_t> intra = split_container(encode_mesh3d(other, o).stream).units[0].payload;
  return edited(stream, [&](ContainerParts& p) {
    ContainerUnit& unit = unit_of(p, UnitType::kFrame, 2);
    unit.payload = intra;
    put_field(unit.payload, unit_header_field("frame_index"), 2);
  });
}

// Group hash units that cover frames not decoded, none, or past the end.
std::vector<SuiteCase> group_hash_rejected(const std::vector<SuiteCase>& valid) {
  std::vector<SuiteCase> suite;
  // Group hash units (after hash-01's frame 3, a group of frames 0 … 3).
  const std::vector<uint8_t> grouped = stream_of(valid, "hash-01-groups");
  auto first_group = [](ContainerParts& p) -> ContainerUnit& {
    for (ContainerUnit& unit : p.units)
      if (unit_header_of(unit.payload).type() == UnitType::kGroupHash) return unit;
    throw Error(ErrorKind::kStructure, "", kNoPlane, kNoOffset, "suite: no group hash unit");
  };
  const FieldBytes group_frames = unit_field<GroupHash>("group_frames");
  suite.push_back(invalid("x-42-group-ahead", "a group hash of frames 0 … 4 after frame 3", {"container-hash"},
                          edited(grouped, [&](ContainerParts& p) { put_field(first_group(p).payload, group_frames, 5); }), ErrorKind::kStructure,
                          "group_frames", 0));
  suite.push_back(invalid("x-43-group-empty", "group_frames 0", {"container-hash"},
                          edited(grouped, [&](ContainerParts& p) { put_field(first_group(p).payload, group_frames, 0); }), ErrorKind::kOutOfRange,
                          "group_frames", 0));
  suite.push_back(invalid("x-44-group-beyond", "a group of frames 8 … 10 where frame_count is 10: one frame past the end", {"container-hash"},
                          edited(grouped,
                                 [&](ContainerParts& p) {
                                   ContainerUnit& last = p.units[p.units.size() - 1];
                                   put_field(last.payload, group_frames, 3);  // frames 8 and 9 are the last group
                                 }),
                          ErrorKind::kStructure, "group_frames", 8));
  suite.push_back(invalid("x-45-group-md5-cut", "a group hash unit one byte short", {"container-hash"},
                          edited(grouped, [&](ContainerParts& p) { first_group(p).payload.pop_back(); }), ErrorKind::kOutOfRange,
                          "group_md5", 0));
  // Two rules broken at once: the digest's size is checked before the group's frames.
  suite.push_back(invalid("x-172-group-md5-cut-and-ahead", "x-42's group of frames 0 … 4 after frame 3, its digest one byte short",
                          {"container-hash"},
                          edited(grouped,
                                 [&](ContainerParts& p) {
                                   put_field(first_group(p).payload, group_frames, 5);
                                   first_group(p).payload.pop_back();
                                 }),
                          ErrorKind::kOutOfRange, "group_md5", 0));
  // A hash unit's frame_index is checked by the group's rules, not by rule 3 (below frame_count).
  suite.push_back(invalid("x-184-group-at-frame-count", "hash-01's last group hash labelled frame 10, frame_count", {"container-hash"},
                          edited(grouped,
                                 [&](ContainerParts& p) { put_field(p.units[p.units.size() - 1].payload, unit_header_field("frame_index"), 10); }),
                          ErrorKind::kStructure, "group_frames", 10));
  suite.push_back(invalid("x-179-group-md5-differs", "hash-01's first group hash with the last bit of its digest flipped", {"container-hash"},
                          edited(grouped, [&](ContainerParts& p) { first_group(p).payload.back() ^= 1; }), ErrorKind::kStructure, "group_md5", 0));
  return suite;
}

// Each at the edge of its rule, so that a decoder whose check is one off accepts it.
std::vector<SuiteCase> container_edge_rejected(const std::vector<SuiteCase>& valid) {
  std::vector<SuiteCase> suite;
  const std::vector<uint8_t> base = stream_of(valid, "ao-01-me1-k16");
  suite.push_back(invalid("x-50-frame-index-at-count", "a seventh frame unit labelled frame 6 where frame_count is 6", {"container-units"},
                          edited(base,
                                 [](ContainerParts& p) {
                                   ContainerUnit extra = unit_of(p, UnitType::kFrame, 5);
                                   put_field(extra.payload, unit_header_field("frame_index"), 6);
                                   p.units.push_back(std::move(extra));
                                 }),
                          ErrorKind::kStructure, "frame_index", 6));
  {
    std::vector<uint8_t> trailing = base;
    trailing.push_back(0x00);
    suite.push_back(invalid("x-51-trailing-byte", "a zero byte after the end code", {"container"}, trailing, ErrorKind::kTrailingData,
                            "mesh_object_end_code", kNoPlane));
  }
  // Format 1.0 is version 16; its neighbours are not defined.
  for (const auto& neighbour : {std::pair{"x-52-version", kFormatVersion + 1}, std::pair{"x-146-version", kFormatVersion - 1}}) {
    const uint32_t version = neighbour.second;
    suite.push_back(invalid(std::string(neighbour.first) + "-" + std::to_string(version), "version " + std::to_string(version) + ", format 1.0 is 16",
                            {"container"},
                            edited(base, [&](ContainerParts& p) { put_field(p.object_payload, object_field<AffineOctreeHeader>(base, "version"), version); }),
                            ErrorKind::kReservedValue, "version", kNoPlane));
  }
  return suite;
}

// The object header's ranges met at both ends: the smallest object, and
// the slowest and fastest frame rates.
std::vector<SuiteCase> container_cases(bool traced) {
  std::vector<SuiteCase> suite;
  MeshSequence triangle;
  triangle.vertex_count = 3;
  triangle.faces = {{{0, 1, 2}}};
  for (int f = 0; f < 3; ++f) triangle.frames.push_back({{0, 0, 0.5 * f}, {1, 0, 0.25 * f}, {0, 1, 0}});
  suite.push_back(valid("hdr-01-one-triangle", "vertex_count 3 and face_count 1: the smallest object", {"container"}, triangle,
                        Encode3dOptions{}, traced));
  for (const uint32_t rate : {65535u, 1u}) {
    Encode3dOptions o;
    o.frame_rate_num = rate;
    o.frame_rate_den = rate;
    suite.push_back(valid(rate == 1 ? "hdr-03-frame-rate-min" : "hdr-02-frame-rate-max",
                          "frame_rate_num and frame_rate_den " + std::to_string(rate) + ", the " + (rate == 1 ? "smallest" : "largest"),
                          {"container"}, box_and_sheet(3, 2), o, traced));
  }
  return suite;
}

namespace {

// How bfs3d_raw_unit damages its raw_x.
enum class RawDamage { kPaddingBitSet, kLastByteCut };

// A bfs3d frame unit of `vertex_count` residuals per axis, all 0 but the
// first x residual, whose raw bits do not end on a byte, with raw_x
// damaged: a padding bit set, or its last byte cut.
std::vector<uint8_t> bfs3d_raw_unit(std::vector<uint8_t> unit_header, uint32_t vertex_count, RawDamage damage) {
  Bfs3dFrame frame;
  std::vector<uint8_t> sections[3][2];
  for (int32_t first = 2;; ++first) {
    std::vector<int32_t> x(vertex_count, 0);
    x[0] = first;
    syntax::EntropyWriteIO<false> symbols(syntax::SectionPlace{});
    syntax::describe_axis(symbols, std::span<int32_t>(x));
    if (symbols.raw_bits() % 8 == 0) continue;
    sections[0][0] = symbols.finish_bins();
    sections[0][1] = symbols.finish_raw();
    if (damage == RawDamage::kPaddingBitSet) sections[0][1].back() |= 1;  // the last padding bit
    else sections[0][1].pop_back();
    break;
  }
  for (int axis = 1; axis < 3; ++axis) {
    std::vector<int32_t> zeros(vertex_count, 0);
    syntax::EntropyWriteIO<false> symbols(syntax::SectionPlace{});
    syntax::describe_axis(symbols, std::span<int32_t>(zeros));
    sections[axis][0] = symbols.finish_bins();
    sections[axis][1] = symbols.finish_raw();
  }
  for (int axis = 0; axis < 3; ++axis) {
    frame.arithmetic_bytes[axis] = static_cast<uint32_t>(sections[axis][0].size());
    frame.raw_bytes[axis] = static_cast<uint32_t>(sections[axis][1].size());
    frame.bins[axis] = sections[axis][0];
    frame.raw[axis] = sections[axis][1];
  }
  return unit_with(std::move(unit_header), frame);
}

}  // namespace

// The object and unit headers' ranges one past each end, bytes left after
// the codec header, the units' order and placement, and the end of a
// section: a bin or raw section one byte short, a raw section's padding not
// zero.
std::vector<SuiteCase> container_rules_rejected(const std::vector<SuiteCase>& valid) {
  std::vector<SuiteCase> suite;
  const std::vector<uint8_t> base = stream_of(valid, "bfs3d-01-average");
  const struct {
    const char* id;
    const char* purpose;
    const char* field;
    uint32_t value;
  } header_cases[] = {
      {"x-67-vertex-count-two", "vertex_count 2, one below the smallest", "vertex_count", 2},
      {"x-68-vertex-count-beyond", "vertex_count 2^24 + 1, one past the largest", "vertex_count", (1u << 24) + 1},
      {"x-69-face-count-zero", "face_count 0, one below the smallest", "face_count", 0},
      {"x-70-face-count-beyond", "face_count 2^25 + 1, one past the largest", "face_count", (1u << 25) + 1},
      {"x-71-frame-rate-num-zero", "frame_rate_num 0", "frame_rate_num", 0},
      {"x-72-frame-rate-den-zero", "frame_rate_den 0", "frame_rate_den", 0},
  };
  for (const auto& c : header_cases)
    suite.push_back(invalid(c.id, c.purpose, {"container"},
                            edited(base, [&](ContainerParts& p) { put_field(p.object_payload, object_field<Bfs3dHeader>(base, c.field), c.value); }),
                            ErrorKind::kOutOfRange, c.field, kNoPlane));
  suite.push_back(invalid("x-73-object-payload-left-over", "a byte after the codec header", {"container"},
                          edited(base, [](ContainerParts& p) { p.object_payload.push_back(0x00); }), ErrorKind::kStructure, "object_payload",
                          kNoPlane));
  suite.push_back(invalid("x-74-unit-type-5", "unit_type 5, one past the last", {"container-units"},
                          edited(base, [](ContainerParts& p) { put_field(unit_of(p, UnitType::kFrame, 1).payload, unit_header_field("unit_type"), 5); }),
                          ErrorKind::kOutOfRange, "unit_type", kNoPlane));
  suite.push_back(invalid("x-75-first-unit-a-frame", "the base mesh unit and its hash left out: frame 1's unit first", {"container-units"},
                          edited(base, [](ContainerParts& p) { p.units.erase(p.units.begin(), p.units.begin() + 2); }), ErrorKind::kStructure,
                          "unit_type", 1));
  suite.push_back(invalid("x-76-unit-type-unused", "a refinement unit in a bfs3d stream", {"container-units"},
                          edited(base,
                                 [](ContainerParts& p) {
                                   ContainerUnit refinement = unit_of(p, UnitType::kFrame, 1);
                                   put_field(refinement.payload, unit_header_field("unit_type"), static_cast<uint32_t>(UnitType::kRefinement));
                                   p.units.insert(p.units.begin() + 2, refinement);  // after the base mesh and its hash
                                 }),
                          ErrorKind::kStructure, "unit_type", kNoPlane));
  suite.push_back(invalid("x-77-frame-hash-ahead", "the frame hash unit after frame 1 labelled frame 2", {"container-hash"},
                          edited(base, [](ContainerParts& p) { put_field(unit_of(p, UnitType::kFrameHash, 1).payload, unit_header_field("frame_index"), 2); }),
                          ErrorKind::kStructure, "frame_index", 2));
  suite.push_back(invalid("x-178-frame-md5-differs", "the frame hash unit after frame 1 with the last bit of its digest flipped", {"container-hash"},
                          edited(base, [](ContainerParts& p) { unit_of(p, UnitType::kFrameHash, 1).payload.back() ^= 1; }), ErrorKind::kStructure,
                          "frame_md5", 1));
  // A frame hash's digest of the wrong size: placed at frame_index, the field read before it.
  suite.push_back(invalid("x-180-frame-md5-cut", "the frame hash unit after frame 1 one byte short", {"container-hash"},
                          edited(base, [](ContainerParts& p) { unit_of(p, UnitType::kFrameHash, 1).payload.pop_back(); }), ErrorKind::kOutOfRange,
                          "frame_md5", 1));
  suite.push_back(invalid("x-181-frame-md5-long", "the frame hash unit after frame 1 one byte long", {"container-hash"},
                          edited(base, [](ContainerParts& p) { unit_of(p, UnitType::kFrameHash, 1).payload.push_back(0x5A); }), ErrorKind::kStructure,
                          "frame_md5", 1));
  suite.push_back(invalid("x-176-frame-hash-behind", "the frame hash unit after frame 2 labelled frame 1, decoded by the unit before", {"container-hash"},
                          edited(base, [](ContainerParts& p) { put_field(unit_of(p, UnitType::kFrameHash, 2).payload, unit_header_field("frame_index"), 1); }),
                          ErrorKind::kStructure, "frame_index", 1));
  // Two rules broken at once: which one a decoder reports.
  suite.push_back(invalid("x-173-frame-hash-ahead-and-cut", "x-77's frame hash labelled frame 2, its digest one byte short: the frame is checked first",
                          {"container-hash"},
                          edited(base,
                                 [](ContainerParts& p) {
                                   std::vector<uint8_t>& hash = unit_of(p, UnitType::kFrameHash, 1).payload;
                                   put_field(hash, unit_header_field("frame_index"), 2);
                                   hash.pop_back();
                                 }),
                          ErrorKind::kStructure, "frame_index", 2));
  suite.push_back(invalid("x-175-unit-type-unused-and-frame-beyond", "x-76's refinement unit, its frame_index past frame_count: the unit type is checked first",
                          {"container-units"},
                          edited(base,
                                 [](ContainerParts& p) {
                                   ContainerUnit refinement = unit_of(p, UnitType::kFrame, 1);
                                   put_field(refinement.payload, unit_header_field("unit_type"), static_cast<uint32_t>(UnitType::kRefinement));
                                   put_field(refinement.payload, unit_header_field("frame_index"), 1000);
                                   p.units.insert(p.units.begin() + 2, refinement);
                                 }),
                          ErrorKind::kStructure, "unit_type", kNoPlane));
  suite.push_back(invalid("x-78-bins-one-byte-short", "frame 1's bins_x one byte short, arithmetic_bytes_x one less", {"container"},
                          edited(base,
                                 [](ContainerParts& p) {
                                   std::vector<uint8_t>& unit = unit_of(p, UnitType::kFrame, 1).payload;
                                   const FieldBytes length = unit_field<Bfs3dFrame>("arithmetic_bytes_x");
                                   const uint64_t bins = field_value(unit, length);
                                   unit.erase(unit.begin() + static_cast<std::ptrdiff_t>(unit_field<Bfs3dFrame>("bins_x").first + bins - 1));
                                   put_field(unit, length, bins - 1);
                                 }),
                          ErrorKind::kTruncated, "bins_x", 1));
  const uint32_t vertices = read_headers<Bfs3dHeader>(split_container(base)).first.vertex_count;
  const struct {
    const char* id;
    const char* purpose;
    RawDamage damage;
    ErrorKind kind;
    const char* element;
  } raw_damages[] = {{"x-79-raw-padding", "a padding bit of raw_x set", RawDamage::kPaddingBitSet, ErrorKind::kStructure, "raw_padding"},
                     {"x-151-raw-one-byte-short", "frame 1's raw_x one byte short, raw_bytes_x one less", RawDamage::kLastByteCut,
                      ErrorKind::kTruncated, "raw_x"}};
  for (const auto& d : raw_damages)
    suite.push_back(invalid(d.id, d.purpose, {"container"},
                            edited(base,
                                   [&](ContainerParts& p) {
                                     ContainerUnit& unit = unit_of(p, UnitType::kFrame, 1);
                                     unit.payload = bfs3d_raw_unit(unit_header_bytes(unit.payload), vertices, d.damage);
                                   }),
                            d.kind, d.element, 1));
  // A decoder that decodes zeros on past the end reports another error here (mutant ct-39).
  suite.push_back(invalid("x-152-base-bins-cut", "the base mesh's bins cut to their first 6 bytes (arithmetic_bytes 6): the traversal stops "
                          "where they end", {"container"},
                          edited(base,
                                 [](ContainerParts& p) {
                                   std::vector<uint8_t>& unit = unit_of(p, UnitType::kBaseMesh, 0).payload;
                                   const FieldBytes length = unit_field<BaseMeshData>("arithmetic_bytes");
                                   const auto bins = static_cast<std::ptrdiff_t>(field_value(unit, length));
                                   const auto first = static_cast<std::ptrdiff_t>(length.first + length.count);
                                   unit.erase(unit.begin() + first + 6, unit.begin() + first + bins);
                                   put_field(unit, length, 6);
                                 }),
                          ErrorKind::kTruncated, "bins", 0));
  return suite;
}

}  // namespace m4mesh::suite3d
