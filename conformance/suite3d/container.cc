// The container's own streams (docs/container3d.md): group hash units, and
// streams that break the container's rules.
#include <utility>

#include "conformance/suite3d/cases.h"
#include "conformance/suite3d/inputs.h"
#include "conformance/suite3d/stream_edits.h"
#include "syntax/mesh3d/affine_octree.h"

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
  {
    // An intra base mesh whose faces are not frame 0's.
    MeshSequence other = box_and_sheet(6, 4);
    std::swap(other.faces[0], other.faces[1]);
    const std::vector<uint8_t> other_stream = encode_mesh3d(other, affine("1")).stream;
    const std::vector<uint8_t> intra = split_container(other_stream).units[0].payload;
    suite.push_back(invalid("x-09-intra-other-faces", "an intra base mesh with other faces", {"container-units"},
                            edited(base,
                                   [&](ContainerParts& p) {
                                     ContainerUnit& unit = unit_of(p, UnitType::kFrame, 2);
                                     unit.payload = intra;
                                     put_field(unit.payload, unit_header_field("frame_index"), 2);
                                   }),
                            ErrorKind::kStructure, "base_mesh", 2));
  }
  return suite;
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
  suite.push_back(invalid("x-52-version", "version 2", {"container"}, edited(base, [&](ContainerParts& p) { put_field(p.object_payload, object_field<AffineOctreeHeader>(base, "version"), 2); }),
                          ErrorKind::kReservedValue, "version", kNoPlane));
  return suite;
}

}  // namespace m4mesh::suite3d
