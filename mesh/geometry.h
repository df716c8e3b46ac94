// Integer points and exact predicates. Coordinates are half-pixel integers
// with y pointing down (§1); orient() > 0 means clockwise as displayed.
#pragma once

#include <cstdint>

namespace m4mesh {

struct Point {
  int32_t x = 0;
  int32_t y = 0;
  friend bool operator==(const Point&, const Point&) = default;
};

// Twice the signed area of (a, b, c); > 0 clockwise as displayed. Exact for
// |coordinates| < 2^30.
inline int64_t orient(const Point& a, const Point& b, const Point& c) {
  return (int64_t{b.x} - a.x) * (int64_t{c.y} - a.y) - (int64_t{b.y} - a.y) * (int64_t{c.x} - a.x);
}

// > 0 when d lies inside the circle through a, b, c (orient(a, b, c) > 0),
// 0 on it. Exact for |coordinates| < 2^14 (the half-pixel range and the
// CDT's enclosing triangle fit).
inline int64_t incircle(const Point& a, const Point& b, const Point& c, const Point& d) {
  const int64_t adx = a.x - d.x, ady = a.y - d.y;
  const int64_t bdx = b.x - d.x, bdy = b.y - d.y;
  const int64_t cdx = c.x - d.x, cdy = c.y - d.y;
  const int64_t alift = adx * adx + ady * ady;
  const int64_t blift = bdx * bdx + bdy * bdy;
  const int64_t clift = cdx * cdx + cdy * cdy;
  return alift * (bdx * cdy - bdy * cdx) + blift * (cdx * ady - cdy * adx) + clift * (adx * bdy - ady * bdx);
}

// §1: smallest x + y, then smallest y.
inline bool more_top_left(const Point& a, const Point& b) {
  const int64_t sa = int64_t{a.x} + a.y, sb = int64_t{b.x} + b.y;
  return sa != sb ? sa < sb : a.y < b.y;
}

}  // namespace m4mesh
