// Base mesh units written symbol by symbol (docs/base_mesh.md): oracles
// that answer the gate traversal's questions in ways m4mesh's encoder
// never does, to reach every context and index or to break a rule.
#pragma once

#include <cstdint>
#include <limits>
#include <optional>
#include <set>
#include <span>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "common/random.h"
#include "conformance/suite3d/cases.h"
#include "conformance/suite3d/inputs.h"
#include "conformance/suite3d/stream_edits.h"
#include "mesh3d/base_mesh.h"
#include "syntax/mesh3d/bfs3d.h"
#include "syntax/mesh3d/entropy_io.h"

namespace m4mesh::suite3d {

// Writes as EntropyWriteIO does and stops at the first rule the symbols
// break, where a decoder must fail.
class StopAtFailureIO {
 public:
  static constexpr bool kReading = false;
  struct Stop {};
  explicit StopAtFailureIO(syntax::EntropyWriteIO<false>& io) : io_(io) {}
  void bin(const char* name, BinContext& state, int context, bool& value) { io_.bin(name, state, context, value); }
  void raw(const char* name, int bits, uint32_t& value) { io_.raw(name, bits, value); }
  [[noreturn]] void fail(ErrorKind, const char*, const std::string&) const { throw Stop{}; }

 private:
  syntax::EntropyWriteIO<false>& io_;
};

// Answers the traversal's questions for a base mesh that breaks a rule:
// seeds of new vertices but for seed `old_seed`'s `old_corner` (vertex
// `old_vertex`, when the corner is not −1), and the gates answered by
// `script` in turn, then by `answer`: by default the far vertex 3 (the
// first seed's vertices are 0, 1 and 2, so 3 is not numbered yet).
struct BrokenBaseMesh {
  int old_corner = -1;
  int old_seed = 0;
  uint32_t old_vertex = 0;
  GateAnswer answer{GateSymbol::kFarVertex, 0, 3};
  std::vector<GateAnswer> script;
  size_t gates = 0;  // gates answered so far
  int seeds = 0;     // seeds answered so far
  bool seed_corner(int corner, uint32_t& vertex) {
    vertex = old_vertex;
    const bool old = seeds == old_seed && corner == old_corner;
    if (corner == 2) ++seeds;
    return old;
  }
  void numbered(uint32_t) {}
  GateAnswer gate(HalfEdge, std::span<const uint32_t>) { return gates < script.size() ? script[gates++] : answer; }
};

// A base mesh unit for frame 0 from its unit header and its symbols.
std::vector<uint8_t> base_mesh_unit(std::vector<uint8_t> unit_header, syntax::EntropyWriteIO<false>& symbols, uint32_t vertex_order);

// A base mesh unit for frame 0 of an object of `vertex_count` vertices and
// `face_count` faces whose traversal the oracle breaks; or, when the
// traversal completes, with no loose face and the vertex order (order 1)
// given by `order_differences`, which breaks it.
std::vector<uint8_t> broken_base_mesh_unit(std::vector<uint8_t> unit_header, uint32_t vertex_count, uint32_t face_count, BrokenBaseMesh oracle,
                                           std::vector<int32_t> order_differences = {});

// A one-frame bfs3d stream (no hash unit) of `vertex_count` vertices and
// `face_count` faces whose base mesh is written symbol by symbol: the
// traversal the oracle answers, no loose face, the vertex order given by
// `order_differences` (coding order without), every position at the
// grid's origin unless `positions` (in coding order) are given; those
// past ±2^26 are written up to the first, where a decoder must fail.
template <class Oracle>
std::vector<uint8_t> written_base_mesh_stream(uint32_t vertex_count, uint32_t face_count, Oracle& oracle,
                                              std::vector<int32_t> order_differences = {}, std::vector<IntPoint3> positions = {},
                                              uint32_t order_method = kVertexOrderFromGate) {
  MeshSequence points;  // any object of this vertex count: its base mesh unit and face count are replaced
  points.vertex_count = vertex_count;
  points.faces = {{{0, 1, 2}}};
  points.frames.emplace_back(vertex_count, Vec3{0, 0, 0});
  points.frames[0][0] = {1, 1, 1};
  Encode3dOptions o;
  o.hashes = false;
  const std::vector<uint8_t> encoded = encode_mesh3d(points, o).stream;
  syntax::EntropyWriteIO<false> symbols(syntax::SectionPlace{});
  syntax::BaseMeshContexts contexts;
  GateTraversal traversal(face_count);
  if constexpr (requires { oracle.watch(traversal); }) oracle.watch(traversal);
  describe_traversal(symbols, contexts, traversal, vertex_count, face_count, &oracle);
  describe_loose_faces(symbols, vertex_count, std::span<Triangle>());
  for (int32_t& d : order_differences) contexts.order.describe(symbols, 0, d, syntax::kOrderNames);
  positions.resize(vertex_count);
  try {
    describe_positions(symbols, contexts, PositionCoding(traversal.faces(), vertex_count), 0, positions);
  } catch (const Error&) {
  }
  const FieldBytes faces = object_field<Bfs3dHeader>(encoded, "face_count");
  return edited(encoded, [&](ContainerParts& p) {
    put_field(p.object_payload, faces, face_count);
    ContainerUnit& unit = unit_of(p, UnitType::kBaseMesh, 0);
    unit.payload = base_mesh_unit(unit_header_bytes(unit.payload), symbols,
                                  order_differences.empty() ? kVertexOrderCoding : order_method);
  });
}

// Answers for a strip of new vertices, then one far vertex: vertex 0 from
// the first gate leaving vertex `from` or a later one, so that the unit's
// first far residual is 0 − from; then the traversal ends (the face count
// is reached).
struct FirstFarOracle {
  uint32_t from = 0;
  uint32_t visited = 0;
  bool seed_corner(int, uint32_t&) { return false; }
  void numbered(uint32_t v) { visited = v + 1; }
  GateAnswer gate(HalfEdge gate, std::span<const uint32_t>) {
    if (gate.from >= from) return {GateSymbol::kFarVertex, 0, 0};
    return {visited <= gate.to + 1 ? GateSymbol::kNewVertex : GateSymbol::kBorder, 0, 0};
  }
};

// The base of the oracles below: the vertices numbered and the faces
// answered so far, to keep the answers valid. Seeds take new vertices.
class FaceTracker {
 public:
  // A seed's corner is asked for; numbered() hears the vertex.
  bool seed_corner(int corner, uint32_t&) {
    corner_ = corner;
    return false;
  }
  // A vertex just numbered: a gate's new vertex or a seed's corner, the seed face complete at its third.
  void numbered(uint32_t v) {
    visited_ = v + 1;
    if (corner_ < 0) return;
    seed_.v[static_cast<size_t>(corner_)] = v;
    if (corner_ == 2) {
      add(seed_);
      corner_ = -1;
    }
  }
  // Whether the face (gate.to, gate.from, c) repeats no vertex and no directed edge.
  bool can_attach(HalfEdge gate, uint32_t c) const {
    return c != gate.from && c != gate.to && !edges_.count({gate.to, gate.from}) && !edges_.count({gate.from, c}) && !edges_.count({c, gate.to});
  }
  void add(const Triangle& face) {
    ++faces_;
    for (int i = 0; i < 3; ++i) edges_.insert({face.v[static_cast<size_t>(i)], face.v[static_cast<size_t>((i + 1) % 3)]});
  }
  // The face behind the gate for an answer.
  void add(HalfEdge gate, const GateAnswer& answer, std::span<const uint32_t> candidates, uint32_t new_vertex) {
    if (answer.symbol == GateSymbol::kBorder) return;
    const uint32_t c = answer.symbol == GateSymbol::kNewVertex ? new_vertex
                       : answer.symbol == GateSymbol::kCandidate ? candidates[answer.candidate]
                                                                 : answer.far_vertex;
    add({{gate.to, gate.from, c}});
  }
  uint32_t faces() const { return faces_; }
  uint32_t vertices() const { return visited_; }

