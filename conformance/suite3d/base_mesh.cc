// The base mesh's streams (docs/base_mesh.md) and those to reject.
#include <cstdio>

#include "conformance/suite3d/base_mesh_oracles.h"
#include "conformance/suite3d/cases.h"
#include "conformance/suite3d/inputs.h"
#include "conformance/suite3d/stream_edits.h"
#include "mesh3d/quantization.h"
#include "syntax/mesh3d/affine_octree.h"
#include "syntax/mesh3d/base_mesh.h"
#include "syntax/mesh3d/bfs3d.h"

namespace m4mesh::suite3d {

namespace {

// Five vertices, two degenerate faces and a vertex in no face: every face
// loose, the traversal empty.
MeshSequence all_loose() {
  MeshSequence s;
  s.vertex_count = 5;
  s.faces = {{{0, 0, 1}}, {{2, 3, 3}}};
  s.frames = {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}}, {{0, 0, 1}, {1, 0, 1}, {0, 1, 1}, {0, 0, 2}, {1, 1, 2}}};
  return s;
}

}  // namespace

// The base mesh: every kind of face and vertex, in the input order and in
// coding order; a row-major sheet, whose input numbers parallelograms predict.
std::vector<SuiteCase> base_mesh_cases(bool traced) {
  std::vector<SuiteCase> suite;
  const MeshSequence awkward = awkward_mesh(4);
  suite.push_back(valid("base-01-awkward", "components, borders, vertices in no face, non-manifold, degenerate and repeated faces",
                        {"base-mesh"}, awkward, Encode3dOptions{}, traced));
  Encode3dOptions reorder;
  reorder.reorder = true;
  suite.push_back(valid("base-02-coding-order", "the same mesh numbered in coding order (encode3d --reorder)", {"base-mesh"}, awkward,
                        reorder, traced));
  suite.push_back(valid("base-03-row-major", "a row-major sheet: input numbers predicted by parallelograms", {"base-mesh"},
                        rotating_sheet(3), Encode3dOptions{}, traced));
  suite.push_back(valid("base-04-crown", "gates with up to 8 candidates: candidate indices 1 … 7, the cut at 8, and a loose face (v, v, u)",
                        {"base-mesh"}, crown(2, 12, 12), Encode3dOptions{}, traced));
  suite.push_back(valid("base-05-irregular", "a grid of random diagonals: gate and candidate contexts over most pairs of degrees, both ways",
                        {"base-mesh"}, irregular_grid(2, 16), Encode3dOptions{}, traced));
  Encode3dOptions bits24;
  bits24.codec_options = {{"bits", "24"}};
  suite.push_back(valid("base-06-shuffled", "256 vertices numbered at random (vertex order 1), loose faces on a 2^8 index, parallelograms "
                        "across edges that loose faces repeat", {"base-mesh"}, shuffled_grid(2), Encode3dOptions{}, traced));
  {
    MeshSequence spiky = spiky_sheet(2, 32, 200, 46, 4);
    renumber_at_random(spiky, 1289);
    suite.push_back(valid("base-07-spikes", "1,291 vertices numbered at random, a quarter of them off their place by 2^−2 … 2^−23 of the box on a "
                          "24-bit grid: position and order residuals of every prefix length", {"base-mesh"}, spiky, bits24, traced));
  }
  Encode3dOptions bits16;
  bits16.codec_options = {{"bits", "16"}};
  suite.push_back(valid("base-08-far-chain", "a chain of faces whose third vertices are often earlier ones at random: far vertices at "
                        "every distance, after near and far ones", {"base-mesh"}, far_chain(3000, 51), Encode3dOptions{}, traced));
  suite.push_back(valid("base-09-dense-soup", "300 faces on 32 vertices at random: gates with 3 and more candidates at every pair of "
                        "degrees, every candidate index", {"base-mesh"}, dense_soup(32, 300, 54), Encode3dOptions{}, traced));
  suite.push_back(valid("base-10-loose-chain", "vertices in no face, each off the one before by a residual of every prefix length 0 … 13 "
                        "after each class", {"base-mesh"}, loose_chain(prefix_schedule()), bits16, traced));
  suite.push_back(valid("base-11-parallelograms", "separate quads whose fourth vertex is off the parallelogram by a residual of every "
                        "prefix length 0 … 13 after each class", {"base-mesh"}, parallelogram_quads(prefix_schedule()), bits16, traced));
  suite.push_back(written_case("base-12-order-prefixes", "a face and 23,997 vertices in no face whose vertex order differences take every "
                              "prefix length 0 … 13 after each class (written symbol by symbol)", {"base-mesh"},
                              [] {
                                constexpr uint32_t kVertices = 24000;
                                FirstFarOracle seed;  // the one face: a seed of new vertices
                                return written_base_mesh_stream(kVertices, 1, seed, order_schedule(kVertices));
                              }()));
  {
    // Seed 0, 1, 2; gate 2 → 0 numbers 3 (parallelogram 2 + 0 − 1, input 3:
    // difference 0), gate 2 → 3 numbers 4 (parallelogram 2 + 3 − 0 = 5, one
    // untaken number below: input 4 is difference −1), vertex 5 in no face.
    BrokenBaseMesh fan;
    fan.script = {{GateSymbol::kBorder, 0, 0}, {GateSymbol::kBorder, 0, 0}, {GateSymbol::kNewVertex, 0, 0}, {GateSymbol::kNewVertex, 0, 0}};
    suite.push_back(written_case("base-23-order-below-first", "a vertex order (by parallelograms) whose first nonzero difference is "
                                 "negative (written symbol by symbol)", {"base-mesh"},
                                 written_base_mesh_stream(6, 3, fan, {0, 0, 0, 0, -1, 0}, {}, kVertexOrderFromParallelogram)));
  }
  {
    const std::vector<uint64_t> seeds = covering_component_seeds();
    const Traversed size = traversed(ComponentOracle(seeds));
    ComponentOracle oracle(seeds);
    suite.push_back(written_case("base-13-gate-contexts", "components of random answers, chosen among many for the gate and candidate "
                                "contexts they reach (written symbol by symbol)", {"base-mesh"},
                                written_base_mesh_stream(size.vertices, size.faces, oracle)));
  }
  // The first far residual of a unit is the only one after a zero class: one prefix length per unit.
  for (int e = 4; e <= 12; ++e) {
    FirstFarOracle oracle{static_cast<uint32_t>(3 << (e - 1))};
    char id[40];
    std::snprintf(id, sizeof id, "base-14-first-far-%02d", e);
    suite.push_back(written_case(id, "a fan whose first far vertex takes a residual of prefix length " + std::to_string(e) + " (written symbol by symbol)",
                                {"base-mesh"}, written_base_mesh_stream(oracle.from + 2, oracle.from + 1, oracle)));
  }
  {
    FarScheduleOracle oracle(20000);
    const Traversed size = traversed(oracle);
    suite.push_back(written_case("base-15-far-prefixes", "a fan of 20,000 vertices, then faces on far vertices whose residuals take every "
                                "prefix length 0 … 13 after a residual of length 0 and of length 1 (written symbol by symbol)", {"base-mesh"},
                                written_base_mesh_stream(size.vertices, size.faces, oracle)));
  }
  {
    FrontOracle oracle;
    const Traversed size = traversed(oracle);
    suite.push_back(written_case("base-26-front", "a disc grown by new vertices and far vertices on the gate's front: every index 0 … 12 with more "
                                "after it, the last index of fronts of 1 … 14 vertices, and a far vertex off a front (written symbol by symbol)",
                                {"base-mesh"}, written_base_mesh_stream(size.vertices, size.faces, oracle)));
  }
  suite.push_back(valid("base-16-all-loose", "every face loose (degenerate), no traversal: loose_face_count equal to face_count", {"base-mesh"},
                        all_loose(), Encode3dOptions{}, traced));
  {
    BrokenBaseMesh triangle;  // a seed of three new vertices, its gates borders
    triangle.answer = {GateSymbol::kBorder, 0, 0};
    constexpr int32_t kMost = kMaxQuantized;
    suite.push_back(written_case("base-17-position-limits", "positions at 2^26 and −2^26 on every axis, written symbol by symbol", {"base-mesh"},
                                 written_base_mesh_stream(3, 1, triangle, {}, {{kMost, -kMost, 0}, {-kMost, kMost, kMost}, {0, 0, -kMost}})));
  }
  {
    // Spikes off a sheet: parallelograms and neighbours' means of either sign, far from each other.
    const MeshSequence spiky = spiky_sheet(2, 32, 200, 46, 4);
    const std::pair<const char*, uint32_t> blends[] = {{"base-18-blend-16", 16}, {"base-19-blend-5", 5}, {"base-20-blend-0", 0}};
    for (const auto& [id, blend] : blends) {
      Encode3dOptions o = bits24;
      o.position_blend = blend;
      suite.push_back(valid(id, "positions predicted with position_blend " + std::to_string(blend) + " on a spiky sheet", {"base-mesh"}, spiky, o,
                            traced));
    }
    // A degenerate face (v, v, u) from the middle of the sheet to the first vertex coded.
    MeshSequence repeated_corner = spiky;
    repeated_corner.faces.push_back({{544, 544, spiky.faces.front().v[0]}});
    Encode3dOptions blend5 = bits24;
    blend5.position_blend = 5;
    suite.push_back(valid("base-25-repeated-corner", "base-19's spiky sheet and a loose face (v, v, u) to the first vertex coded: u "
                          "counted twice in v's neighbours' mean, position_blend 5", {"base-mesh"}, repeated_corner, blend5, traced));
    // Its second frame moved below the first frame's box, an intra base mesh of negative positions.
    MeshSequence below = spiky;
    for (size_t v = 0; v < below.frames[1].size(); ++v) {
      const Vec3& p = below.frames[0][v];
      below.frames[1][v] = {p.x - 0.9, p.y - 0.9, p.z - 0.9};
    }
    Encode3dOptions intra;
    intra.codec_options = {{"bits", "16"}, {"intra-period", "1"}};
    intra.position_blend = 5;
    suite.push_back(valid("base-21-blend-below-zero", "position_blend 5 on an intra base mesh below the grid's origin: blended sums of "
                          "either sign, rounded down", {"base-mesh"}, below, intra, traced));
  }
  return suite;
}

