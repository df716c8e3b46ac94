#include "conformance/suite3d/base_mesh_oracles.h"

#include <algorithm>

namespace m4mesh::suite3d {

std::vector<uint8_t> base_mesh_unit(std::vector<uint8_t> unit_header, syntax::EntropyWriteIO<false>& symbols, uint32_t vertex_order) {
  const std::vector<uint8_t> bins = symbols.finish_bins(), raw = symbols.finish_raw();
  BaseMeshData data;
  data.vertex_order = vertex_order;
  data.arithmetic_bytes = static_cast<uint32_t>(bins.size());
  data.bins = bins;
  data.raw = raw;
  return unit_with(std::move(unit_header), data);
}

std::vector<uint8_t> broken_base_mesh_unit(std::vector<uint8_t> unit_header, uint32_t vertex_count, uint32_t face_count, BrokenBaseMesh oracle,
                                           std::vector<int32_t> order_differences) {
  syntax::EntropyWriteIO<false> symbols(syntax::SectionPlace{});
  StopAtFailureIO io(symbols);
  syntax::BaseMeshContexts contexts;
  GateTraversal traversal(face_count);
  try {
    describe_traversal(io, contexts, traversal, vertex_count, face_count, &oracle);
    describe_loose_faces(io, vertex_count, std::span<Triangle>());
    for (int32_t& d : order_differences) contexts.order.describe(io, 0, d, syntax::kOrderNames);
  } catch (const StopAtFailureIO::Stop&) {
  }
  return base_mesh_unit(std::move(unit_header), symbols, order_differences.empty() ? kVertexOrderCoding : kVertexOrderFromGate);
}

namespace {

// A bin the components are chosen for: any but a residual's sign and top
// bins, which every component reaches, and the front's (base-26 reaches
// them all).
bool is_counted_bin(const std::tuple<std::string, int, bool>& bin) {
  const std::string& name = std::get<0>(bin);
  return !name.ends_with("_sign") && !name.ends_with("_top") && name != "far_on_front" && name != "front_index";
}

}  // namespace

std::vector<uint64_t> covering_component_seeds() {
  std::vector<uint64_t> chosen;
  std::set<std::tuple<std::string, int, bool>> reached;
  SplitMix64 random(60);
  for (;;) {
    uint64_t best = 0;
    size_t most = 0;
    for (int trial = 0; trial < 2000; ++trial) {
      const uint64_t seed = random.next();
      size_t fresh = 0;
      for (const auto& bin : traversed(ComponentOracle({seed})).bins) fresh += is_counted_bin(bin) && !reached.count(bin);
      if (fresh > most) {
        most = fresh;
        best = seed;
      }
    }
    if (most == 0) return chosen;
    chosen.push_back(best);
    for (const auto& bin : traversed(ComponentOracle({best})).bins)
      if (is_counted_bin(bin)) reached.insert(bin);
  }
}

FrontOracle::FrontOracle() {
  for (uint32_t i = 0; i + 1 < GateTraversal::kMaxFront; ++i) inner_indices_.insert(i);
  for (uint32_t size = 1; size <= GateTraversal::kMaxFront; ++size) last_sizes_.insert(size);
}

std::optional<uint32_t> FrontOracle::far_vertex(HalfEdge gate, std::span<const uint32_t> candidates, bool any) {
  traversal_->front(gate, candidates, front_);
  const uint32_t size = static_cast<uint32_t>(front_.size());
  if (last_sizes_.count(size) && can_attach(gate, front_.back())) {
    last_sizes_.erase(size);
    return front_.back();
  }
  if (!any) return std::nullopt;
  for (const uint32_t i : inner_indices_)
    if (i + 1 < size && can_attach(gate, front_[i])) {
      inner_indices_.erase(i);
      return front_[i];
    }
  if (off_front_ && size > 0)
    for (uint32_t v = 0; v < visited_; ++v)
      if (std::find(front_.begin(), front_.end(), v) == front_.end() && std::find(candidates.begin(), candidates.end(), v) == candidates.end() &&
          can_attach(gate, v)) {
        off_front_ = false;
        return v;
      }
  return std::nullopt;
}

GateAnswer FrontOracle::gate(HalfEdge gate, std::span<const uint32_t> candidates) {
  if (++gates_ > kGates || done()) throw std::out_of_range("front oracle done");
  GateAnswer answer{GateSymbol::kNewVertex, 0, 0};
  if (visited_ >= kDisc) {
    if (const std::optional<uint32_t> c = far_vertex(gate, candidates, gates_ % 3 == 0)) answer = {GateSymbol::kFarVertex, 0, *c};
    else if (gates_ % 3 != 2 && !candidates.empty() && can_attach(gate, candidates[0])) answer = {GateSymbol::kCandidate, 0, 0};
  }
  if (answer.symbol == GateSymbol::kNewVertex && !can_attach(gate, visited_)) answer.symbol = GateSymbol::kBorder;
  add(gate, answer, candidates, visited_);
  return answer;
}

std::vector<int32_t> order_schedule(uint32_t count) {
  std::vector<uint32_t> unused(count);
  for (uint32_t i = 0; i < count; ++i) unused[i] = i;
  const std::vector<int32_t> schedule = prefix_schedule();
  std::vector<int32_t> differences;
  int64_t previous = -1;
  for (uint32_t i = 0; i < count; ++i) {
    const int64_t predicted = std::clamp<int64_t>(previous + 1, 0, count - 1);
    const int64_t from = std::lower_bound(unused.begin(), unused.end(), static_cast<uint32_t>(predicted)) - unused.begin();
    const int64_t room_above = static_cast<int64_t>(unused.size()) - from;
    int32_t d = i < schedule.size() ? std::abs(schedule[i]) : 0;
    if (room_above <= from) d = -d;
    if (room_above == 0 && d == 0) d = -1;  // the prediction is past every number left
    differences.push_back(d);
    previous = unused[static_cast<size_t>(from + d)];
    unused.erase(unused.begin() + from + d);
  }
  return differences;
}

}  // namespace m4mesh::suite3d
