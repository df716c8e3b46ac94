// SplitMix64: the deterministic pseudo-random numbers of the project
// (insertion orders, test inputs, conformance streams).
#pragma once

#include <cstdint>

namespace m4mesh {

class SplitMix64 {
 public:
  explicit SplitMix64(uint64_t seed) : state_(seed) {}

  uint64_t next() {
    uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  // Uniform in [lo, hi] (a modulo, so not exactly uniform: fine for its uses).
  int32_t uniform(int32_t lo, int32_t hi) {
    return lo + static_cast<int32_t>(next() % static_cast<uint64_t>(int64_t{hi} - lo + 1));
  }

 private:
  uint64_t state_;
};

}  // namespace m4mesh
