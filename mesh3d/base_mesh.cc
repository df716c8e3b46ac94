#include "mesh3d/base_mesh.h"

#include <algorithm>
#include <bit>

#include "mesh3d/quantization.h"
#include "syntax/mesh3d/entropy_io.h"

namespace m4mesh {

void DirectedEdgeIndex::reserve(size_t count) {
  size_t capacity = 16;
  while (capacity < 2 * count) capacity *= 2;
  if (capacity <= keys_.size()) return;
  std::vector<uint64_t> keys = std::move(keys_);
  std::vector<uint32_t> values = std::move(values_);
  keys_.assign(capacity, ~uint64_t{0});
  values_.assign(capacity, kNone);
  shift_ = 64 - std::countr_zero(capacity);
  for (size_t i = 0; i < keys.size(); ++i)
    if (keys[i] != ~uint64_t{0}) {
      size_t at = slot(keys[i]);
      while (keys_[at] != ~uint64_t{0}) at = (at + 1) & (capacity - 1);
      keys_[at] = keys[i];
      values_[at] = values[i];
    }
}

uint32_t DirectedEdgeIndex::find(uint32_t from, uint32_t to) const {
  if (keys_.empty()) return kNone;
  const uint64_t key = (uint64_t{from} << 32) | to;
  for (size_t at = slot(key);; at = (at + 1) & (keys_.size() - 1)) {
    if (keys_[at] == key) return values_[at];
    if (keys_[at] == ~uint64_t{0}) return kNone;
  }
}

void DirectedEdgeIndex::insert(uint32_t from, uint32_t to, uint32_t value) {
  if (2 * (count_ + 1) > keys_.size()) reserve(2 * (count_ + 1));
  const uint64_t key = (uint64_t{from} << 32) | to;
  size_t at = slot(key);
  while (keys_[at] != ~uint64_t{0}) at = (at + 1) & (keys_.size() - 1);
  keys_[at] = key;
  values_[at] = value;
  ++count_;
}

GateTraversal::GateTraversal(uint32_t expected_faces) {
  const size_t faces = std::min<uint32_t>(expected_faces, 1u << 20);
  edges_.reserve(3 * faces);
  index_.reserve(3 * faces);
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
    const Edge& e = edges_[gates_[next_gate_++]];
    if (e.open) {
      gate = {e.from, e.to};
      return true;
    }
  }
  return false;
}

void GateTraversal::candidates(HalfEdge gate, std::vector<uint32_t>& out) const {
  out.clear();
  for (uint32_t e = out_head_[gate.to]; e != kNone && out.size() < kMaxCandidates; e = edges_[e].out_next)
    if (edges_[e].to != gate.from) out.push_back(edges_[e].to);
  for (uint32_t e = in_head_[gate.from]; e != kNone && out.size() < kMaxCandidates; e = edges_[e].in_next) {
    const uint32_t c = edges_[e].from;
    if (c != gate.to && std::find(out.begin(), out.end(), c) == out.end()) out.push_back(c);
  }
}

syntax::GateContext GateTraversal::context(HalfEdge gate, uint32_t candidates) const {
  const uint32_t from = std::min<uint32_t>(degree_[gate.from], 7), to = std::min<uint32_t>(degree_[gate.to], 7);
  return {static_cast<int>(std::min<uint32_t>(candidates, 3) * 8 + std::max(from, to)), static_cast<int>(to * 8 + from)};
}

void GateTraversal::close(uint32_t index) {
  Edge& e = edges_[index];
  e.open = false;
  if (e.out_prev != kNone) edges_[e.out_prev].out_next = e.out_next;
  else out_head_[e.from] = e.out_next;
  if (e.out_next != kNone) edges_[e.out_next].out_prev = e.out_prev;
  if (e.in_prev != kNone) edges_[e.in_prev].in_next = e.in_next;
  else in_head_[e.to] = e.in_next;
  if (e.in_next != kNone) edges_[e.in_next].in_prev = e.in_prev;
}

