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

// Directed edge → a number: open addressing, linear probing. Both
// directions of an edge share a slot, which holds the edge's ends and the
// two numbers together: a probe reads one cache line, and a face's edges
// and their reverses are found in three probes. Vertices are below kNone.
class DirectedEdgeIndex {
 public:
  static constexpr uint32_t kNone = 0xFFFFFFFF;
  // Room for this many edges (a direction and its reverse count once).
  void reserve(size_t edges);
  uint32_t find(uint32_t from, uint32_t to) const;
  // Keys must be new.
  void insert(uint32_t from, uint32_t to, uint32_t value);
  // Inserts from→to (new) and returns to→from's number (kNone without one).
  uint32_t insert_and_find_reverse(uint32_t from, uint32_t to, uint32_t value);

 private:
  struct Slot {
    uint32_t low = kNone, high = kNone;  // the ends, low < high
    uint32_t value[2] = {kNone, kNone};  // of low→high, of high→low
  };
  size_t slot(uint32_t low, uint32_t high) const {
    return static_cast<size_t>((((uint64_t{low} << 32) | high) * 0x9E3779B97F4A7C15ull) >> shift_);
  }
  // The slot of edge low–high, or the empty slot where it would go.
  size_t place(uint32_t low, uint32_t high) const;
  std::vector<Slot> slots_;
  size_t count_ = 0;
  int shift_ = 64;
};

}  // namespace m4mesh
