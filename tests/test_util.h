// Helpers shared by the tests.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "mesh/plane.h"

namespace m4mesh::test {

// Bytes from a string of '0'/'1' (spaces and '|' ignored); the length must be a multiple of 8.
std::vector<uint8_t> bytes_from_bits(std::string_view bits);
// '0'/'1' string of bytes.
std::string bits_of(const std::vector<uint8_t>& bytes);

MeshPlane uniform_plane(uint32_t cols, uint32_t rows, uint32_t dx, uint32_t dy, uint32_t split);
MeshPlane inter_plane(std::vector<Point> nodes, uint32_t range = 0);
MeshPlane delaunay_plane(std::vector<Point> nodes, uint32_t boundary);

// Deterministic pseudo-random numbers for test inputs.
class Random {
 public:
  explicit Random(uint64_t seed) : state_(seed) {}
  uint64_t next();
  int32_t uniform(int32_t lo, int32_t hi);  // inclusive

 private:
  uint64_t state_;
};

// A random star-shaped simple polygon of `boundary` nodes around (512, 512)
// with `interior` distinct nodes strictly inside, in §10 order (node 0
// top-left, boundary counterclockwise).
std::vector<Point> random_polygon_with_interior(uint64_t seed, uint32_t boundary, uint32_t interior,
                                                int32_t min_radius = 150, int32_t max_radius = 500);

// Whether p lies strictly inside the polygon nodes[0 … boundary−1].
bool strictly_inside(const std::vector<Point>& nodes, uint32_t boundary, const Point& p);

// §9 text of a stream's decoding.
std::string decoded_text(const std::vector<uint8_t>& stream);

}  // namespace m4mesh::test
