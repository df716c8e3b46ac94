#include "mesh3d/directed_edge_index.h"

#include <bit>

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

}  // namespace m4mesh
