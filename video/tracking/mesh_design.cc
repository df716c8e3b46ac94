#include "video/tracking/mesh_design.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "common/error.h"
#include "encoder/mesh_object_encoder.h"
#include "mesh/cdt.h"
#include "mesh/uniform.h"

namespace m4mesh {

namespace {

[[noreturn]] void refuse(ErrorKind kind, const std::string& message) { throw Error(kind, "", kNoPlane, kNoOffset, message); }

void check_frame(uint32_t width, uint32_t height, uint32_t smallest) {
  if (width > kMaxMeshFrameSide || height > kMaxMeshFrameSide)
    refuse(ErrorKind::kLimit, "a " + std::to_string(width) + " × " + std::to_string(height) + " frame: a mesh covers at most " +
                                  std::to_string(kMaxMeshFrameSide) + " × " + std::to_string(kMaxMeshFrameSide) + " pixels (coordinates 0 … 1023 half pixels)");
  if (width < smallest || height < smallest)
    refuse(ErrorKind::kUsage, "a " + std::to_string(width) + " × " + std::to_string(height) + " frame is too small for a mesh (" +
                                  std::to_string(smallest) + " × " + std::to_string(smallest) + " pixels at least)");
}

// The smaller eigenvalue of the structure tensor summed over 5 × 5 pixels.
std::vector<float> corner_strength(const Luma& frame) {
  const uint32_t w = frame.width, h = frame.height;
  std::vector<float> xx(size_t{w} * h), xy(xx.size()), yy(xx.size()), strength(xx.size());
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      const float gx = (frame.at(std::min(x + 1, w - 1), y) - frame.at(x > 0 ? x - 1 : 0, y)) * 0.5f;
      const float gy = (frame.at(x, std::min(y + 1, h - 1)) - frame.at(x, y > 0 ? y - 1 : 0)) * 0.5f;
      const size_t i = size_t{y} * w + x;
      xx[i] = gx * gx, xy[i] = gx * gy, yy[i] = gy * gy;
    }
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      double a = 0, b = 0, c = 0;
      for (uint32_t v = y > 2 ? y - 2 : 0; v <= std::min(y + 2, h - 1); ++v)
        for (uint32_t u = x > 2 ? x - 2 : 0; u <= std::min(x + 2, w - 1); ++u) {
          const size_t i = size_t{v} * w + u;
          a += xx[i], b += xy[i], c += yy[i];
        }
      strength[size_t{y} * w + x] = static_cast<float>((a + c) / 2 - std::sqrt((a - c) * (a - c) / 4 + b * b));
    }
  return strength;
}

double segment_distance(double px, double py, const Point& a, const Point& b) {
  const double ax = a.x / 2.0, ay = a.y / 2.0, dx = b.x / 2.0 - ax, dy = b.y / 2.0 - ay;
  const double length2 = dx * dx + dy * dy;
  const double t = length2 > 0 ? std::clamp(((px - ax) * dx + (py - ay) * dy) / length2, 0.0, 1.0) : 0.0;
  return std::hypot(px - ax - t * dx, py - ay - t * dy);
}

bool inside_polygon(double px, double py, const std::vector<Point>& polygon) {
  bool inside = false;
  for (size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++) {
    const double xi = polygon[i].x / 2.0, yi = polygon[i].y / 2.0, xj = polygon[j].x / 2.0, yj = polygon[j].y / 2.0;
    if ((yi > py) != (yj > py) && px < (xj - xi) * (py - yi) / (yj - yi) + xi) inside = !inside;
  }
  return inside;
}

// The outline of a hole-free 8-connected object: its border pixels in order
// (Moore-neighbour tracing), as half-pixel centres.
std::vector<Point> trace_outline(const Mask& object) {
  const uint32_t w = object.width, h = object.height;
  auto in = [&](int64_t x, int64_t y) { return x >= 0 && y >= 0 && x < w && y < h && object.inside[static_cast<size_t>(y) * w + static_cast<size_t>(x)]; };
  static constexpr int kDx[8] = {1, 1, 0, -1, -1, -1, 0, 1}, kDy[8] = {0, 1, 1, 1, 0, -1, -1, -1};
  const size_t first = static_cast<size_t>(std::find(object.inside.begin(), object.inside.end(), 1) - object.inside.begin());
  const int64_t sx = static_cast<int64_t>(first % w), sy = static_cast<int64_t>(first / w);
  std::vector<Point> outline;
  int64_t x = sx, y = sy;
  int from = 4;  // the direction of a background pixel: the start's west
  int first_move = -1;
  const size_t most = 4 * size_t{w} * h + 8;
  for (size_t steps = 0; steps < most; ++steps) {
    int next = -1;
    for (int k = 1; k <= 8 && next < 0; ++k)
      if (const int d = (from + k) % 8; in(x + kDx[d], y + kDy[d])) next = d;
    if (x == sx && y == sy) {
      if (next == first_move && next >= 0) break;  // the start entered as at first (Jacob's criterion)
      if (first_move < 0) first_move = next;
    }
    outline.push_back({static_cast<int32_t>(2 * x + 1), static_cast<int32_t>(2 * y + 1)});
    if (next < 0) break;  // a single pixel
    // The background pixel checked just before `next`, seen from the new pixel.
    const int back = (next + 7) % 8;
    const int bx = kDx[back] - kDx[next], by = kDy[back] - kDy[next];
    x += kDx[next], y += kDy[next];
    for (int d = 0; d < 8; ++d)
      if (kDx[d] == bx && kDy[d] == by) from = d;
  }
  return outline;
}

