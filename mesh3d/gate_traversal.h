// The gate traversal of docs/base_mesh.md ("Connectivity"): the faces
// decoded so far, the open half-edges (gates) in the order they are
// visited, and the candidates offered at a gate. Both directions run it.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "mesh/topology.h"
#include "mesh3d/directed_edge_index.h"
#include "syntax/mesh3d/base_mesh.h"

namespace m4mesh {

// The connectivity decoded so far, in coding-order vertex numbers. An open
// half-edge is one of a decoded face whose other side is not known yet;
// each is a gate, visited first in, first out. Memory grows with the
// vertices numbered and the faces attached, beyond a reserve the header's
// count sets up to 2^20 faces.
class GateTraversal {
 public:
  // At most this many candidates are offered for a gate.
  static constexpr uint32_t kMaxCandidates = 8;
  // Steps a front walks each way, and the most vertices it lists: each
  // way's first step reaches a candidate or the gate's other vertex.
  static constexpr uint32_t kFrontSteps = 8;
  static constexpr uint32_t kMaxFront = 2 * (kFrontSteps - 1);

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
  // The vertices a far vertex is looked for among first: up to kFrontSteps
  // along the open half-edges from gate.to and, backwards, from
  // gate.from, alternately, without the gate's vertices, the candidates
  // and repeats.
  void front(HalfEdge gate, std::span<const uint32_t> candidates, std::vector<uint32_t>& out) const;
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
  // Half-edge e is the side of face e / 3 from its corner e % 3 to the next.
  HalfEdge half_edge(uint32_t e) const {
    const Triangle& t = faces_[e / 3];
    const uint32_t k = e % 3;
    return {t.v[k], t.v[k == 2 ? 0 : k + 1]};
  }
  struct Links {
    uint32_t out_prev, out_next, in_prev, in_next;  // lists of open half-edges per vertex
  };
  bool add_face(const Triangle& face);
  void link(uint32_t from, uint32_t to);
  void close(uint32_t e);
  // The half-edge of a gate: the one next_gate gave last, without a lookup.
  uint32_t edge_of(HalfEdge gate) const;

  std::vector<Triangle> faces_;
  std::vector<Triangle> parents_;
  std::vector<uint32_t> degree_;  // faces around each vertex
  std::vector<uint32_t> out_head_, in_head_;
  std::vector<Links> links_;   // per half-edge
  std::vector<uint8_t> open_;  // per half-edge
  DirectedEdgeIndex index_;
  std::vector<uint32_t> gates_;
  size_t next_gate_ = 0;
  uint32_t gate_edge_ = kNone;  // the last gate's half-edge
};

}  // namespace m4mesh
