#include "mesh3d/gate_traversal.h"

#include <algorithm>

namespace m4mesh {

GateTraversal::GateTraversal(uint32_t expected_faces) {
  const size_t faces = std::min<uint32_t>(expected_faces, 1u << 20);
  links_.reserve(3 * faces);
  open_.reserve(3 * faces);
  index_.reserve(3 * faces / 2);  // a closed mesh's edges
  gates_.reserve(faces);
  faces_.reserve(faces);
}

uint32_t GateTraversal::new_vertex() {
  const uint32_t v = visited();
  parents_.push_back({{v, v, v}});
  degree_.push_back(0);
  out_head_.push_back(kNone);
  in_head_.push_back(kNone);
  return v;
}

bool GateTraversal::next_gate(HalfEdge& gate) {
  while (next_gate_ < gates_.size()) {
    gate_edge_ = gates_[next_gate_++];
    if (open_[gate_edge_]) {
      gate = half_edge(gate_edge_);
      return true;
    }
  }
  return false;
}

void GateTraversal::candidates(HalfEdge gate, std::vector<uint32_t>& out) const {
  out.clear();
  for (uint32_t e = out_head_[gate.to]; e != kNone && out.size() < kMaxCandidates; e = links_[e].out_next)
    if (const uint32_t c = half_edge(e).to; c != gate.from) out.push_back(c);
  for (uint32_t e = in_head_[gate.from]; e != kNone && out.size() < kMaxCandidates; e = links_[e].in_next) {
    const uint32_t c = half_edge(e).from;
    if (c != gate.to && std::find(out.begin(), out.end(), c) == out.end()) out.push_back(c);
  }
}

void GateTraversal::front(HalfEdge gate, std::span<const uint32_t> candidates, std::vector<uint32_t>& out) const {
  out.clear();
  const auto add = [&](uint32_t v) {
    if (v != gate.from && v != gate.to && std::find(candidates.begin(), candidates.end(), v) == candidates.end() &&
        std::find(out.begin(), out.end(), v) == out.end())
      out.push_back(v);
  };
  uint32_t ahead = gate.to, behind = gate.from;
  for (uint32_t step = 0; step < kFrontSteps; ++step) {
    if (ahead != kNone) {
      const uint32_t e = out_head_[ahead];
      ahead = e == kNone ? kNone : half_edge(e).to;
      if (ahead != kNone) add(ahead);
    }
    if (behind != kNone) {
      const uint32_t e = in_head_[behind];
      behind = e == kNone ? kNone : half_edge(e).from;
      if (behind != kNone) add(behind);
    }
  }
}

syntax::GateContext GateTraversal::context(HalfEdge gate, uint32_t candidates) const {
  const uint32_t from = std::min<uint32_t>(degree_[gate.from], 7), to = std::min<uint32_t>(degree_[gate.to], 7);
  return {static_cast<int>(std::min<uint32_t>(candidates, 3) * 8 + std::max(from, to)), static_cast<int>(to * 8 + from)};
}

void GateTraversal::close(uint32_t index) {
  open_[index] = 0;
  const Links& e = links_[index];
  const HalfEdge ends = half_edge(index);
  if (e.out_prev != kNone) links_[e.out_prev].out_next = e.out_next;
  else out_head_[ends.from] = e.out_next;
  if (e.out_next != kNone) links_[e.out_next].out_prev = e.out_prev;
  if (e.in_prev != kNone) links_[e.in_prev].in_next = e.in_next;
  else in_head_[ends.to] = e.in_next;
  if (e.in_next != kNone) links_[e.in_next].in_prev = e.in_prev;
}

// A face's half-edge from→to: it closes the open half-edge to→from when
// there is one, else it is open: a new gate.
void GateTraversal::link(uint32_t from, uint32_t to) {
  const uint32_t index = static_cast<uint32_t>(links_.size());
  const uint32_t reverse = index_.insert_and_find_reverse(from, to, index);
  if (reverse != kNone && open_[reverse]) {
    close(reverse);
    links_.push_back({kNone, kNone, kNone, kNone});
    open_.push_back(0);
    return;
  }
  const uint32_t out_next = out_head_[from], in_next = in_head_[to];
  links_.push_back({kNone, out_next, kNone, in_next});
  open_.push_back(1);
  if (out_next != kNone) links_[out_next].out_prev = index;
  if (in_next != kNone) links_[in_next].in_prev = index;
  out_head_[from] = index;
  in_head_[to] = index;
  gates_.push_back(index);
}

bool GateTraversal::add_face(const Triangle& face) {
  const auto [a, b, c] = face.v;
  if (a == b || b == c || c == a) return false;
  if (index_.find(a, b) != kNone || index_.find(b, c) != kNone || index_.find(c, a) != kNone) return false;
  faces_.push_back(face);  // its half-edges are 3 f, 3 f + 1 and 3 f + 2
  link(a, b);
  link(b, c);
  link(c, a);
  for (NodeIndex v : face.v) ++degree_[v];
  return true;
}

bool GateTraversal::attach(HalfEdge gate, uint32_t c) {
  if (c >= visited()) return false;
  const bool numbered_here = degree_[c] == 0;
  const Triangle in_front = faces_[edge_of(gate) / 3];
  if (!add_face(Triangle{{gate.to, gate.from, c}})) return false;
  if (numbered_here) parents_[c] = {{gate.from, gate.to, in_front.third(gate.from, gate.to)}};
  return true;
}

bool GateTraversal::seed(const Triangle& face) { return add_face(face); }

void GateTraversal::border(HalfEdge gate) { close(edge_of(gate)); }

uint32_t GateTraversal::edge_of(HalfEdge gate) const {
  if (gate_edge_ != kNone) {
    const HalfEdge last = half_edge(gate_edge_);
    if (last.from == gate.from && last.to == gate.to) return gate_edge_;
  }
  return index_.find(gate.from, gate.to);
}

}  // namespace m4mesh