// Nodes in the §10 order with the decoder's triangles.
FrameMesh delaunay_mesh(std::vector<Point> nodes, std::vector<NodeFreedom> freedom, uint32_t boundary) {
  const std::vector<NodeIndex> order = delaunay_node_order(nodes, boundary);
  FrameMesh mesh;
  for (NodeIndex i : order) {
    mesh.tracking.nodes.push_back(nodes[i]);
    mesh.tracking.freedom.push_back(freedom[i]);
  }
  mesh.tracking.triangles = canonical_triangles(constrained_delaunay(mesh.tracking.nodes, boundary).triangles, mesh.tracking.nodes);
  mesh.plane = delaunay_plane(mesh.tracking.nodes, boundary);
  return mesh;
}

}  // namespace

FrameMesh uniform_frame_mesh(uint32_t width, uint32_t height, uint32_t cell_width, uint32_t cell_height) {
  if (cell_width < 1 || cell_height < 1 || cell_width > 127 || cell_height > 127)
    refuse(ErrorKind::kUsage, "--uniform: cells of 1 … 127 pixels a side (mesh_rect_size up to 255 half pixels)");
  check_frame(width, height, 1);
  if (cell_width > width || cell_height > height)
    refuse(ErrorKind::kUsage, "a " + std::to_string(width) + " × " + std::to_string(height) + " frame is smaller than one " +
                                  std::to_string(cell_width) + " × " + std::to_string(cell_height) + " mesh cell: choose smaller cells");
  const uint32_t dx = 2 * cell_width, dy = 2 * cell_height;
  const uint32_t cols = (2 * width - 1 + dx - 1) / dx + 1, rows = (2 * height - 1 + dy - 1) / dy + 1;
  FrameMesh mesh;
  mesh.plane = uniform_plane(cols, rows, dx, dy, 0);
  mesh.tracking.nodes = mesh.plane.nodes;
  mesh.tracking.triangles = canonical_triangles(uniform_triangles(mesh.plane.info.uniform), mesh.tracking.nodes);
  for (uint32_t r = 0; r < rows; ++r)
    for (uint32_t c = 0; c < cols; ++c) {
      const bool edge_x = c == 0 || c == cols - 1, edge_y = r == 0 || r == rows - 1;
      mesh.tracking.freedom.push_back(edge_x && edge_y ? NodeFreedom::kFixed
                                      : edge_y        ? NodeFreedom::kAlongX
                                      : edge_x        ? NodeFreedom::kAlongY
                                                      : NodeFreedom::kFree);
    }
  return mesh;
}