// The base mesh unit's fields, and bytes left over after its sections.
std::vector<SuiteCase> base_mesh_unit_rejected(const std::vector<SuiteCase>& valid) {
  std::vector<SuiteCase> suite;
  const std::vector<uint8_t> awkward = stream_of(valid, "base-01-awkward");
  auto base_unit = [](ContainerParts& p) -> std::vector<uint8_t>& { return unit_of(p, UnitType::kBaseMesh, 0).payload; };
  suite.push_back(invalid("x-46-base-vertex-order", "vertex_order 3", {"base-mesh"},
                          edited(awkward, [&](ContainerParts& p) { put_field(base_unit(p), unit_field<BaseMeshData>("vertex_order"), 3); }), ErrorKind::kOutOfRange,
                          "vertex_order", 0));
  suite.push_back(invalid("x-47-base-loose-faces", "loose_face_count one more than face_count", {"base-mesh"},
                          edited(awkward,
                                 [&](ContainerParts& p) {
                                   const uint64_t faces = field_value(p.object_payload, object_field<Bfs3dHeader>(awkward, "face_count"));
                                   put_field(base_unit(p), unit_field<BaseMeshData>("loose_face_count"), faces + 1);
                                 }),
                          ErrorKind::kOutOfRange, "loose_face_count", 0));
  suite.push_back(invalid("x-174-base-loose-faces-and-length", "x-47's loose_face_count, arithmetic_bytes past the unit: the length is checked first",
                          {"base-mesh"},
                          edited(awkward,
                                 [&](ContainerParts& p) {
                                   const uint64_t faces = field_value(p.object_payload, object_field<Bfs3dHeader>(awkward, "face_count"));
                                   put_field(base_unit(p), unit_field<BaseMeshData>("loose_face_count"), faces + 1);
                                   put_field(base_unit(p), unit_field<BaseMeshData>("arithmetic_bytes"), 1u << 30);
                                 }),
                          ErrorKind::kOutOfRange, "arithmetic_bytes", 0));
  {
    // Seed 0 of three new vertices, its gates borders; seed 1 a new vertex
    // and the old 2 and 1, in the raw section, which is cut: read as zeros,
    // they would make a seed of corners 3, 0, 0 (structure seed_vertex:
    // mutant ct-48).
    struct SecondSeedOnOldVertices {
      int seeds = 0;
      bool seed_corner(int corner, uint32_t& vertex) {
        const bool old = seeds == 1 && corner > 0;
        vertex = corner == 1 ? 2 : 1;
        if (corner == 2) ++seeds;
        return old;
      }
      void numbered(uint32_t) {}
      GateAnswer gate(HalfEdge, std::span<const uint32_t>) { return {GateSymbol::kBorder, 0, 0}; }
    } oracle;
    suite.push_back(invalid("x-153-base-raw-cut", "a second seed's two old corners in the raw section, cut: the decoder stops at the "
                            "first seed_vertex", {"container"},
                            edited(written_base_mesh_stream(4, 2, oracle),
                                   [&](ContainerParts& p) {
                                     std::vector<uint8_t>& unit = base_unit(p);
                                     unit.resize(unit_field<BaseMeshData>("bins").first + field_value(unit, unit_field<BaseMeshData>("arithmetic_bytes")));
                                   }),
                            ErrorKind::kTruncated, "raw", 0));
  }
  suite.push_back(invalid("x-48-base-raw-left-over", "a byte after the raw bits", {"base-mesh"},
                          edited(awkward, [&](ContainerParts& p) { base_unit(p).push_back(0x00); }), ErrorKind::kStructure, "base_mesh", 0));
  suite.push_back(invalid("x-49-base-bins-left-over", "a zero byte after the last bin, counted by arithmetic_bytes", {"base-mesh"},
                          edited(awkward,
                                 [&](ContainerParts& p) {
                                   std::vector<uint8_t>& unit = base_unit(p);
                                   const FieldBytes length = unit_field<BaseMeshData>("arithmetic_bytes");
                                   const uint64_t bins = field_value(unit, length);
                                   unit.insert(unit.begin() + static_cast<std::ptrdiff_t>(unit_field<BaseMeshData>("bins").first + bins), 0x00);
                                   put_field(unit, length, bins + 1);
                                 }),
                          ErrorKind::kStructure, "base_mesh", 0));
  return suite;
}

