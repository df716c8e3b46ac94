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

// Directed edge → a number: open addressing, linear probing; a slot holds
// its key and value together, so that a probe reads one cache line.
// Vertices are below kNone.
class DirectedEdgeIndex {
 public:
  static constexpr uint32_t kNone = 0xFFFFFFFF;
  void reserve(size_t count);
  uint32_t find(uint32_t from, uint32_t to) const;
  // Keys must be new.
  void insert(uint32_t from, uint32_t to, uint32_t value);

 private:
  struct Slot {
    uint32_t from = kNone, to = kNone, value = kNone;
  };
  size_t slot(uint32_t from, uint32_t to) const {
    return static_cast<size_t>((((uint64_t{from} << 32) | to) * 0x9E3779B97F4A7C15ull) >> shift_);
  }
  std::vector<Slot> slots_;
  size_t count_ = 0;
  int shift_ = 64;
};

}  // namespace m4mesh