// A face's half-edge from→to: it closes the open half-edge to→from when
// there is one, else it is open: a new gate.
void GateTraversal::link(uint32_t from, uint32_t to) {
  const uint32_t face = static_cast<uint32_t>(faces_.size());
  const uint32_t index = static_cast<uint32_t>(edges_.size());
  index_.insert(from, to, index);
  const uint32_t reverse = index_.find(to, from);
  if (reverse != kNone && edges_[reverse].open) {
    close(reverse);
    edges_.push_back({from, to, face, false, kNone, kNone, kNone, kNone});
    return;
  }
  const uint32_t out_next = out_head_[from], in_next = in_head_[to];
  edges_.push_back({from, to, face, true, kNone, out_next, kNone, in_next});
  if (out_next != kNone) edges_[out_next].out_prev = index;
  if (in_next != kNone) edges_[in_next].in_prev = index;
  out_head_[from] = index;
  in_head_[to] = index;
  gates_.push_back(index);
}

bool GateTraversal::add_face(const Triangle& face) {
  const auto [a, b, c] = face.v;
  if (a == b || b == c || c == a) return false;
  if (index_.find(a, b) != kNone || index_.find(b, c) != kNone || index_.find(c, a) != kNone) return false;
  link(a, b);
  link(b, c);
  link(c, a);
  for (NodeIndex v : face.v) ++degree_[v];
  faces_.push_back(face);
  return true;
}

bool GateTraversal::attach(HalfEdge gate, uint32_t c) {
  if (c >= visited()) return false;
  const bool numbered_here = degree_[c] == 0;
  const Triangle in_front = faces_[edges_[index_.find(gate.from, gate.to)].face];
  if (!add_face(Triangle{{gate.to, gate.from, c}})) return false;
  if (numbered_here) parents_[c] = {{gate.from, gate.to, in_front.third(gate.from, gate.to)}};
  return true;
}

bool GateTraversal::seed(const Triangle& face) { return add_face(face); }

void GateTraversal::border(HalfEdge gate) { close(index_.find(gate.from, gate.to)); }

MeshPredictor::MeshPredictor(std::span<const Triangle> faces, uint32_t vertex_count) : faces_(faces), first_(vertex_count + 1, 0) {
  for (const Triangle& t : faces)
    for (NodeIndex v : t.v) ++first_[v + 1];
  for (uint32_t v = 0; v < vertex_count; ++v) first_[v + 1] += first_[v];
  around_.resize(first_.back());
  std::vector<uint32_t> fill(first_.begin(), first_.end() - 1);
  edges_.reserve(3 * faces.size());
  for (uint32_t f = 0; f < faces.size(); ++f)
    for (int i = 0; i < 3; ++i) {
      const NodeIndex from = faces[f].v[i], to = faces[f].v[(i + 1) % 3];
      around_[fill[from]++] = f;
      if (edges_.find(from, to) == DirectedEdgeIndex::kNone) edges_.insert(from, to, f);
    }
}

namespace {

// Fenwick tree over the input numbers not yet taken, for ranks.
class UnusedSet {
 public:
  explicit UnusedSet(uint32_t size) : tree_(size + 1, 0) {
    for (uint32_t i = 1; i <= size; ++i) {
      tree_[i] += 1;
      const uint32_t parent = i + (i & (~i + 1));
      if (parent <= size) tree_[parent] += tree_[i];
    }
  }
  // How many unused numbers are below n.
  uint32_t rank(uint32_t n) const {
    uint32_t sum = 0;
    for (uint32_t i = n; i > 0; i -= i & (~i + 1)) sum += tree_[i];
    return sum;
  }
  // The unused number with `rank` unused numbers below it.
  uint32_t select(uint32_t rank) const {
    uint32_t position = 0;
    for (uint32_t step = std::bit_floor(static_cast<uint32_t>(tree_.size() - 1)); step > 0; step >>= 1)
      if (position + step < tree_.size() && tree_[position + step] <= rank) {
        position += step;
        rank -= tree_[position];
      }
    return position;
  }
  void take(uint32_t n) {
    for (uint32_t i = n + 1; i < tree_.size(); i += i & (~i + 1)) --tree_[i];
  }