// A vertex count one short.
std::vector<SuiteCase> base_mesh_count_rejected(const std::vector<SuiteCase>& valid) {
  std::vector<SuiteCase> suite;
  const std::vector<uint8_t> tetrahedron = stream_of(valid, "ao-06-direct-root");
  suite.push_back(invalid("x-53-vertex-count-short", "vertex_count 3 for a tetrahedron: its fourth vertex is one too many", {"base-mesh"},
                          edited(tetrahedron, [&](ContainerParts& p) { put_field(p.object_payload, object_field<AffineOctreeHeader>(tetrahedron, "vertex_count"), 3); }), ErrorKind::kStructure,
                          "gate_new_vertex", 0));
  return suite;
}

// Traversals and vertex orders that break a rule, written symbol by symbol.
std::vector<SuiteCase> base_mesh_traversal_rejected(const std::vector<SuiteCase>& valid) {
  std::vector<SuiteCase> suite;
  const std::vector<uint8_t> base = stream_of(valid, "ao-01-me1-k16");
  {
    // Base mesh units of the box and sheet (ao-01) broken by the traversal's answers.
    const ObjectHeader object = read_headers<AffineOctreeHeader>(split_container(base)).first;
    auto broken = [&](BrokenBaseMesh oracle) {
      return edited(base, [&](ContainerParts& p) {
        ContainerUnit& unit = unit_of(p, UnitType::kBaseMesh, 0);
        unit.payload = broken_base_mesh_unit(unit_header_bytes(unit.payload), object.vertex_count, object.face_count, oracle);
      });
    };
    BrokenBaseMesh seed_repeats;
    seed_repeats.old_corner = 1;
    suite.push_back(invalid("x-59-base-seed-repeats", "a seed face whose second corner is its first vertex again", {"base-mesh"},
                            broken(seed_repeats), ErrorKind::kStructure, "seed_vertex", 0));
    suite.push_back(invalid("x-60-base-far-unnumbered", "a far vertex equal to the count of vertices numbered so far", {"base-mesh"},
                            broken(BrokenBaseMesh{}), ErrorKind::kOutOfRange, "far_vertex", 0));
    BrokenBaseMesh old_first;
    old_first.old_corner = 0;
    suite.push_back(invalid("x-80-base-old-vertex-first", "the first seed's first corner a vertex numbered before, when none is", {"base-mesh"},
                            broken(old_first), ErrorKind::kStructure, "seed_new_vertex", 0));
    BrokenBaseMesh unnumbered;  // a triangle whose gates are borders, then a seed on vertex 3 of 3 numbered
    unnumbered.old_corner = 0;
    unnumbered.old_seed = 1;
    unnumbered.old_vertex = 3;
    unnumbered.answer = {GateSymbol::kBorder, 0, 0};
    suite.push_back(invalid("x-81-base-seed-vertex-unnumbered", "a second seed's corner equal to the count of vertices numbered so far",
                            {"base-mesh"}, broken(unnumbered), ErrorKind::kOutOfRange, "seed_vertex", 0));
  }
  {
    // One triangle (a seed, three border gates) whose last vertex takes the
    // rank one past the single input number left.
    MeshSequence triangle;
    triangle.vertex_count = 3;
    triangle.faces = {{{0, 1, 2}}};
    triangle.frames = {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 0, 1}, {1, 0, 1}, {0, 1, 1}}};
    BrokenBaseMesh borders;
    borders.answer = {GateSymbol::kBorder, 0, 0};
    suite.push_back(invalid("x-61-base-order-past", "a vertex order whose last difference is one past the input numbers not taken", {"base-mesh"},
                            edited(encode_mesh3d(triangle, Encode3dOptions{}).stream,
                                   [&](ContainerParts& p) {
                                     ContainerUnit& unit = unit_of(p, UnitType::kBaseMesh, 0);
                                     unit.payload = broken_base_mesh_unit(unit_header_bytes(unit.payload), 3, 1, borders, {0, 0, 1});
                                   }),
                            ErrorKind::kOutOfRange, "vertex_order_difference", 0));
  }
  return suite;
}

