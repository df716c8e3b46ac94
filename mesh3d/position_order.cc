#include "mesh3d/position_order.h"

#include <limits>

namespace m4mesh {

namespace {

constexpr uint32_t kNotCandidate = std::numeric_limits<uint32_t>::max();
// A candidate's support, its parallelograms above its known corners. Both counts stay below 2^28: a face counts once
// per corner of the candidate, with at most two other corners.
constexpr uint64_t kParallelogram = uint64_t{1} << 32, kCorner = 1;

// The candidates with support, by support (more first), then by index (lower first); each held once, raised in
// place when its support grows (it never shrinks).
class SupportHeap {
 public:
  SupportHeap(std::span<const uint64_t> support, uint32_t count) : support_(support), place_(count, kNotCandidate) {}

  bool empty() const { return heap_.empty(); }

  // i's support grew: i enters, or moves up.
  void raise(uint32_t i) {
    uint32_t at = place_[i];
    if (at == kNotCandidate) {
      at = static_cast<uint32_t>(heap_.size());
      heap_.push_back(i);
    }
    while (at > 0) {
      const uint32_t parent = (at - 1) / 2;
      if (!ahead(i, heap_[parent])) break;
      put(heap_[parent], at);
      at = parent;
    }
    put(i, at);
  }

  uint32_t pop() {
    const uint32_t top = heap_[0];
    place_[top] = kNotCandidate;
    const uint32_t last = heap_.back();
    heap_.pop_back();
    if (heap_.empty()) return top;
    uint32_t at = 0;
    for (;;) {
      uint32_t child = 2 * at + 1;
      if (child >= heap_.size()) break;
      if (child + 1 < heap_.size() && ahead(heap_[child + 1], heap_[child])) ++child;
      if (!ahead(heap_[child], last)) break;
      put(heap_[child], at);
      at = child;
    }
    put(last, at);
    return top;
  }

 private:
  bool ahead(uint32_t a, uint32_t b) const { return support_[a] != support_[b] ? support_[a] > support_[b] : a < b; }
  void put(uint32_t i, uint32_t at) {
    heap_[at] = i;
    place_[i] = at;
  }

  std::span<const uint64_t> support_;
  std::vector<uint32_t> heap_, place_;
};

}  // namespace

PositionOrder::PositionOrder(const MeshPredictor& predictor, uint32_t vertex_count)
    : predictor_(predictor), local_(vertex_count, kNotCandidate) {}

// Supports only grow, each by one event: a corner becomes known, or the last
// of a parallelogram's three vertices does. Arrays are by candidate, so a
// call costs its candidates' faces, not the mesh's vertices.
std::vector<uint32_t> PositionOrder::of(std::span<const uint32_t> candidates) {
  const auto count = static_cast<uint32_t>(candidates.size());
  for (uint32_t i = 0; i < count; ++i) local_[candidates[i]] = i;
  // Each candidate's parallelograms: whose they are and how many of their vertices are unknown; per candidate, the
  // parallelograms it is a vertex of (once per place it takes). A vertex that is no candidate stays unknown.
  std::vector<uint32_t> owner, first_use(count + 1, 0), uses;
  std::vector<std::array<uint32_t, 3>> vertices;
  for (const uint32_t v : candidates)
    predictor_.for_each_parallelogram(v, [](uint32_t) { return true; }, [&](uint32_t x, uint32_t y, uint32_t z) {
      owner.push_back(local_[v]);
      vertices.push_back({local_[x], local_[y], local_[z]});
      for (const uint32_t w : vertices.back())
        if (w != kNotCandidate) ++first_use[w + 1];
    });
  for (uint32_t i = 0; i < count; ++i) first_use[i + 1] += first_use[i];
  uses.resize(first_use.back());
  std::vector<uint32_t> fill(first_use.begin(), first_use.end() - 1);
  for (uint32_t k = 0; k < vertices.size(); ++k)
    for (const uint32_t w : vertices[k])
      if (w != kNotCandidate) uses[fill[w]++] = k;
  std::vector<uint8_t> unknown(owner.size(), 3);

  std::vector<uint8_t> known(count, 0);
  std::vector<uint64_t> support(count, 0);
  // Those without support come after those with, in the candidates' order, which first_unknown walks: no heap of
  // every vertex.
  SupportHeap heap(support, count);
  uint32_t first_unknown = 0;
  const auto grow = [&](uint32_t i, uint64_t part) {
    if (i == kNotCandidate || known[i]) return;
    support[i] += part;
    heap.raise(i);
  };
  std::vector<uint32_t> order;
  order.reserve(count);
  while (order.size() < count) {
    uint32_t i;
    if (!heap.empty()) {
      i = heap.pop();
    } else {
      while (known[first_unknown]) ++first_unknown;
      i = first_unknown;
    }
    known[i] = 1;
    order.push_back(candidates[i]);
    predictor_.for_each_face(candidates[i], [&](const Triangle& face) {
      for (const NodeIndex u : face.v)
        if (u != candidates[i]) grow(local_[u], kCorner);
    });
    for (uint32_t k = first_use[i]; k < first_use[i + 1]; ++k)
      if (--unknown[uses[k]] == 0) grow(owner[uses[k]], kParallelogram);
  }
  for (const uint32_t v : candidates) local_[v] = kNotCandidate;
  return order;
}

}  // namespace m4mesh
