// The base mesh's coding (docs/base_mesh.md), shared by both directions:
// the gate traversal that codes the connectivity and numbers the vertices
// in coding order, the vertex order back to the input's, and the first
// frame's positions predicted by parallelograms. Each runs one description
// through a reading or a writing IO (syntax/mesh3d/entropy_io.h); the
// encoder adds an oracle that says what the mesh has behind each gate.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "common/point3.h"
#include "mesh/topology.h"
#include "syntax/mesh3d/base_mesh.h"

namespace m4mesh {

struct BaseMesh {
  std::vector<Triangle> faces;
  std::vector<IntPoint3> positions;
  std::vector<uint32_t> coding_order;  // the vertices in the order the traversal numbered them
};

// A directed edge from→to.
struct HalfEdge {
  uint32_t from, to;
};

// Directed edge → a number: open addressing, linear probing.
class DirectedEdgeIndex {
 public:
  static constexpr uint32_t kNone = 0xFFFFFFFF;
  void reserve(size_t count);
  uint32_t find(uint32_t from, uint32_t to) const;
  // Keys must be new.
  void insert(uint32_t from, uint32_t to, uint32_t value);

 private:
  size_t slot(uint64_t key) const { return static_cast<size_t>((key * 0x9E3779B97F4A7C15ull) >> shift_); }
  std::vector<uint64_t> keys_;
  std::vector<uint32_t> values_;
  size_t count_ = 0;
  int shift_ = 64;
};

// The connectivity decoded so far, in coding-order vertex numbers. An open
// half-edge is one of a decoded face whose other side is not known yet;
// each is a gate, visited first in, first out. Memory grows with the
// vertices numbered and the faces attached, beyond a reserve the header's
// count sets up to 2^20 faces.
class GateTraversal {
 public:
  // At most this many candidates are offered for a gate.
  static constexpr uint32_t kMaxCandidates = 8;

  // Room for the faces the traversal will hold, up to 2^20 of them (a
  // header's count is a hint, not a promise).
  explicit GateTraversal(uint32_t expected_faces);

  uint32_t visited() const { return static_cast<uint32_t>(degree_.size()); }
  uint32_t new_vertex();
  const std::vector<Triangle>& faces() const { return faces_; }
  // Per vertex, (a, b, d): the gate a → b it was numbered behind and the
  // third vertex d of the face in front of that gate; {v, v, v} for a
  // seed's corner.
  const std::vector<Triangle>& parents() const { return parents_; }

  // The next open gate; false when none is left (the next face is a seed).
  bool next_gate(HalfEdge& gate);
  // The vertices a face behind the gate can close on without a new vertex:
  // the ends of open half-edges leaving gate.to, then the starts of open
  // half-edges entering gate.from, newest first.
  void candidates(HalfEdge gate, std::vector<uint32_t>& out) const;
  // The contexts of the gate's bins.
  syntax::GateContext context(HalfEdge gate, uint32_t candidates) const;

  // Adds the face (gate.to, gate.from, c) behind the gate; false when it
  // would repeat a directed edge or a vertex.
  bool attach(HalfEdge gate, uint32_t c);
  // Adds a face that starts a region; false as attach.
  bool seed(const Triangle& face);
  // Closes a gate that has no face behind it.
  void border(HalfEdge gate);

 private:
  static constexpr uint32_t kNone = DirectedEdgeIndex::kNone;
  struct Edge {
    uint32_t from, to;
    uint32_t face;  // the face that has this half-edge
    bool open;
    uint32_t out_prev, out_next, in_prev, in_next;  // lists of open half-edges per vertex
  };
  bool add_face(const Triangle& face);
  void link(uint32_t from, uint32_t to);
  void close(uint32_t e);

  std::vector<Triangle> faces_;
  std::vector<Triangle> parents_;
  std::vector<uint32_t> degree_;  // faces around each vertex
  std::vector<uint32_t> out_head_, in_head_;
  std::vector<Edge> edges_;
  DirectedEdgeIndex index_;
  std::vector<uint32_t> gates_;
  size_t next_gate_ = 0;
};

// Floor division, for predictions of either sign.
inline int64_t floor_div(int64_t sum, int64_t n) {
  const int64_t q = sum / n;
  return (sum % n != 0 && sum < 0) ? q - 1 : q;
}

// The parallelogram prediction of docs/base_mesh.md ("Positions") for any
// values that live on the vertices (positions, a component's basis) and
// any set of vertices already known; the faces in any numbering, in their
// decoded order (which sets each directed edge's first face).
class MeshPredictor {
 public:
  MeshPredictor(std::span<const Triangle> faces, uint32_t vertex_count);