 protected:
  uint32_t visited_ = 0;

 private:
  std::set<std::pair<uint32_t, uint32_t>> edges_;
  uint32_t faces_ = 0;
  int corner_ = -1;
  Triangle seed_{};
};

// Answers for components of a base mesh, each from its own random seed:
// seed faces of new vertices, then at each gate a border, a new vertex, a
// candidate or a far vertex of the component (each with the component's
// own odds, among the answers that make a valid face) until the component
// has `kFaces` faces, then borders. Past the last seed, std::out_of_range.
class ComponentOracle : public FaceTracker {
 public:
  static constexpr uint32_t kFaces = 40;

  explicit ComponentOracle(std::vector<uint64_t> seeds) : seeds_(std::move(seeds)), random_(0) {}

  bool seed_corner(int corner, uint32_t& vertex) {
    if (corner == 0) {
      random_ = SplitMix64(seeds_.at(component_++));
      for (uint32_t& odds : odds_) odds = static_cast<uint32_t>(1 + random_.next() % 8);
      first_ = visited_;
      first_face_ = faces();
    }
    return FaceTracker::seed_corner(corner, vertex);
  }

  GateAnswer gate(HalfEdge gate, std::span<const uint32_t> candidates) {
    std::vector<GateAnswer> answers[4];  // border, new vertex, candidate, far vertex
    answers[0].push_back({GateSymbol::kBorder, 0, 0});
    if (faces() - first_face_ < kFaces) {
      if (can_attach(gate, visited_)) answers[1].push_back({GateSymbol::kNewVertex, 0, 0});
      for (uint32_t i = 0; i < candidates.size(); ++i)
        if (can_attach(gate, candidates[i])) answers[2].push_back({GateSymbol::kCandidate, i, 0});
      const uint32_t far = first_ + static_cast<uint32_t>(random_.next() % (visited_ - first_));
      if (can_attach(gate, far)) answers[3].push_back({GateSymbol::kFarVertex, 0, far});
    }
    uint32_t total = 0;
    for (int k = 0; k < 4; ++k) total += answers[k].empty() ? 0 : odds_[k];
    uint32_t pick = static_cast<uint32_t>(random_.next() % total);
    int kind = 0;
    while (answers[kind].empty() || pick >= odds_[kind]) {
      if (!answers[kind].empty()) pick -= odds_[kind];
      ++kind;
    }
    const GateAnswer answer = answers[kind][random_.next() % answers[kind].size()];
    add(gate, answer, candidates, visited_);
    return answer;
  }

