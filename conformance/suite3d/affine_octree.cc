// The Affine-Octree streams (docs/codec_affine_octree.md) and those to reject.
#include <cstdio>

#include "conformance/suite3d/cases.h"
#include "conformance/suite3d/inputs.h"
#include "conformance/suite3d/stream_edits.h"
#include "mesh3d/affine_octree.h"
#include "syntax/mesh3d/affine_octree.h"
#include "syntax/mesh3d/entropy_io.h"

namespace m4mesh::suite3d {

namespace {

// An Affine-Octree frame unit with its header and the one cell `cell` of
// `count` vertices, the root, written through `coder`.
std::vector<uint8_t> ao_root_unit(const AffineOctreeHeader& coder, uint32_t count, AffineCell cell, std::vector<uint8_t> unit_header,
                                  uint32_t direct_shift = 0) {
  AffineCellCoder cells(coder);
  syntax::EntropyWriteIO<false> symbols(syntax::SectionPlace{});
  cells.describe(symbols, 0, count, cell);
  const std::vector<uint8_t> bins = symbols.finish_bins(), raw = symbols.finish_raw();
  AffineFrame data{direct_shift, static_cast<uint32_t>(bins.size()), bins, raw};
  return unit_with(std::move(unit_header), data);
}

// An Affine-Octree frame unit of `stream` whose only cell, the root, is a
// leaf with the identity matrix but element `element` `value` (written
// with twice the range at the same fraction bits, to pass matrix_bits' range).
std::vector<uint8_t> ao_matrix_element_unit(const std::vector<uint8_t>& stream, size_t element, int32_t value, std::vector<uint8_t> unit_header) {
  const auto [object, header] = read_headers<AffineOctreeHeader>(split_container(stream));
  AffineOctreeHeader wider = header;
  ++wider.matrix_bits;
  ++wider.matrix_range_log2;
  AffineCell cell;
  for (int i = 0; i < 3; ++i) cell.matrix[static_cast<size_t>(5 * i)] = int32_t{1} << header.fraction_bits();
  cell.matrix[element] = value;
  return ao_root_unit(wider, object.vertex_count, cell, std::move(unit_header));
}

// An Affine-Octree frame unit of `stream` whose root, of more than 4
// vertices, is a leaf coded directly (m4mesh's encoder splits it instead):
// vertex v moves by v mod 3 − 1 steps on each axis.
std::vector<uint8_t> ao_direct_root_unit(const std::vector<uint8_t>& stream, std::vector<uint8_t> unit_header) {
  const auto [object, header] = read_headers<AffineOctreeHeader>(split_container(stream));
  AffineCell cell;
  cell.direct = true;
  for (uint32_t v = 0; v < object.vertex_count; ++v) {
    const int32_t d = static_cast<int32_t>(v % 3) - 1;
    cell.motion.push_back({d, d, d});
  }
  return ao_root_unit(header, object.vertex_count, cell, std::move(unit_header));
}

// A moving tetrahedron (no hash units) whose frame 1 is written: its
// root, 4 vertices, coded directly with direct_shift 26, vertex 0 moved by
// `steps` on x (steps × 2^26 grid steps), the others still.
std::vector<uint8_t> ao_widest_shift_stream(int32_t steps) {
  Encode3dOptions o = affine("1");
  o.hashes = false;
  const std::vector<uint8_t> base = encode_mesh3d(moving_tetrahedron(2), o).stream;
  const std::pair<ObjectHeader, AffineOctreeHeader> headers = read_headers<AffineOctreeHeader>(split_container(base));
  AffineCell cell;
  cell.direct = true;
  cell.motion.assign(headers.first.vertex_count, {0, 0, 0});
  cell.motion[0][0] = steps;
  return edited(base, [&](ContainerParts& p) {
    ContainerUnit& unit = unit_of(p, UnitType::kFrame, 1);
    unit.payload = ao_root_unit(headers.second, headers.first.vertex_count, cell, unit_header_bytes(unit.payload), kMaxDirectShift);
  });
}

// A 2-frame `stream` with matrix_range_log2 1, where no matrix holds the
// identity: frame 1's root is a leaf whose diagonal is the largest element,
// 2^(k−1) − 1 (a shrink by 2^−f), and whose element 1 is the smallest,
// −2^(k−1).
std::vector<uint8_t> ao_narrowest_range_stream(const std::vector<uint8_t>& stream) {
  const std::pair<ObjectHeader, AffineOctreeHeader> headers = read_headers<AffineOctreeHeader>(split_container(stream));
  const uint32_t vertex_count = headers.first.vertex_count;
  AffineOctreeHeader narrow = headers.second;
  narrow.matrix_range_log2 = 1;
  AffineCell cell;
  for (int i = 0; i < 3; ++i) cell.matrix[static_cast<size_t>(5 * i)] = narrow.matrix_max();
  cell.matrix[1] = narrow.matrix_min();
  return edited(stream, [&](ContainerParts& p) {
    put_field(p.object_payload, object_field<AffineOctreeHeader>(stream, "matrix_range_log2"), 1);
    ContainerUnit& unit = unit_of(p, UnitType::kFrame, 1);
    unit.payload = ao_root_unit(narrow, vertex_count, cell, unit_header_bytes(unit.payload));
  });
}

}  // namespace

// Affine-Octree streams: the paper's settings and the extremes of each header field.
std::vector<SuiteCase> affine_octree_cases(bool traced) {
  const MeshSequence shape = box_and_sheet(6, 4);
  std::vector<SuiteCase> suite;
  suite.push_back(valid("ao-01-me1-k16", "affine-octree at the paper's settings: ME 1 %, k = 16", {"container", "ao-header", "ao-frame", "ao-cell"},
                        shape, affine("1"), traced));
  {
    Encode3dOptions o = affine("25", 8);
    o.codec_options["max-depth"] = "3";
    suite.push_back(valid("ao-02-coarse", "ME 25 %, k = 8, octree depth at most 3", {"ao-header", "ao-cell"}, shape, o, traced));
  }
  {
    Encode3dOptions o = affine("0.1", 16);
    o.codec_options["bits"] = "16";
    o.codec_options["max-depth"] = "20";
    suite.push_back(valid("ao-03-fine", "ME 0.1 %, 16-bit grid, octree depth up to 20", {"ao-cell", "ao-reconstruction"}, shape, o, traced));
  }
  {
    Encode3dOptions o = affine("2", 24);
    o.codec_options["matrix-range-log2"] = "8";
    suite.push_back(valid("ao-04-wide-matrices", "k = 24 over [−128, 128): the widest matrix elements", {"ao-header", "ao-reconstruction"},
                          shape, o, traced));
  }
  {
    Encode3dOptions o = affine("1");
    o.codec_options["intra-period"] = "3";
    suite.push_back(valid("ao-05-intra", "an intra base mesh every 3 frames", {"container-units", "ao-frame"}, box_and_sheet(7, 3), o, traced));
  }
  suite.push_back(valid("ao-06-direct-root", "4 vertices: the root cell codes direct motion", {"ao-cell"}, moving_tetrahedron(5), affine("1"), traced));
  suite.push_back(valid("ao-07-coplanar", "a flat sheet rotating: singular cells, one matrix per frame", {"ao-cell", "ao-reconstruction"},
                        rotating_sheet(5), affine("1"), traced));
  {
    Encode3dOptions o = affine("0.1");
    o.codec_options["bits"] = "24";
    o.codec_options["max-depth"] = "20";
    suite.push_back(valid("ao-08-deep", "cells down to depth 20 (depth contexts 15 with both bins), a leaf of 12 vertices at the deepest depth",
                          {"ao-cell", "ao-reconstruction"}, deep_clusters(5), o, traced));
  }
  {
    Encode3dOptions o = affine("0.1", 24);
    o.codec_options["bits"] = "24";
    o.codec_options["max-depth"] = "20";
    suite.push_back(valid("ao-09-spikes", "vertices that jump by 2^−2 … 2^−23 of the box on a 24-bit grid: matrix and direct residuals of many "
                          "prefix lengths, leaves at every depth", {"ao-cell"}, spiky_sheet(8, 16, 100, 42, 30), o, traced));
  }
  for (int depth = 2; depth <= 15; ++depth) {
    Encode3dOptions o = affine("0.001", 24);
    o.codec_options["bits"] = "24";
    o.codec_options["max-depth"] = std::to_string(depth);
    char id[32];
    std::snprintf(id, sizeof id, "ao-11-depth-%02d", depth);
    suite.push_back(valid(id, "max_depth " + std::to_string(depth) + ": leaves of more than 4 vertices coded directly there, and matrix "
                          "leaves of more than 4 one level up", {"ao-cell"},
                          clustered_jumps(3, depth), o, traced));
  }
  {
    Encode3dOptions o = affine("0.1", 8);
    o.codec_options["bits"] = "4";
    o.codec_options["max-depth"] = "1";
    suite.push_back(valid("ao-10-shallow", "max_depth 1 on a 4-bit grid: leaves of many vertices at depth 1, matrix or direct", {"ao-header", "ao-cell"},
                          spiky_sheet(4, 4, 8, 48, 3), o, traced));
  }
  {
    Encode3dOptions o = affine("0.001");
    o.codec_options["bits"] = "16";
    suite.push_back(valid("ao-12-direct-prefixes", "three vertices whose direct motion takes every prefix length 0 … 13 after each class",
                          {"ao-cell"}, direct_triples(), o, traced));
  }
  {
    Encode3dOptions o = affine("0.001");
    o.codec_options["bits"] = "19";
    suite.push_back(valid("ao-13-matrix-prefixes", "two clusters whose matrices' residuals take every prefix length 0 … 13 after each class",
                          {"ao-cell"}, matrix_pairs(), o, traced));
  }
  {
    // ao-01's first two frames, with frame 1 a root leaf coded directly (no hash units: the frame is written, not encoded).
    Encode3dOptions o = affine("1");
    o.hashes = false;
    const std::vector<uint8_t> base = encode_mesh3d(box_and_sheet(2, 4), o).stream;
    suite.push_back(written_case("ao-14-direct-root", "a root of more than 4 vertices coded directly", {"ao-cell"},
                                edited(base, [&](ContainerParts& p) {
                                  ContainerUnit& unit = unit_of(p, UnitType::kFrame, 1);
                                  unit.payload = ao_direct_root_unit(base, unit_header_bytes(unit.payload));
                                })));
  }
  {
    Encode3dOptions o = affine("1", 4);
    suite.push_back(valid("ao-15-four-bit-matrices", "k = 4 over [−2, 2): the fewest bits per matrix element", {"ao-header", "ao-reconstruction"},
                          box_and_sheet(4, 4), o, traced));
  }
  {
    Encode3dOptions o = affine("1");
    o.hashes = false;
    suite.push_back(written_case("ao-17-matrix-range-1", "matrix_range_log2 1: a root leaf whose elements are the largest and the smallest k "
                                 "allows", {"ao-header", "ao-reconstruction"}, ao_narrowest_range_stream(encode_mesh3d(box_and_sheet(2, 4), o).stream)));
  }
  {
    Encode3dOptions o = affine("1", 4);
    o.codec_options["matrix-range-log2"] = "3";
    suite.push_back(valid("ao-18-one-fraction-bit", "k = 4, r = 3: one fraction bit, the largest r below k", {"ao-header", "ao-reconstruction"},
                          box_and_sheet(4, 4), o, traced));
  }
  suite.push_back(written_case("ao-16-direct-shift-26", "direct_shift 26, the largest: a vertex moved by 2^26 grid steps", {"ao-frame"},
                               ao_widest_shift_stream(-1)));
  return suite;
}

// Header ranges and frame units: their fields, a unit cut short.
std::vector<SuiteCase> affine_octree_rejected(const std::vector<SuiteCase>& valid) {
  std::vector<SuiteCase> suite;
  const std::vector<uint8_t> base = stream_of(valid, "ao-01-me1-k16");
  suite.push_back(invalid("x-03-matrix-bits", "matrix_bits 30", {"ao-header"},
                          edited(base, [&](ContainerParts& p) { put_field(p.object_payload, object_field<AffineOctreeHeader>(base, "matrix_bits"), 30); }), ErrorKind::kOutOfRange,
                          "matrix_bits", kNoPlane));
  suite.push_back(invalid("x-04-direct-shift", "direct_shift 27", {"ao-frame"},
                          edited(base, [](ContainerParts& p) { put_field(unit_of(p, UnitType::kFrame, 1).payload, unit_field<AffineFrame>("direct_shift"), 27); }),
                          ErrorKind::kOutOfRange, "direct_shift", 1));
  suite.push_back(invalid("x-05-arithmetic-bytes", "arithmetic_bytes longer than the frame", {"ao-frame"},
                          edited(base, [](ContainerParts& p) { unit_of(p, UnitType::kFrame, 2).payload[unit_field<AffineFrame>("arithmetic_bytes").first] = 0x7F; }),
                          ErrorKind::kOutOfRange, "arithmetic_bytes", 2));
  suite.push_back(invalid("x-06-frame-cut", "a frame unit cut after 3 bytes of data", {"ao-frame"},
                          edited(base,
                                 [](ContainerParts& p) {
                                   std::vector<uint8_t>& unit = unit_of(p, UnitType::kFrame, 1).payload;
                                   unit.resize(unit_header_bytes(unit).size() + 3);
                                 }),
                          ErrorKind::kTruncated, "arithmetic_bytes", 1));
  return suite;
}

// A matrix element and max_depth one past their ranges.
std::vector<SuiteCase> affine_octree_edge_rejected(const std::vector<SuiteCase>& valid) {
  std::vector<SuiteCase> suite;
  const std::vector<uint8_t> base = stream_of(valid, "ao-01-me1-k16");
  suite.push_back(invalid("x-57-ao-matrix-beyond", "a root leaf whose matrix element 0 is one above matrix_bits' range", {"ao-cell"},
                          edited(base,
                                 [&](ContainerParts& p) {
                                   ContainerUnit& unit = unit_of(p, UnitType::kFrame, 1);
                                   const AffineOctreeHeader header = read_headers<AffineOctreeHeader>(split_container(base)).second;
                                   unit.payload = ao_matrix_element_unit(base, 0, header.matrix_max() + 1, unit_header_bytes(unit.payload));
                                 }),
                          ErrorKind::kOutOfRange, "matrix_residual", 1));
  suite.push_back(invalid("x-115-ao-matrix-below", "a root leaf whose matrix element 0 is one below matrix_bits' range", {"ao-cell"},
                          edited(base,
                                 [&](ContainerParts& p) {
                                   ContainerUnit& unit = unit_of(p, UnitType::kFrame, 1);
                                   const AffineOctreeHeader header = read_headers<AffineOctreeHeader>(split_container(base)).second;
                                   unit.payload = ao_matrix_element_unit(base, 0, header.matrix_min() - 1, unit_header_bytes(unit.payload));
                                 }),
                          ErrorKind::kOutOfRange, "matrix_residual", 1));
  suite.push_back(invalid("x-116-ao-direct-beyond", "a vertex moved by −2 × 2^26 grid steps (direct_shift 26): beyond ±2^26", {"ao-frame"},
                          ao_widest_shift_stream(-2), ErrorKind::kOutOfRange, "direct_motion", 1));
  suite.push_back(invalid("x-112-ao-range-not-below-bits", "matrix_range_log2 equal to matrix_bits (8): no fraction bits", {"ao-header"},
                          edited(stream_of(valid, "ao-02-coarse"),
                                 [&](ContainerParts& p) {
                                   put_field(p.object_payload, object_field<AffineOctreeHeader>(stream_of(valid, "ao-02-coarse"), "matrix_range_log2"), 8);
                                 }),
                          ErrorKind::kOutOfRange, "matrix_range_log2", kNoPlane));
  {
    // A zero byte after frame 2's bins, counted by arithmetic_bytes; one after its raw bits.
    const FieldBytes length = unit_field<AffineFrame>("arithmetic_bytes");
    suite.push_back(invalid("x-113-ao-bins-left-over", "a byte after the last bin, counted by arithmetic_bytes", {"ao-frame"},
                            edited(base, [&](ContainerParts& p) { add_bins_byte(unit_of(p, UnitType::kFrame, 2).payload, length); }),
                            ErrorKind::kStructure, "matrix_residual", 2));
    suite.push_back(invalid("x-114-ao-raw-left-over", "a byte after the last raw bits", {"ao-frame"},
                            edited(base, [](ContainerParts& p) { unit_of(p, UnitType::kFrame, 2).payload.push_back(0x00); }),
                            ErrorKind::kStructure, "matrix_residual", 2));
  }
  {
    // A 24-bit grid, k = 24, r = 8: the largest translation moves the root by about 2^31 steps.
    Encode3dOptions o = affine("1", 24);
    o.codec_options["bits"] = "24";
    o.codec_options["matrix-range-log2"] = "8";
    o.hashes = false;
    const std::vector<uint8_t> wide = encode_mesh3d(box_and_sheet(2, 4), o).stream;
    const int32_t most = read_headers<AffineOctreeHeader>(split_container(wide)).second.matrix_max();
    suite.push_back(invalid("x-134-ao-affine-beyond", "a root leaf whose translation on x is the largest element: its vertices leave ±2^26",
                            {"ao-reconstruction"},
                            edited(wide,
                                   [&](ContainerParts& p) {
                                     ContainerUnit& unit = unit_of(p, UnitType::kFrame, 1);
                                     unit.payload = ao_matrix_element_unit(wide, 3, most, unit_header_bytes(unit.payload));
                                   }),
                            ErrorKind::kOutOfRange, "matrix_residual", 1));
  }
  const FieldBytes max_depth = object_field<AffineOctreeHeader>(base, "max_depth");
  suite.push_back(invalid("x-54-max-depth-21", "max_depth 21", {"ao-header"},
                          edited(base, [max_depth](ContainerParts& p) { put_field(p.object_payload, max_depth, 21); }), ErrorKind::kOutOfRange,
                          "max_depth", kNoPlane));
  return suite;
}

}  // namespace m4mesh::suite3d
