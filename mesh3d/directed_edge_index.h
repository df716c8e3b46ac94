// Directed edges of a mesh and a table from each to a number, for the
// gate traversal.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace m4mesh {

// A directed edge from→to.
struct HalfEdge {
  uint32_t from, to;
};

// Directed edge → a number: open addressing, linear probing.
class DirectedEdgeIndex {
 public:
  static constexpr uint32_t kNone = 0xFFFFFFFF;
  void reserve(size_t count);
  uint32_t find(uint32_t from, uint32_t to) const;
  // Keys must be new.
  void insert(uint32_t from, uint32_t to, uint32_t value);

 private:
  size_t slot(uint64_t key) const { return static_cast<size_t>((key * 0x9E3779B97F4A7C15ull) >> shift_); }
  std::vector<uint64_t> keys_;
  std::vector<uint32_t> values_;
  size_t count_ = 0;
  int shift_ = 64;
};

}  // namespace m4mesh