 private:
  std::vector<uint64_t> seeds_;
  size_t component_ = 0;
  SplitMix64 random_;
  uint32_t odds_[4] = {};
  uint32_t first_ = 0, first_face_ = 0;  // the component's first vertex and face
};
// Answers for a disc of new vertices, then far vertices on the gate's
// front where the face is valid: at the last index of fronts
// of each size 1 … 14 at any gate, and at every third gate each index
// 0 … 12 with more after it and one off a front that has vertices; the
// first candidate at two gates of three otherwise (loops shrink), else a
// new vertex. Until each far vertex is answered or kGates gates, then
// std::out_of_range. The traversal is watched for the fronts.
class FrontOracle : public FaceTracker {
 public:
  static constexpr uint32_t kDisc = 40;  // vertices numbered before the first far vertex
  static constexpr uint32_t kGates = 20000;
  FrontOracle();
  void watch(const GateTraversal& traversal) { traversal_ = &traversal; }
  GateAnswer gate(HalfEdge gate, std::span<const uint32_t> candidates);
  // Whether every answer listed was given (rather than kGates reached).
  bool done() const { return inner_indices_.empty() && last_sizes_.empty() && !off_front_; }
  std::string left() const {
    std::string s;
    for (uint32_t i : inner_indices_) s += " index " + std::to_string(i);
    for (uint32_t n : last_sizes_) s += " last of " + std::to_string(n);
    return s + (off_front_ ? " off" : "");
  }

