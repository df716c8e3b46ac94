// Value semantics of the coded elements: node deltas (§4.1) and motion
// vector differences (§4.2).
#pragma once

#include <cstdint>

#include "syntax/structures.h"

namespace m4mesh {

// §4.1: the value of a coded delta, and the code of a value (|v| ≤ 2047).
int32_t delta_value(const DeltaCode& code);
DeltaCode delta_code(int32_t value);

// §4.2: the motion vector range of a motion_range_code (1 … 3).
struct MotionRange {
  explicit MotionRange(uint32_t motion_range_code)
      : r_size(static_cast<int>(motion_range_code) - 1),
        f(1 << r_size),
        low(-32 * f),
        high(32 * f - 1),
        range(64 * f) {}

  int wrap(int v) const {
    if (v < low) v += range;
    if (v > high) v -= range;
    return v;
  }
  bool contains(int v) const { return v >= low && v <= high; }

  // The difference d coded by the VLC value m and residual res.
  int difference(int m, int res) const {
    if (f == 1 || m == 0) return m;
    int magnitude = ((m < 0 ? -m : m) - 1) * f + res + 1;
    return m < 0 ? -magnitude : magnitude;
  }
  // The VLC value and residual that code d (d inside [low, high]).
  void code(int d, int16_t& m, uint16_t& res) const {
    if (d == 0) {
      m = 0;
      res = 0;
      return;
    }
    int magnitude = d < 0 ? -d : d;
    int code = ((magnitude - 1) >> r_size) + 1;
    m = static_cast<int16_t>(d < 0 ? -code : code);
    res = static_cast<uint16_t>((magnitude - 1) & (f - 1));
  }

  int r_size;
  int f;
  int low;
  int high;
  int range;
};

// §10: the smallest motion_range_code whose range holds every component
// in [lo, hi]; 0 when none does.
uint32_t smallest_motion_range_code(int lo, int hi);

}  // namespace m4mesh
