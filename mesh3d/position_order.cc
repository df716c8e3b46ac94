#include "mesh3d/position_order.h"

#include <limits>

namespace m4mesh {

namespace {

constexpr uint32_t kNotCandidate = std::numeric_limits<uint32_t>::max();
// A candidate's support, its parallelograms above its known corners. Both counts stay below 2^28: a face counts once
// per corner of the candidate, with at most two other corners.
constexpr uint64_t kParallelogram = uint64_t{1} << 32, kCorner = 1;
// A candidate's state in one call: unknown, known, or unknown with support grown in this step.
enum : uint8_t { kUnknown, kKnown, kGrown };

// The candidates with support, by support (more first), then by index (lower first); each held once with its
// support, raised in place when the support grows (it never shrinks).
class SupportHeap {
 public:
  explicit SupportHeap(uint32_t count) : place_(count, kNotCandidate) {}

  bool empty() const { return heap_.empty(); }

  // i's support grew to `support`: i enters, or moves up.
  void raise(uint32_t i, uint64_t support) {
    uint32_t at = place_[i];
    if (at == kNotCandidate) {
      at = static_cast<uint32_t>(heap_.size());
      heap_.emplace_back();
    }
    const Entry raised = entry(i, support);
    while (at > 0) {
      const uint32_t parent = (at - 1) / 2;
      if (!ahead(raised, heap_[parent])) break;
      put(heap_[parent], at);
      at = parent;
    }
    put(raised, at);
  }

  uint32_t pop() {
    const uint32_t top = heap_[0].i();
    place_[top] = kNotCandidate;
    const Entry last = heap_.back();
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
  // A candidate's support above its complemented index: the greater key is ahead, in one comparison.
  __extension__ using Key = unsigned __int128;
  struct Entry {
    Key key;
    uint32_t i() const { return ~static_cast<uint32_t>(key); }
  };
  static Entry entry(uint32_t i, uint64_t support) { return {(static_cast<Key>(support) << 32) | ~i}; }
  static bool ahead(const Entry& a, const Entry& b) { return a.key > b.key; }
  void put(const Entry& e, uint32_t at) {
    heap_[at] = e;
    place_[e.i()] = at;
  }

  std::vector<Entry> heap_;
  std::vector<uint32_t> place_;
};

}  // namespace

PositionOrder::PositionOrder(const MeshPredictor& predictor, uint32_t vertex_count)
    : predictor_(predictor), local_(vertex_count, kNotCandidate) {
  // Room for every parallelogram, so that the lists never move (pages are touched only as they fill).
  owner_.reserve(predictor.corners());
  corners_.reserve(3 * predictor.corners());
}

// Supports only grow, each by one event: a corner becomes known, or the last
// of a parallelogram's three vertices does. Arrays are by candidate, so a
// call costs its candidates' faces, not the mesh's vertices; they are kept
// between calls.
std::vector<uint32_t> PositionOrder::of(std::span<const uint32_t> candidates) {
  const auto count = static_cast<uint32_t>(candidates.size());
  for (uint32_t i = 0; i < count; ++i) local_[candidates[i]] = i;
  const auto is_candidate = [&](uint32_t v) { return local_[v] != kNotCandidate; };
  // The parallelograms whose three vertices are candidates (one with another vertex never completes): whose they
  // are, how many of their vertices are unknown; per candidate, those it is a vertex of (once per place it takes).
  owner_.clear(), corners_.clear();
  first_use_.assign(count + 1, 0);
  for (const uint32_t v : candidates)
    predictor_.for_each_parallelogram(v, is_candidate, [&](uint32_t x, uint32_t y, uint32_t z) {
      if (!is_candidate(z)) return;
      owner_.push_back(local_[v]);
      for (const uint32_t w : {local_[x], local_[y], local_[z]}) corners_.push_back(w), ++first_use_[w + 1];
    });
  for (uint32_t i = 0; i < count; ++i) first_use_[i + 1] += first_use_[i];
  uses_.resize(corners_.size());
  fill_.assign(first_use_.begin(), first_use_.end() - 1);
  for (uint32_t k = 0; k < corners_.size(); ++k) uses_[fill_[corners_[k]]++] = k / 3;
  unknown_.assign(owner_.size(), 3);

  state_.assign(count, kUnknown);
  support_.assign(count, 0);
  // Those without support come after those with, in the candidates' order, which first_unknown walks: no heap of
  // every vertex. A step's growths are summed first, and each candidate they touched raised once: the heap's top
  // is the same whatever the order of raises.
  SupportHeap heap(count);
  uint32_t first_unknown = 0;
  const auto grow = [&](uint32_t i, uint64_t part) {
    if (i == kNotCandidate || state_[i] == kKnown) return;
    support_[i] += part;
    if (state_[i] == kUnknown) state_[i] = kGrown, grown_.push_back(i);
  };
  std::vector<uint32_t> order;
  order.reserve(count);
  while (order.size() < count) {
    uint32_t i;
    if (!heap.empty()) {
      i = heap.pop();
    } else {
      while (state_[first_unknown] == kKnown) ++first_unknown;
      i = first_unknown;
    }
    state_[i] = kKnown;
    order.push_back(candidates[i]);
    predictor_.for_each_known_corner(candidates[i], [](uint32_t) { return true; }, [&](uint32_t u) { grow(local_[u], kCorner); });
    for (uint32_t k = first_use_[i]; k < first_use_[i + 1]; ++k)
      if (--unknown_[uses_[k]] == 0) grow(owner_[uses_[k]], kParallelogram);
    for (const uint32_t g : grown_) state_[g] = kUnknown, heap.raise(g, support_[g]);
    grown_.clear();
  }
  for (const uint32_t v : candidates) local_[v] = kNotCandidate;
  return order;
}

}  // namespace m4mesh
