// Shaded pictures of 3D meshes: an orthographic camera fitted to a box,
// a z-buffer, Lambert shading lit from the viewer; optionally per-vertex
// colours (an error through a colour map, with its legend).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "mesh/topology.h"
#include "mesh3d/sequence.h"
#include "render/image.h"

namespace m4mesh {

// Looks from azimuth and elevation (degrees) at a box, which fills
// `size` × `size` pixels with a margin.
class Camera {
 public:
  Camera(const Vec3& lo, const Vec3& hi, double azimuth, double elevation, uint32_t size);
  // Pixel x, y and depth (larger: nearer the viewer).
  std::array<double, 3> project(const Vec3& p) const;
  const Vec3& toward_viewer() const { return view_; }
  uint32_t size() const { return size_; }

 private:
  Vec3 right_, up_, view_, centre_;
  double scale_;
  uint32_t size_;
};

// The box of every frame of a sequence.
std::pair<Vec3, Vec3> sequence_box(const MeshSequence& sequence);

// What each frame's view frames: the sequence's box (kSequence), the
// frame's own (kFit), or the frame's centre with the largest frame's
// extent, so that the subject stays in the middle at one scale (kFollow).
enum class View { kFollow, kFit, kSequence };
std::vector<std::pair<Vec3, Vec3>> view_boxes(const MeshSequence& sequence, View view);

// One frame drawn into `image` at column `x0`: grey, or coloured per vertex
// when `colours` is not empty.
void draw_shaded(Image& image, uint32_t x0, const Camera& camera, std::span<const Vec3> positions, std::span<const Triangle> faces,
                 std::span<const Rgb> colours = {});

// The colour map of errors: 0 → dark blue … 1 → yellow (viridis-like).
Rgb error_colour(double t);
// A vertical colour bar at column x0, titled ERROR, with its range
// written at its ends (the error in the sequence's units).
void draw_legend(Image& image, uint32_t x0, double max_value);
// Text in 3 × 5 glyphs scaled by `scale` (digits, letters as capitals,
// . - + : / ( ) % ,), its top-left corner at x, y.
void draw_text(Image& image, uint32_t x, uint32_t y, const std::string& text, int scale);

}  // namespace m4mesh