// The traversal's rules on seeds, candidates and far vertices, loose
// faces' vertices and bits, and positions, each broken alone.
std::vector<SuiteCase> base_mesh_rules_rejected(const std::vector<SuiteCase>& valid) {
  std::vector<SuiteCase> suite;
  // Base mesh units of an Affine-Octree stream broken by the traversal's answers.
  auto broken = [&](const char* stream, BrokenBaseMesh oracle) {
    const std::vector<uint8_t>& base = stream_of(valid, stream);
    const ObjectHeader object = read_headers<AffineOctreeHeader>(split_container(base)).first;
    return edited(base, [&](ContainerParts& p) {
      ContainerUnit& unit = unit_of(p, UnitType::kBaseMesh, 0);
      unit.payload = broken_base_mesh_unit(unit_header_bytes(unit.payload), object.vertex_count, object.face_count, oracle);
    });
  };
  BrokenBaseMesh second_seed;  // a triangle whose gates are borders, then a seed of new vertices
  second_seed.answer = {GateSymbol::kBorder, 0, 0};
  suite.push_back(invalid("x-127-base-seed-beyond", "a tetrahedron's second seed numbering vertices 3 and 4: one past vertex_count", {"base-mesh"},
                          broken("ao-06-direct-root", second_seed), ErrorKind::kStructure, "seed_new_vertex", 0));
  BrokenBaseMesh repeated_edge;  // gate 0 → 1 a new vertex 3, gate 1 → 2 the candidate 0: face (2, 1, 0) repeats 1 → 0
  repeated_edge.script = {{GateSymbol::kNewVertex, 0, 0}, {GateSymbol::kCandidate, 0, 0}};
  suite.push_back(invalid("x-128-base-candidate-repeats", "a face on a candidate that repeats a directed edge", {"base-mesh"},
                          broken("ao-01-me1-k16", repeated_edge), ErrorKind::kStructure, "candidate_index", 0));
  BrokenBaseMesh below_zero;  // gate 0 → 1 answered by vertex −1
  below_zero.answer = {GateSymbol::kFarVertex, 0, ~uint32_t{0}};
  suite.push_back(invalid("x-129-base-far-below-zero", "a far vertex of −1", {"base-mesh"}, broken("ao-01-me1-k16", below_zero),
                          ErrorKind::kOutOfRange, "far_vertex", 0));
  BrokenBaseMesh front_repeats;  // gates 0 → 1 and 1 → 2 new vertices 3 and 4, gate 2 → 0 vertex 1, its front's one vertex: 2 → 1 again
  front_repeats.script = {{GateSymbol::kNewVertex, 0, 0}, {GateSymbol::kNewVertex, 0, 0}, {GateSymbol::kFarVertex, 0, 1}};
  suite.push_back(invalid("x-156-base-front-repeats", "a face on a far vertex on the gate's front that repeats a directed edge", {"base-mesh"},
                          broken("ao-01-me1-k16", front_repeats), ErrorKind::kStructure, "front_index", 0));
  BrokenBaseMesh far_repeats;  // gate 0 → 1 answered by vertex 0: the face (1, 0, 0)
  far_repeats.answer = {GateSymbol::kFarVertex, 0, 0};
  suite.push_back(invalid("x-130-base-far-repeats", "a face on a far vertex that repeats a vertex", {"base-mesh"}, broken("ao-01-me1-k16", far_repeats),
                          ErrorKind::kStructure, "far_vertex", 0));
  const std::vector<uint8_t>& loose = stream_of(valid, "base-16-all-loose");
  suite.push_back(invalid("x-131-base-loose-vertex-beyond", "a loose face's first vertex 5 of 5", {"base-mesh"},
                          edited(loose,
                                 [](ContainerParts& p) {
                                   // The raw section starts with the loose faces: 3 bits a vertex.
                                   std::vector<uint8_t>& unit = unit_of(p, UnitType::kBaseMesh, 0).payload;
                                   const size_t raw = unit_field<BaseMeshData>("bins").first + field_value(unit, unit_field<BaseMeshData>("arithmetic_bytes"));
                                   unit.at(raw) = static_cast<uint8_t>((unit.at(raw) & 0x1F) | 5 << 5);
                                 }),
                          ErrorKind::kOutOfRange, "loose_vertex", 0));
  suite.push_back(invalid("x-132-base-loose-faces-cut", "face_count and loose_face_count 1000: more loose faces than the raw bits hold",
                          {"base-mesh"},
                          edited(loose,
                                 [&](ContainerParts& p) {
                                   put_field(p.object_payload, object_field<Bfs3dHeader>(loose, "face_count"), 1000);
                                   put_field(unit_of(p, UnitType::kBaseMesh, 0).payload, unit_field<BaseMeshData>("loose_face_count"), 1000);
                                 }),
                          ErrorKind::kTruncated, "loose_vertex", 0));
  {
    // base-04-crown's traversal takes 19 raw bits of its 2,336: 97 loose faces of 24 bits fit the whole section, not the
    // bits after the traversal, so the loose faces are read, and the first loose vertex, 255 of 242, is out of range.
    const std::vector<uint8_t>& crown = stream_of(valid, "base-04-crown");
    suite.push_back(invalid("x-185-base-loose-faces-whole-raw", "97 loose faces, fitting the whole raw section but not the bits after the "
                            "traversal; the first loose vertex 255 of 242", {"base-mesh"},
                            edited(crown,
                                   [&](ContainerParts& p) {
                                     std::vector<uint8_t>& unit = unit_of(p, UnitType::kBaseMesh, 0).payload;
                                     const uint64_t faces = field_value(p.object_payload, object_field<Bfs3dHeader>(crown, "face_count"));
                                     const uint64_t loose_faces = field_value(unit, unit_field<BaseMeshData>("loose_face_count"));
                                     put_field(p.object_payload, object_field<Bfs3dHeader>(crown, "face_count"), faces + 97 - loose_faces);
                                     put_field(unit, unit_field<BaseMeshData>("loose_face_count"), 97);
                                     const size_t raw = unit_field<BaseMeshData>("bins").first + field_value(unit, unit_field<BaseMeshData>("arithmetic_bytes"));
                                     unit.at(raw + 2) |= 0x1F;  // raw bits 19 … 26: 255
                                     unit.at(raw + 3) |= 0xE0;
                                   }),
                            ErrorKind::kOutOfRange, "loose_vertex", 0));
  }
  {
    BrokenBaseMesh triangle;
    triangle.answer = {GateSymbol::kBorder, 0, 0};
    suite.push_back(invalid("x-133-base-position-beyond", "a position of 2^26 + 1", {"base-mesh"},
                            written_base_mesh_stream(3, 1, triangle, {}, {{0, 0, 0}, {kMaxQuantized + 1, 0, 0}, {0, 0, 0}}),
                            ErrorKind::kOutOfRange, "position", 0));
  }
  suite.push_back(invalid("x-145-base-position-blend", "position_blend 17", {"base-mesh"},
                          edited(stream_of(valid, "base-18-blend-16"),
                                 [&](ContainerParts& p) { put_field(unit_of(p, UnitType::kBaseMesh, 0).payload, unit_field<BaseMeshData>("position_blend"), 17); }),
                          ErrorKind::kOutOfRange, "position_blend", 0));
  return suite;
}

}  // namespace m4mesh::suite3d
