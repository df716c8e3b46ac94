#include "mesh3d/directed_edge_index.h"

#include <algorithm>
#include <bit>
#include <utility>

namespace m4mesh {

void DirectedEdgeIndex::reserve(size_t edges) {
  size_t capacity = 16;
  while (capacity < 2 * edges) capacity *= 2;
  if (capacity <= slots_.size()) return;
  std::vector<Slot> old = std::move(slots_);
  slots_.assign(capacity, Slot{});
  shift_ = 64 - std::countr_zero(capacity);
  for (const Slot& s : old)
    if (s.low != kNone) slots_[place(s.low, s.high)] = s;
}

size_t DirectedEdgeIndex::place(uint32_t low, uint32_t high) const {
  size_t at = slot(low, high);
  while (slots_[at].low != kNone && (slots_[at].low != low || slots_[at].high != high)) at = (at + 1) & (slots_.size() - 1);
  return at;
}

uint32_t DirectedEdgeIndex::find(uint32_t from, uint32_t to) const {
  if (slots_.empty()) return kNone;
  const Slot& s = slots_[place(std::min(from, to), std::max(from, to))];
  return s.low == kNone ? kNone : s.value[from > to];
}

void DirectedEdgeIndex::insert(uint32_t from, uint32_t to, uint32_t value) { insert_and_find_reverse(from, to, value); }

uint32_t DirectedEdgeIndex::insert_and_find_reverse(uint32_t from, uint32_t to, uint32_t value) {
  if (2 * (count_ + 1) > slots_.size()) reserve(2 * (count_ + 1));
  const uint32_t low = std::min(from, to), high = std::max(from, to);
  Slot& s = slots_[place(low, high)];
  if (s.low == kNone) s.low = low, s.high = high, ++count_;
  s.value[from > to] = value;
  return s.value[from < to];
}

}  // namespace m4mesh