 private:
  // The far vertex for a gate: the last of its front where a front of this
  // size has had none, else (when `any`) one still to answer.
  std::optional<uint32_t> far_vertex(HalfEdge gate, std::span<const uint32_t> candidates, bool any);
  const GateTraversal* traversal_ = nullptr;
  std::set<uint32_t> inner_indices_, last_sizes_;
  bool off_front_ = true;
  uint32_t gates_ = 0;
  std::vector<uint32_t> front_;
};

// Writes nothing: records the (element, context, value) of every bin.
class BinRecorder {
 public:
  static constexpr bool kReading = false;
  void bin(const char* name, BinContext&, int context, bool& value) { bins.insert({name, context, value}); }
  void raw(const char*, int, uint32_t&) {}
  [[noreturn]] void fail(ErrorKind kind, const char* element, const std::string& message) const {
    throw Error(kind, element, kNoPlane, kNoOffset, "suite: " + message);
  }
  std::set<std::tuple<std::string, int, bool>> bins;
};

// What an oracle's traversal makes, run until the oracle throws
// std::out_of_range (it has no more to say): the faces and vertices, and
// the bins it reaches.
struct Traversed {
  uint32_t faces = 0, vertices = 0;
  std::set<std::tuple<std::string, int, bool>> bins;
};
template <class Oracle>
Traversed traversed(Oracle oracle) {
  BinRecorder recorder;
  syntax::BaseMeshContexts contexts;
  GateTraversal traversal(0);
  if constexpr (requires { oracle.watch(traversal); }) oracle.watch(traversal);
  try {
    constexpr uint32_t kUnbounded = std::numeric_limits<uint32_t>::max();
    describe_traversal(recorder, contexts, traversal, kUnbounded, kUnbounded, &oracle);
  } catch (const std::out_of_range&) {
  }
  return {static_cast<uint32_t>(traversal.faces().size()), oracle.vertices(), std::move(recorder.bins)};
}

// Answers for a fan of `fan` vertices, then far vertices whose
// differences from their gate's vertex follow the patterns of
// for_each_prefix_pattern() after a zero class's (a far residual is never
// 0), each after a run of ±1 long enough for the far channel's order k to
// return to 0: a border where the difference fits neither way. Past the
// last, std::out_of_range.
class FarScheduleOracle : public FaceTracker {
 public:
  explicit FarScheduleOracle(uint32_t fan) : fan_(fan) {
    for_each_prefix_pattern(13, [&](int32_t first, int32_t second) {
      if (first == 0) return;
      for (int i = 0; i < 100; ++i) schedule_.push_back(1);
      schedule_.push_back(std::abs(first));
      schedule_.push_back(std::abs(second));
    });
  }
  GateAnswer gate(HalfEdge gate, std::span<const uint32_t> candidates) {
    GateAnswer answer{GateSymbol::kBorder, 0, 0};
    if (visited_ < fan_) {
      if (visited_ == gate.to + 1) answer.symbol = GateSymbol::kNewVertex;
    } else {
      const int64_t d = schedule_.at(next_);
      for (int64_t c : {int64_t{gate.from} + d, int64_t{gate.from} - d})
        if (c >= 0 && c < visited_ && can_attach(gate, static_cast<uint32_t>(c))) {
          answer = {GateSymbol::kFarVertex, 0, static_cast<uint32_t>(c)};
          ++next_;
          break;
        }
    }
    add(gate, answer, candidates, visited_);
    return answer;
  }
 private:
  uint32_t fan_;
  std::vector<int64_t> schedule_;
  size_t next_ = 0;
};

// Seeds of components that reach the gate and candidate contexts: per
// round, of 2,000 seeds tried, the component that reaches the most bins not
// reached before, until a round adds none.
std::vector<uint64_t> covering_component_seeds();

// Vertex order differences that follow prefix_schedule() for `count`
// vertices in no face (each predicted by the input number after the one
// before), towards the side with more numbers not taken, then 0.
std::vector<int32_t> order_schedule(uint32_t count);

}  // namespace m4mesh::suite3d