Mask mask_object(const Mask& mask) {
  const uint32_t w = mask.width, h = mask.height;
  auto morph = [&](const std::vector<uint8_t>& in, bool erode) {
    std::vector<uint8_t> out(in.size());
    for (uint32_t y = 0; y < h; ++y)
      for (uint32_t x = 0; x < w; ++x) {
        bool all = true, any = false;
        for (int64_t v = int64_t{y} - 1; v <= int64_t{y} + 1; ++v)
          for (int64_t u = int64_t{x} - 1; u <= int64_t{x} + 1; ++u) {
            const bool set = u >= 0 && v >= 0 && u < w && v < h && in[static_cast<size_t>(v) * w + static_cast<size_t>(u)];
            all = all && set, any = any || set;
          }
        out[size_t{y} * w + x] = erode ? all : any;
      }
    return out;
  };
  const std::vector<uint8_t> opened = morph(morph(mask.inside, true), false);
  // Largest 8-connected part.
  std::vector<int32_t> label(opened.size(), -1);
  std::vector<size_t> stack;
  size_t best_size = 0;
  int32_t best = -1, next_label = 0;
  for (size_t start = 0; start < opened.size(); ++start) {
    if (!opened[start] || label[start] >= 0) continue;
    size_t size = 0;
    label[start] = next_label;
    stack.assign(1, start);
    while (!stack.empty()) {
      const size_t i = stack.back();
      stack.pop_back();
      ++size;
      const int64_t x = static_cast<int64_t>(i % w), y = static_cast<int64_t>(i / w);
      for (int64_t v = y - 1; v <= y + 1; ++v)
        for (int64_t u = x - 1; u <= x + 1; ++u) {
          if (u < 0 || v < 0 || u >= w || v >= h) continue;
          const size_t j = static_cast<size_t>(v) * w + static_cast<size_t>(u);
          if (opened[j] && label[j] < 0) label[j] = next_label, stack.push_back(j);
        }
    }
    if (size > best_size) best_size = size, best = next_label;
    ++next_label;
  }
  if (best < 0) refuse(ErrorKind::kInput, "the mask outlines no object (none left after a 3 × 3 opening)");
  // Holes: background not 4-connected to the picture's border.
  std::vector<uint8_t> outside(opened.size(), 0);
  stack.clear();
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x)
      if ((x == 0 || y == 0 || x == w - 1 || y == h - 1) && label[size_t{y} * w + x] != best) outside[size_t{y} * w + x] = 1, stack.push_back(size_t{y} * w + x);
  while (!stack.empty()) {
    const size_t i = stack.back();
    stack.pop_back();
    const int64_t x = static_cast<int64_t>(i % w), y = static_cast<int64_t>(i / w);
    static constexpr int kStep[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
    for (const auto& s : kStep) {
      const int64_t u = x + s[0], v = y + s[1];
      if (u < 0 || v < 0 || u >= w || v >= h) continue;
      const size_t j = static_cast<size_t>(v) * w + static_cast<size_t>(u);
      if (!outside[j] && label[j] != best) outside[j] = 1, stack.push_back(j);
    }
  }
  Mask object{w, h, std::vector<uint8_t>(opened.size())};
  for (size_t i = 0; i < opened.size(); ++i) object.inside[i] = !outside[i];
  return object;
}

