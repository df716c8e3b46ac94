#include "syntax/values.h"

#include <bit>

namespace m4mesh {

int32_t delta_value(const DeltaCode& code) {
  if (code.length == 0) return 0;
  const int32_t bits = static_cast<int32_t>(code.bits);
  if ((bits >> (code.length - 1)) & 1) return bits;
  return bits - ((1 << code.length) - 1);
}

DeltaCode delta_code(int32_t value) {
  if (value == 0) return {0, 0};
  const uint32_t magnitude = static_cast<uint32_t>(value < 0 ? -value : value);
  const int length = std::bit_width(magnitude);
  const int32_t bits = value > 0 ? value : value + (1 << length) - 1;
  return {length, static_cast<uint32_t>(bits)};
}

uint32_t smallest_motion_range_code(int lo, int hi) {
  for (uint32_t code = 1; code <= 3; ++code) {
    MotionRange range(code);
    if (range.contains(lo) && range.contains(hi)) return code;
  }
  return 0;
}

}  // namespace m4mesh
