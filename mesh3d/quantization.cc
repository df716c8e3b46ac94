#include "mesh3d/quantization.h"

#include <algorithm>
#include <cmath>
#include <numbers>


namespace m4mesh {

namespace {

Grid over_box(const Box3& box, double steps, bool equal_steps) {
  const Vec3& lo = box.lo;
  const Vec3& hi = box.hi;
  const double extent[3] = {hi.x - lo.x, hi.y - lo.y, hi.z - lo.z};
  const double largest = std::max({extent[0], extent[1], extent[2], 1e-30});
  Grid grid;
  const double low[3] = {lo.x, lo.y, lo.z};
  for (int axis = 0; axis < 3; ++axis) {
    grid.origin[axis] = static_cast<float>(low[axis]);
    grid.step[axis] = static_cast<float>((extent[axis] > 0 && !equal_steps ? extent[axis] : largest) / steps);
    if (!(grid.step[axis] > 0)) grid.step[axis] = 1e-30f;
  }
  return grid;
}

double steps_of(int bits) { return std::ldexp(1.0, bits) - 1; }

}  // namespace

double power_of_sqrt2(int half) { return half % 2 == 0 ? std::ldexp(1.0, half / 2) : std::ldexp(std::numbers::sqrt2, (half - 1) / 2); }

Grid Grid::over(std::span<const Vec3> frame, int bits, bool equal_steps) { return over_box(box_of(frame), steps_of(bits), equal_steps); }

Grid Grid::over_half_bits(std::span<const Vec3> frame, int half_bits, bool equal_steps) {
  return over_box(box_of(frame), power_of_sqrt2(half_bits) - 1, equal_steps);
}

Grid Grid::covering(const FrameSource& source, int bits, bool equal_steps) {
  FrameReader first_frame(source);
  const Grid first = over(first_frame.get(0), bits, equal_steps);
  // Quantizing is monotonic per axis: every position fits when the box's corners do.
  const Box3& box = source.scan().box;
  IntPoint3 q;
  if (first.quantize(box.lo, q) && first.quantize(box.hi, q)) return first;
  return over_box(box, steps_of(bits), equal_steps);
}

bool Grid::quantize(const Vec3& p, IntPoint3& q) const {
  const double value[3] = {p.x, p.y, p.z};
  for (int axis = 0; axis < 3; ++axis) {
    const double index = std::nearbyint((value[axis] - static_cast<double>(origin[axis])) / static_cast<double>(step[axis]));
    if (!(std::abs(index) <= static_cast<double>(kMaxQuantized))) return false;
    q[axis] = static_cast<int32_t>(index);
  }
  return true;
}

}  // namespace m4mesh
