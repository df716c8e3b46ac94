#include "mesh3d/directed_edge_index.h"

#include <bit>

namespace m4mesh {

void DirectedEdgeIndex::reserve(size_t count) {
  size_t capacity = 16;
  while (capacity < 2 * count) capacity *= 2;
  if (capacity <= slots_.size()) return;
  std::vector<Slot> old = std::move(slots_);
  slots_.assign(capacity, Slot{});
  shift_ = 64 - std::countr_zero(capacity);
  for (const Slot& s : old)
    if (s.from != kNone) {
      size_t at = slot(s.from, s.to);
      while (slots_[at].from != kNone) at = (at + 1) & (capacity - 1);
      slots_[at] = s;
    }
}

uint32_t DirectedEdgeIndex::find(uint32_t from, uint32_t to) const {
  if (slots_.empty()) return kNone;
  for (size_t at = slot(from, to);; at = (at + 1) & (slots_.size() - 1)) {
    const Slot& s = slots_[at];
    if (s.from == from && s.to == to) return s.value;
    if (s.from == kNone) return kNone;
  }
}

void DirectedEdgeIndex::insert(uint32_t from, uint32_t to, uint32_t value) {
  if (2 * (count_ + 1) > slots_.size()) reserve(2 * (count_ + 1));
  size_t at = slot(from, to);
  while (slots_[at].from != kNone) at = (at + 1) & (slots_.size() - 1);
  slots_[at] = {from, to, value};
  ++count_;
}

}  // namespace m4mesh
