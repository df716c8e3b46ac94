// The global motion between two pictures: the affine map q = A p + b that
// takes most points of a reference picture to where they lie in a frame
// (a camera's pan, zoom or rotation, or the bulk motion of the content).
// Found coarse to fine on their pyramids: a full search of translations
// on the coarsest level, then robust Gauss–Newton (iteratively reweighted
// least squares, Huber weights) on every level, so that objects moving
// against the rest weigh little. The node tracker starts its nodes there.
#pragma once

#include <array>
#include <vector>

#include "video/tracking/luma.h"

namespace m4mesh {

// q = A p + b in pixels: x' = a[0] x + a[1] y + a[4], y' = a[2] x + a[3] y + a[5].
struct Affine {
  std::array<double, 6> a{1, 0, 0, 1, 0, 0};

  std::array<double, 2> operator()(double x, double y) const { return {a[0] * x + a[1] * y + a[4], a[2] * x + a[3] * y + a[5]}; }
  double determinant() const { return a[0] * a[3] - a[1] * a[2]; }
  Affine inverse() const;
  // This map after `first`.
  Affine after(const Affine& first) const;
};

// The map from `reference` to `frame` (pyramids of the same levels, finest
// first), starting from `guess`; translations are searched ±`search`
// pixels around it on the coarsest level. A picture with too little
// structure to say gives the guess back.
Affine global_motion(const std::vector<Luma>& reference, const std::vector<Luma>& frame, const Affine& guess, uint32_t search);

}  // namespace m4mesh
