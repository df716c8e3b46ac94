#include "mesh3d/position_order.h"

#include <limits>
#include <queue>

namespace m4mesh {

namespace {

constexpr uint32_t kNotCandidate = std::numeric_limits<uint32_t>::max();

// A candidate's support when it was queued, its parallelograms above its
// known corners: more support first, then the earlier candidate.
struct Entry {
  uint64_t support;
  uint32_t tie;
  bool operator<(const Entry& other) const { return support != other.support ? support < other.support : tie > other.tie; }
};
// Both counts stay below 2^28: a face counts once per corner of the candidate, with at most two other corners.
constexpr uint64_t kParallelogram = uint64_t{1} << 32, kCorner = 1;

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
  std::vector<uint32_t> grown;  // the candidates whose support grew at this step, queued once each after it
  std::vector<uint8_t> in_grown(count, 0);
  // Candidates with support, queued again whenever it grows (only the latest entry counts). Those without come
  // after them in the candidates' order, which first_unknown walks: no queue of every vertex.
  std::priority_queue<Entry> queue;
  uint32_t first_unknown = 0;
  const auto is_stale = [&](const Entry& entry) { return known[entry.tie] || entry.support != support[entry.tie]; };
  const auto grow = [&](uint32_t i, uint64_t part) {
    if (i == kNotCandidate || known[i]) return;
    support[i] += part;
    if (!in_grown[i]) in_grown[i] = 1, grown.push_back(i);
  };
  std::vector<uint32_t> order;
  order.reserve(count);
  while (order.size() < count) {
    while (!queue.empty() && is_stale(queue.top())) queue.pop();
    uint32_t i;
    if (!queue.empty()) {
      i = queue.top().tie;
      queue.pop();
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
    for (const uint32_t g : grown) {
      in_grown[g] = 0;
      queue.push({support[g], g});
    }
    grown.clear();
  }
  for (const uint32_t v : candidates) local_[v] = kNotCandidate;
  return order;
}

}  // namespace m4mesh