 private:
  std::vector<uint32_t> tree_;
};

}  // namespace

template <class IO>
void describe_vertex_order(IO& io, syntax::BaseMeshContexts& contexts, uint32_t method, std::span<const Triangle> parents,
                           std::vector<uint32_t>& input_of) {
  if (method == kVertexOrderCoding) return;
  const uint32_t count = static_cast<uint32_t>(input_of.size());
  UnusedSet unused(count);
  int64_t previous = -1;
  for (uint32_t i = 0; i < count; ++i) {
    int64_t predicted = previous + 1;
    if (i < parents.size() && parents[i].v[0] != i) {
      const auto [a, b, d] = parents[i].v;
      predicted = method == kVertexOrderFromGate ? int64_t{input_of[a]} : int64_t{input_of[a]} + input_of[b] - input_of[d];
    }
    const uint32_t from = unused.rank(static_cast<uint32_t>(std::clamp<int64_t>(predicted, 0, count - 1)));
    int32_t difference = 0;
    if constexpr (!IO::kReading) difference = static_cast<int32_t>(int64_t{unused.rank(input_of[i])} - from);
    contexts.order.describe(io, 0, difference, syntax::kOrderNames);
    const int64_t target = int64_t{from} + difference;
    if (target < 0 || target >= count - i)
      io.fail(ErrorKind::kOutOfRange, "vertex_order_difference", "beyond the input numbers not yet taken");
    input_of[i] = unused.select(static_cast<uint32_t>(target));
    unused.take(input_of[i]);
    previous = input_of[i];
  }
}

template <class IO>
void describe_positions(IO& io, syntax::BaseMeshContexts& contexts, std::span<const Triangle> faces, std::vector<IntPoint3>& positions) {
  const uint32_t count = static_cast<uint32_t>(positions.size());
  const MeshPredictor predictor(faces, count);
  std::array<int64_t, 3> p{};
  for (uint32_t v = 0; v < count; ++v) {
    int channel = predictor.predict(v, [v](uint32_t u) { return u < v; }, [&](uint32_t u) { return positions[u]; }, p);
    if (channel < 0) {
      for (int a = 0; a < 3; ++a) p[a] = v > 0 ? positions[v - 1][a] : 0;
      channel = syntax::kNeighbourChannel;
    }
    for (int a = 0; a < 3; ++a) {
      int32_t residual = 0;
      if constexpr (!IO::kReading) residual = static_cast<int32_t>(positions[v][a] - p[a]);
      contexts.positions.describe(io, channel + a, residual, syntax::kPositionNames);
      const int64_t q = p[a] + residual;
      if (q > kMaxQuantized || q < -kMaxQuantized) io.fail(ErrorKind::kOutOfRange, "position", "a position leaves ±2^26 grid steps");
      positions[v][a] = static_cast<int32_t>(q);
    }
  }
}

#define M4MESH_BASE_MESH_IO(IO)                                                                                        \
  template void describe_vertex_order<IO>(IO&, syntax::BaseMeshContexts&, uint32_t, std::span<const Triangle>, std::vector<uint32_t>&); \
  template void describe_positions<IO>(IO&, syntax::BaseMeshContexts&, std::span<const Triangle>, std::vector<IntPoint3>&);
M4MESH_BASE_MESH_IO(syntax::EntropyReadIO<false>)
M4MESH_BASE_MESH_IO(syntax::EntropyReadIO<true>)
M4MESH_BASE_MESH_IO(syntax::EntropyWriteIO<false>)
M4MESH_BASE_MESH_IO(syntax::EntropyWriteIO<true>)
#undef M4MESH_BASE_MESH_IO

}  // namespace m4mesh