  // The prediction p of vertex v from the known vertices' values (D per
  // vertex; never v's own): the mean (floor) of the parallelograms x + y − z of the
  // faces (v, x, y) whose x, y and opposite z (the third vertex of the
  // first face with the directed edge y → x) are known, channel
  // kParallelogramChannel; else the mean of the known corners of the faces
  // around v, each counted once per face, channel kNeighbourChannel; −1
  // (p untouched) when no corner is known.
  template <size_t D, class Known, class Value>
  int predict(uint32_t v, Known known, Value value, std::array<int64_t, D>& p) const {
    std::array<int64_t, D> sum{};
    int64_t n = 0;
    for (uint32_t i = first_[v]; i < first_[v + 1]; ++i) {
      const Triangle& t = faces_[around_[i]];
      const int corner = t.corner_of(v);
      const uint32_t x = t.v[(corner + 1) % 3], y = t.v[(corner + 2) % 3];
      if (t.v[corner] != v || !known(x) || !known(y)) continue;
      const uint32_t z = opposite(y, x);
      if (z == kNoNode || !known(z)) continue;
      const auto& vx = value(x);
      const auto& vy = value(y);
      const auto& vz = value(z);
      for (size_t a = 0; a < D; ++a) sum[a] += int64_t{vx[a]} + vy[a] - vz[a];
      ++n;
    }
    if (n > 0) {
      for (size_t a = 0; a < D; ++a) p[a] = floor_div(sum[a], n);
      return syntax::kParallelogramChannel;
    }
    for (uint32_t i = first_[v]; i < first_[v + 1]; ++i)
      for (NodeIndex u : faces_[around_[i]].v)
        if (u != v && known(u)) {
          const auto& vu = value(u);
          for (size_t a = 0; a < D; ++a) sum[a] += vu[a];
          ++n;
        }
    if (n == 0) return -1;
    for (size_t a = 0; a < D; ++a) p[a] = floor_div(sum[a], n);
    return syntax::kNeighbourChannel;
  }

 private:
  // The third vertex of the first face with the directed edge from→to; kNoNode without one.
  uint32_t opposite(uint32_t from, uint32_t to) const {
    const uint32_t face = edges_.find(from, to);
    return face == DirectedEdgeIndex::kNone ? kNoNode : faces_[face].third(from, to);
  }

  std::span<const Triangle> faces_;
  std::vector<uint32_t> first_, around_;
  DirectedEdgeIndex edges_;  // the first face of each directed edge
};

// What the encoder's oracle answers (encoder/mesh3d/base_mesh.cc).
struct GateAnswer {
  GateSymbol symbol = GateSymbol::kBorder;
  uint32_t candidate = 0;
  uint32_t far_vertex = 0;
};

// The connectivity: `traversal_faces` faces by the traversal, numbering
// vertices as they appear. The oracle (writing only) answers gate() and
// seed_corner() and hears numbered(c) for the vertex just numbered c.
template <class IO, class Oracle>
void describe_traversal(IO& io, syntax::BaseMeshContexts& contexts, GateTraversal& traversal, uint32_t vertex_count,
                        uint32_t traversal_faces, Oracle* oracle) {
  std::vector<uint32_t> candidates;
  while (traversal.faces().size() < traversal_faces) {
    HalfEdge gate{};
    if (!traversal.next_gate(gate)) {
      Triangle face{};
      for (int corner = 0; corner < 3; ++corner) {
        bool is_new = false;
        uint32_t vertex = 0;
        if constexpr (!IO::kReading) is_new = !oracle->seed_corner(corner, vertex);
        syntax::describe_seed_corner(io, contexts, traversal.visited(), is_new, vertex);
        if (is_new) {
          if (traversal.visited() == vertex_count) io.fail(ErrorKind::kStructure, "seed_new_vertex", "more vertices than vertex_count");
          vertex = traversal.new_vertex();
          if constexpr (!IO::kReading) oracle->numbered(vertex);
        }
        face.v[corner] = vertex;
      }
      if (!traversal.seed(face)) io.fail(ErrorKind::kStructure, "seed_vertex", "a seed face repeats a vertex or a directed edge");
      continue;
    }
    traversal.candidates(gate, candidates);
    const uint32_t count = static_cast<uint32_t>(candidates.size());
    GateAnswer answer;
    if constexpr (!IO::kReading) answer = oracle->gate(gate, candidates);
    syntax::describe_gate(io, contexts, traversal.context(gate, count), count, traversal.visited(), gate.from, answer.symbol,
                          answer.candidate, answer.far_vertex);
    uint32_t c = 0;
    switch (answer.symbol) {
      case GateSymbol::kBorder:
        traversal.border(gate);
        continue;
      case GateSymbol::kNewVertex:
        if (traversal.visited() == vertex_count) io.fail(ErrorKind::kStructure, "gate_new_vertex", "more vertices than vertex_count");
        c = traversal.new_vertex();
        if constexpr (!IO::kReading) oracle->numbered(c);
        break;
      case GateSymbol::kCandidate:
        c = candidates[answer.candidate];
        break;
      case GateSymbol::kFarVertex:
        c = answer.far_vertex;
        break;
    }
    if (!traversal.attach(gate, c))
      io.fail(ErrorKind::kStructure, answer.symbol == GateSymbol::kCandidate ? "candidate_index" : "far_vertex",
              "a face that repeats a vertex or a directed edge");
  }
}

// Faces outside the traversal (degenerate, or repeating a directed edge of
// an earlier face): three vertex numbers each.
template <class IO>
void describe_loose_faces(IO& io, uint32_t vertex_count, std::span<Triangle> faces) {
  for (Triangle& face : faces)
    for (NodeIndex& v : face.v) syntax::describe_index(io, "loose_vertex", vertex_count, v);
}

// The input order: input_of[i] is the input number of coded vertex i, each
// coded as the difference of its rank among the input numbers not yet taken
// from the rank of its prediction (by the parents of the traversal).
template <class IO>
void describe_vertex_order(IO& io, syntax::BaseMeshContexts& contexts, uint32_t method, std::span<const Triangle> parents,
                           std::vector<uint32_t>& input_of);

// The first frame's positions in coding order: each the residual from the
// prediction by the vertices before it.
template <class IO>
void describe_positions(IO& io, syntax::BaseMeshContexts& contexts, std::span<const Triangle> faces, std::vector<IntPoint3>& positions);

}  // namespace m4mesh