FrameMesh content_frame_mesh(const Luma& frame, uint32_t node_count, const Mask* mask) {
  const uint32_t w = frame.width, h = frame.height;
  check_frame(w, h, 4);
  if (node_count < 4 || node_count > 65535) refuse(ErrorKind::kUsage, "--nodes: 4 … 65535");
  Mask object;
  if (mask) {
    if (mask->width != w || mask->height != h)
      refuse(ErrorKind::kUsage, "the mask is " + std::to_string(mask->width) + " × " + std::to_string(mask->height) + ", the frames " +
                                    std::to_string(w) + " × " + std::to_string(h));
    object = mask_object(*mask);
  }
  const double area = mask ? static_cast<double>(std::count(object.inside.begin(), object.inside.end(), 1)) : static_cast<double>(w) * h;
  const double spacing = std::sqrt(area / node_count);

  // The boundary.
  std::vector<Point> nodes;
  std::vector<NodeFreedom> freedom;
  if (!mask) {
    const int32_t right = static_cast<int32_t>(2 * w - 1), bottom = static_cast<int32_t>(2 * h - 1);
    const auto cuts_x = static_cast<int32_t>(std::max(1L, std::lround(right / 2.0 / spacing)));
    const auto cuts_y = static_cast<int32_t>(std::max(1L, std::lround(bottom / 2.0 / spacing)));
    auto along = [](int32_t length, int32_t cuts, int32_t i) { return static_cast<int32_t>((int64_t{length} * i + cuts / 2) / cuts); };
    for (int32_t i = 0; i < cuts_x; ++i) nodes.push_back({along(right, cuts_x, i), 0}), freedom.push_back(i == 0 ? NodeFreedom::kFixed : NodeFreedom::kAlongX);
    for (int32_t i = 0; i < cuts_y; ++i) nodes.push_back({right, along(bottom, cuts_y, i)}), freedom.push_back(i == 0 ? NodeFreedom::kFixed : NodeFreedom::kAlongY);
    for (int32_t i = cuts_x; i > 0; --i) nodes.push_back({along(right, cuts_x, i), bottom}), freedom.push_back(i == cuts_x ? NodeFreedom::kFixed : NodeFreedom::kAlongX);
    for (int32_t i = cuts_y; i > 0; --i) nodes.push_back({0, along(bottom, cuts_y, i)}), freedom.push_back(i == cuts_y ? NodeFreedom::kFixed : NodeFreedom::kAlongY);
  } else {
    const std::vector<Point> outline = trace_outline(object);
    // The outline every `step` pixels; a finer step where a coarse one crosses itself.
    for (auto step = static_cast<size_t>(std::max(1.0, std::round(spacing)));; step = std::max<size_t>(1, step / 2)) {
      nodes.clear();
      for (size_t i = 0; i < outline.size(); i += step) nodes.push_back(outline[i]);
      bool simple = nodes.size() >= 3 && nodes.size() <= 1023;
      if (simple) {
        std::vector<Point> ordered;
        for (NodeIndex i : delaunay_node_order(nodes, static_cast<uint32_t>(nodes.size()))) ordered.push_back(nodes[i]);
        simple = delaunay_node_violations(ordered, static_cast<uint32_t>(ordered.size()), 1).empty();
      }
      if (simple) break;
      if (step == 1 || nodes.size() > 1023)
        refuse(ErrorKind::kInput, "the mask's outline (" + std::to_string(outline.size()) + " border pixels) gives no simple boundary of 3 … 1023 nodes");
    }
    freedom.assign(nodes.size(), NodeFreedom::kFree);
  }
  const auto boundary = static_cast<uint32_t>(nodes.size());
  if (boundary >= node_count) return delaunay_mesh(std::move(nodes), std::move(freedom), boundary);

  // Interior candidates: pixel centres well inside the boundary.
  const double margin = std::max(1.0, spacing / 3);
  std::vector<uint32_t> candidates;
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      const double px = x + 0.5, py = y + 0.5;
      if (mask) {
        if (!object.inside[size_t{y} * w + x] || !inside_polygon(px, py, nodes)) continue;
        bool clear = true;
        for (size_t i = 0, j = nodes.size() - 1; i < nodes.size() && clear; j = i++) clear = segment_distance(px, py, nodes[j], nodes[i]) >= margin;
        if (!clear) continue;
      } else if (px < margin || py < margin || px > w - 0.5 - margin || py > h - 0.5 - margin) {
        continue;
      }
      candidates.push_back(y * w + x);
    }
  const uint32_t interior = node_count - boundary;
  std::vector<double> nearest2(candidates.size());  // squared distance to the nearest node, pixels
  auto centre = [&](uint32_t c) { return std::pair<double, double>{c % w + 0.5, c / w + 0.5}; };
  for (size_t i = 0; i < candidates.size(); ++i) {
    const auto [px, py] = centre(candidates[i]);
    double best = std::numeric_limits<double>::max();
    for (const Point& p : nodes) best = std::min(best, (px - p.x / 2.0) * (px - p.x / 2.0) + (py - p.y / 2.0) * (py - p.y / 2.0));
    nearest2[i] = best;
  }
  auto place = [&](size_t i) {
    const auto [px, py] = centre(candidates[i]);
    nodes.push_back({static_cast<int32_t>(2 * (candidates[i] % w) + 1), static_cast<int32_t>(2 * (candidates[i] / w) + 1)});
    freedom.push_back(NodeFreedom::kFree);
    for (size_t j = 0; j < candidates.size(); ++j) {
      const auto [qx, qy] = centre(candidates[j]);
      nearest2[j] = std::min(nearest2[j], (px - qx) * (px - qx) + (py - qy) * (py - qy));
    }
  };
  // Structure first: strongest corners, 0.7 d apart.
  const std::vector<float> strength = corner_strength(frame);
  std::vector<size_t> by_strength(candidates.size());
  std::iota(by_strength.begin(), by_strength.end(), 0);
  std::stable_sort(by_strength.begin(), by_strength.end(), [&](size_t a, size_t b) { return strength[candidates[a]] > strength[candidates[b]]; });
  const float strongest = by_strength.empty() ? 0.0f : strength[candidates[by_strength.front()]];
  const uint32_t structured = interior * 3 / 4;
  const double apart2 = 0.49 * spacing * spacing;
  uint32_t placed = 0;
  for (size_t i : by_strength) {
    if (placed == structured || strength[candidates[i]] <= 0.01f * strongest) break;
    if (nearest2[i] < apart2) continue;
    place(i);
    ++placed;
  }
  // Then where the mesh is emptiest.
  for (; placed < interior; ++placed) {
    const size_t i = static_cast<size_t>(std::max_element(nearest2.begin(), nearest2.end()) - nearest2.begin());
    if (candidates.empty() || nearest2[i] < margin * margin) break;
    place(i);
  }
  return delaunay_mesh(std::move(nodes), std::move(freedom), boundary);
}

}  // namespace m4mesh
