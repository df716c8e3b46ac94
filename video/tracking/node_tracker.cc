#include "video/tracking/node_tracker.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "common/error.h"

namespace m4mesh {

namespace {

// Levels while the coarsest picture keeps 32 pixels on its shorter side.
int automatic_levels(uint32_t width, uint32_t height) {
  int levels = 0;
  while (levels < 4 && (std::min(width, height) >> (levels + 1)) >= 32) ++levels;
  return levels;
}

double orientation(const std::array<double, 2>& a, const std::array<double, 2>& b, const std::array<double, 2>& c) {
  return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

// What a reference sample costs where it lands: its absolute difference,
// or, out of the frame (content that left it), a fixed price.
constexpr float kOutsideCost = 12;

bool in_frame(const Luma& picture, double x, double y) { return x >= 0 && y >= 0 && x <= picture.width && y <= picture.height; }

float sample_cost(const Luma& picture, double x, double y, float value) {
  if (!in_frame(picture, x, y)) return kOutsideCost;
  return std::abs(picture.sample(x, y) - value);
}

// The nearest position on the half-pixel grid the syntax carries.
double on_half_pixel(double v) { return std::round(v * 2) * 0.5; }

}  // namespace

NodeTracker::NodeTracker(TrackingMesh mesh, const Luma& first, const TrackerOptions& options)
    : mesh_(std::move(mesh)), options_(options), positions_(mesh_.nodes) {
  if (mesh_.freedom.size() != mesh_.nodes.size()) throw usage_error("tracking: a freedom per node");
  if (options_.levels > 4 || options_.search > 63)
    throw usage_error("tracking: at most 4 pyramid levels and a search of 63 pixels");
  levels_ = options_.levels >= 0 ? options_.levels : automatic_levels(first.width, first.height);
  node_triangles_.resize(mesh_.nodes.size());
  for (uint32_t t = 0; t < mesh_.triangles.size(); ++t) {
    for (NodeIndex n : mesh_.triangles[t].v) node_triangles_[n].push_back(t);
    const Triangle& tri = mesh_.triangles[t];
    design_area_.push_back(static_cast<double>(orient(mesh_.nodes[tri.v[0]], mesh_.nodes[tri.v[1]], mesh_.nodes[tri.v[2]])) / 4);
  }
  x_lo_ = y_lo_ = std::numeric_limits<double>::max();
  x_hi_ = y_hi_ = std::numeric_limits<double>::lowest();
  for (const Point& p : mesh_.nodes) {
    x_lo_ = std::min(x_lo_, p.x / 2.0), x_hi_ = std::max(x_hi_, p.x / 2.0);
    y_lo_ = std::min(y_lo_, p.y / 2.0), y_hi_ = std::max(y_hi_, p.y / 2.0);
  }
  previous_pyramid_ = pyramid(first, levels_);
  build_samples(previous_pyramid_, mesh_.nodes);
}

void NodeTracker::build_samples(const std::vector<Luma>& reference, const std::vector<Point>& at) {
  samples_.assign(reference.size(), std::vector<std::vector<Sample>>(mesh_.triangles.size()));
  for (size_t level = 0; level < reference.size(); ++level) {
    const Luma& picture = reference[level];
    const double scale = 0.5 / static_cast<double>(1 << level);
    for (uint32_t t = 0; t < mesh_.triangles.size(); ++t) {
      const Triangle& tri = mesh_.triangles[t];
      const double ax = at[tri.v[0]].x * scale, ay = at[tri.v[0]].y * scale;
      const double bx = at[tri.v[1]].x * scale, by = at[tri.v[1]].y * scale;
      const double cx = at[tri.v[2]].x * scale, cy = at[tri.v[2]].y * scale;
      const double area = (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
      if (area <= 0) continue;
      const auto x_from = static_cast<int64_t>(std::max(0.0, std::floor(std::min({ax, bx, cx}))));
      const auto x_to = static_cast<int64_t>(std::min<double>(picture.width - 1, std::ceil(std::max({ax, bx, cx}))));
      const auto y_from = static_cast<int64_t>(std::max(0.0, std::floor(std::min({ay, by, cy}))));
      const auto y_to = static_cast<int64_t>(std::min<double>(picture.height - 1, std::ceil(std::max({ay, by, cy}))));
      std::vector<Sample>& out = samples_[level][t];
      for (int64_t y = y_from; y <= y_to; ++y)
        for (int64_t x = x_from; x <= x_to; ++x) {
          const double px = static_cast<double>(x) + 0.5, py = static_cast<double>(y) + 0.5;
          const double b1 = ((px - ax) * (cy - ay) - (py - ay) * (cx - ax)) / area;
          const double b2 = ((bx - ax) * (py - ay) - (by - ay) * (px - ax)) / area;
          if (b1 < 0 || b2 < 0 || b1 + b2 > 1) continue;
          out.push_back({static_cast<float>(b1), static_cast<float>(b2), picture.at(static_cast<uint32_t>(x), static_cast<uint32_t>(y))});
        }
    }
  }
}

double NodeTracker::triangle_cost(int level, uint32_t t, const std::vector<Position>& p, NodeIndex moved, const Position& to) const {
  const Triangle& tri = mesh_.triangles[t];
  const Position& a = tri.v[0] == moved ? to : p[tri.v[0]];
  const Position& b = tri.v[1] == moved ? to : p[tri.v[1]];
  const Position& c = tri.v[2] == moved ? to : p[tri.v[2]];
  const Luma& picture = frame_pyramid_[static_cast<size_t>(level)];
  double sum = 0;
  for (const Sample& s : samples_[static_cast<size_t>(level)][t]) {
    const double b0 = 1.0 - s.b1 - s.b2;
    const double x = b0 * a[0] + s.b1 * b[0] + s.b2 * c[0], y = b0 * a[1] + s.b1 * b[1] + s.b2 * c[1];
    sum += sample_cost(picture, x, y, s.value);
  }
  return sum;
}

bool NodeTracker::keeps_shape(uint32_t node, const Position& to, const std::vector<Position>& p, double scale) const {
  const double unit = scale * scale;  // a pixel's area on this level
  for (uint32_t t : node_triangles_[node]) {
    const Triangle& tri = mesh_.triangles[t];
    auto at = [&](NodeIndex n) -> const Position& { return n == node ? to : p[n]; };
    const double area = orientation(at(tri.v[0]), at(tri.v[1]), at(tri.v[2])) / unit;
    if (area <= 0 || area > design_area_[t] * kMaxStretch || area * kMaxStretch < design_area_[t]) return false;
  }
  return true;
}

bool NodeTracker::allowed(uint32_t node, const Position& to, double scale) const {
  const Point& from = positions_[node];
  const double limit = kMaxNodeMotion * 0.5 * scale;
  if (std::abs(to[0] - from.x * 0.5 * scale) > limit || std::abs(to[1] - from.y * 0.5 * scale) > limit) return false;
  const NodeFreedom freedom = this->freedom(node);
  if (freedom == NodeFreedom::kAlongX) return to[0] >= x_lo_ * scale && to[0] <= x_hi_ * scale;
  if (freedom == NodeFreedom::kAlongY) return to[1] >= y_lo_ * scale && to[1] <= y_hi_ * scale;
  return true;
}

void NodeTracker::translate_polygons(int level, std::vector<Position>& p, double scale) {
  const Luma& picture = frame_pyramid_[static_cast<size_t>(level)];
  const auto range = static_cast<int>(std::ceil(options_.search * scale));
  std::vector<Position> offsets(p.size(), Position{0, 0});
  std::vector<std::array<double, 3>> mapped;  // x, y, reference value of each polygon sample
  for (uint32_t n = 0; n < p.size(); ++n) {
    const NodeFreedom freedom = this->freedom(n);
    if (freedom == NodeFreedom::kFixed || outside_[n]) continue;
    mapped.clear();
    for (uint32_t t : node_triangles_[n]) {
      const Triangle& tri = mesh_.triangles[t];
      const Position &a = p[tri.v[0]], &b = p[tri.v[1]], &c = p[tri.v[2]];
      for (const Sample& s : samples_[static_cast<size_t>(level)][t]) {
        const double b0 = 1.0 - s.b1 - s.b2;
        mapped.push_back({b0 * a[0] + s.b1 * b[0] + s.b2 * c[0], b0 * a[1] + s.b1 * b[1] + s.b2 * c[1], s.value});
      }
    }
    if (mapped.empty()) continue;
    const int rx = freedom == NodeFreedom::kAlongY ? 0 : range, ry = freedom == NodeFreedom::kAlongX ? 0 : range;
    double best = std::numeric_limits<double>::max();
    int best_norm = 0;
    for (int dy = -ry; dy <= ry; ++dy)
      for (int dx = -rx; dx <= rx; ++dx) {
        double sum = 0;
        for (const auto& [x, y, value] : mapped) {
          sum += sample_cost(picture, x + dx, y + dy, static_cast<float>(value));
          if (sum > best) break;
        }
        const int norm = std::abs(dx) + std::abs(dy);
        if (sum < best || (sum == best && norm < best_norm)) best = sum, best_norm = norm, offsets[n] = {double(dx), double(dy)};
      }
  }
  // Each node takes its polygon's offset when no triangle folds; a node
  // refused waits for its neighbours to move first.
  for (int pass = 0; pass < 3; ++pass) {
    bool moved = false;
    for (uint32_t n = 0; n < p.size(); ++n) {
      if (offsets[n][0] == 0 && offsets[n][1] == 0) continue;
      const Position to{p[n][0] + offsets[n][0], p[n][1] + offsets[n][1]};
      if (!allowed(n, to, scale) || !keeps_shape(n, to, p, scale)) continue;
      p[n] = to;
      offsets[n] = {0, 0};
      moved = true;
    }
    if (!moved) break;
  }
}

void NodeTracker::descend(int level, std::vector<Position>& p, double scale, double step) {
  for (int sweep = 0; sweep < options_.sweeps; ++sweep) {
    bool moved = false;
    for (uint32_t n = 0; n < p.size(); ++n) {
      const NodeFreedom freedom = this->freedom(n);
      if (freedom == NodeFreedom::kFixed || outside_[n]) continue;
      double current = 0;
      for (uint32_t t : node_triangles_[n]) current += costs_[t];
      double best = current;
      Position best_to = p[n];
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          if ((dx == 0 && dy == 0) || (freedom == NodeFreedom::kAlongX && dy != 0) || (freedom == NodeFreedom::kAlongY && dx != 0)) continue;
          const Position to{p[n][0] + dx * step, p[n][1] + dy * step};
          if (!allowed(n, to, scale) || !keeps_shape(n, to, p, scale)) continue;
          double cost = 0;
          for (uint32_t t : node_triangles_[n]) {
            cost += triangle_cost(level, t, p, n, to);
            if (cost >= best) break;
          }
          if (cost < best) best = cost, best_to = to;
        }
      if (best_to == p[n]) continue;
      p[n] = best_to;
      for (uint32_t t : node_triangles_[n]) costs_[t] = triangle_cost(level, t, p, kNoNode, p[n]);
      moved = true;
    }
    if (!moved) break;
  }
}

// Each node where the global motion takes it, keeping its own displacement
// from the global motion in the last frame; where that folds a triangle,
// the last positions moved by the change of global motion alone (an
// orientation-preserving map). A node held on the frame's edge keeps its
// place across it.
std::vector<NodeTracker::Position> NodeTracker::start(const Affine& global) const {
  const bool from_first = options_.reference == TrackingReference::kFirst;
  const Affine change = from_first ? global.after(global_.inverse()) : global;
  std::vector<Position> carried(positions_.size()), moved(positions_.size());
  for (size_t n = 0; n < positions_.size(); ++n) {
    const Point& q = positions_[n];
    // On the half-pixel grid the syntax carries: the moves keep them there, and no rounding at the end folds a triangle.
    if (from_first) {
      const Point& origin = mesh_.nodes[n];
      const std::array<double, 2> now = global(origin.x * 0.5, origin.y * 0.5), before = global_(origin.x * 0.5, origin.y * 0.5);
      carried[n] = {on_half_pixel(now[0] + q.x * 0.5 - before[0]), on_half_pixel(now[1] + q.y * 0.5 - before[1])};
    }
    const std::array<double, 2> changed = change(q.x * 0.5, q.y * 0.5);
    moved[n] = {on_half_pixel(changed[0]), on_half_pixel(changed[1])};
    for (std::vector<Position>* p : {&carried, &moved}) {
      const NodeFreedom f = freedom(static_cast<uint32_t>(n));
      if (f == NodeFreedom::kFixed || f == NodeFreedom::kAlongY) (*p)[n][0] = q.x * 0.5;
      if (f == NodeFreedom::kFixed || f == NodeFreedom::kAlongX) (*p)[n][1] = q.y * 0.5;
    }
  }
  auto valid = [&](const std::vector<Position>& p) {
    for (uint32_t n = 0; n < p.size(); ++n)
      if (!allowed(n, p[n], 1.0) || !keeps_shape(n, p[n], p, 1.0)) return false;
    return true;
  };
  if (from_first && valid(carried)) return carried;
  if (valid(moved)) return moved;
  std::vector<Position> still(positions_.size());
  for (size_t n = 0; n < positions_.size(); ++n) still[n] = {positions_[n].x * 0.5, positions_[n].y * 0.5};
  return still;
}

// The linear map that takes the corners of a node's triangles from their
// offsets to the node in the reference to their offsets now (least squares,
// the polygons' positions): the local motion's shape. None where the
// corners do not span both axes, where they do not move as one linear map
// (over 2 pixels' RMS residual: a motion boundary crosses the ring) or where
// the map changes areas over twice, or under half, as much as the global
// motion.
std::optional<NodeTracker::Linear> NodeTracker::ring_shape(uint32_t node, const std::vector<Position>& p, const std::vector<Point>& origin,
                                                           const Affine& global) const {
  constexpr double kMaxResidual = 2;  // pixels, RMS
  struct Pair {
    double ex, ey, fx, fy;  // a corner's offset from the node in the reference and now
  };
  std::vector<Pair> ring;
  double sxx = 0, sxy = 0, syy = 0, ux = 0, uy = 0, vx = 0, vy = 0;
  for (uint32_t t : node_triangles_[node])
    for (NodeIndex k : mesh_.triangles[t].v) {
      if (k == node) continue;
      const Pair q{(origin[k].x - origin[node].x) * 0.5, (origin[k].y - origin[node].y) * 0.5, p[k][0] - p[node][0], p[k][1] - p[node][1]};
      sxx += q.ex * q.ex, sxy += q.ex * q.ey, syy += q.ey * q.ey;
      ux += q.fx * q.ex, uy += q.fx * q.ey, vx += q.fy * q.ex, vy += q.fy * q.ey;
      ring.push_back(q);
    }
  const double det = sxx * syy - sxy * sxy;
  if (!(det > 0)) return std::nullopt;
  const Linear m{(ux * syy - uy * sxy) / det, (uy * sxx - ux * sxy) / det, (vx * syy - vy * sxy) / det, (vy * sxx - vx * sxy) / det};
  double residual = 0;
  for (const Pair& q : ring) {
    const double rx = q.fx - m[0] * q.ex - m[1] * q.ey, ry = q.fy - m[2] * q.ex - m[3] * q.ey;
    residual += rx * rx + ry * ry;
  }
  const double area = m[0] * m[3] - m[1] * m[2], global_area = global.determinant();
  if (residual > kMaxResidual * kMaxResidual * static_cast<double>(ring.size()) || !(area > 0.5 * global_area && area < 2 * global_area))
    return std::nullopt;
  return m;
}

// The polygons put a node where its triangles' warp fits best, which a
// coarse mesh on a curved motion places off the node's own content, and
// where its polygon straddles a moving object's edge, on the other side's
// motion. Each node then matches a window of the reference around its own
// point (within its triangles) by a descent on the half-pixel grid from
// whichever of the polygons' position and its start fits the window better,
// taking only moves that keep the triangles' shapes. A window too flat to
// say leaves the node. The window is shaped by the global motion's linear
// part, or by the node's ring (ring_shape) where that fits clearly better
// near its two starts: a warp that turns or stretches the content under a
// node is then matched as it is. A larger window is taken where it fits
// better still: content that moves as one over it averages more noise.
void NodeTracker::place_on_content(std::vector<Position>& p, const std::vector<Position>& started, const Affine& global) const {
  constexpr int kRadius = 8, kLargerRadius = 11;  // pixels
  constexpr int kPasses = 4;
  constexpr double kRingFitsBetter = 0.9;  // the ring's shape is taken below this share of the global shape's cost
  const Luma &reference = previous_pyramid_[0], &picture = frame_pyramid_[0];
  const std::vector<Point>& origin = options_.reference == TrackingReference::kFirst ? mesh_.nodes : positions_;
  // The node's own content: the pixels of its triangles (a masked object's, not the background's).
  auto in_polygon = [&](uint32_t node, double x, double y) {
    for (uint32_t t : node_triangles_[node]) {
      const Triangle& tri = mesh_.triangles[t];
      const Position a{origin[tri.v[0]].x * 0.5, origin[tri.v[0]].y * 0.5}, b{origin[tri.v[1]].x * 0.5, origin[tri.v[1]].y * 0.5},
          c{origin[tri.v[2]].x * 0.5, origin[tri.v[2]].y * 0.5}, q{x, y};
      if (orientation(a, b, q) >= 0 && orientation(b, c, q) >= 0 && orientation(c, a, q) >= 0) return true;
    }
    return false;
  };
  // The mean absolute difference over the window's pixels that land in the frame: content leaving the frame neither
  // holds a node back nor pushes it out. A position where under half of them land in the frame is not taken. Infinite
  // as soon as the sum shows the cost is above `bound` (the mean over the pixels in the frame is at least sum / size).
  auto cost_at = [&](const Window& window, const Position& to, double bound = std::numeric_limits<double>::infinity()) {
    const double most = bound * static_cast<double>(window.size());
    double sum = 0;
    size_t inside = 0;
    for (const auto& [dx, dy, value] : window) {
      const double x = to[0] + dx, y = to[1] + dy;
      if (!in_frame(picture, x, y)) continue;
      sum += std::abs(picture.sample(x, y) - static_cast<float>(value));
      ++inside;
      if (sum > most) return std::numeric_limits<double>::infinity();
    }
    return 2 * inside < window.size() ? std::numeric_limits<double>::infinity() : sum / static_cast<double>(inside);
  };
  auto shaped = [](const Window& pixels, const Linear& m) {
    Window window;
    window.reserve(pixels.size());
    for (const auto& [dx, dy, value] : pixels) window.push_back({m[0] * dx + m[1] * dy, m[2] * dx + m[3] * dy, value});
    return window;
  };
  // A window's lowest cost on the half-pixel grid within a pixel of the node's two starts, if below `bound`.
  auto best_near = [&](const Window& window, uint32_t n, double bound = std::numeric_limits<double>::infinity()) {
    double best = bound;
    for (const Position& from : {p[n], started[n]})
      for (int sy = -2; sy <= 2; ++sy)
        for (int sx = -2; sx <= 2; ++sx) best = std::min(best, cost_at(window, {from[0] + 0.5 * sx, from[1] + 0.5 * sy}, best));
    return best < bound ? best : std::numeric_limits<double>::infinity();
  };
  const Linear global_shape{global.a[0], global.a[1], global.a[2], global.a[3]};
  // The reference's pixels within the larger window of a node and in its triangles, row by row.
  struct Pixel {
    int ring;  // max(|i|, |j|): the smallest window radius holding the pixel
    double dx, dy, gradient;
    float value;
  };
  auto pixels_around = [&](uint32_t n) {
    const double ox = origin[n].x * 0.5, oy = origin[n].y * 0.5;
    std::vector<Pixel> pixels;
    for (int j = -kLargerRadius; j <= kLargerRadius; ++j)
      for (int i = -kLargerRadius; i <= kLargerRadius; ++i) {
        const double x = std::floor(ox) + i + 0.5, y = std::floor(oy) + j + 0.5;
        if (x < 1 || y < 1 || x > reference.width - 1.0 || y > reference.height - 1.0 || !in_polygon(n, x, y)) continue;
        const auto xi = static_cast<uint32_t>(x), yi = static_cast<uint32_t>(y);
        const double gradient =
            std::abs(reference.at(xi + 1, yi) - reference.at(xi - 1, yi)) + std::abs(reference.at(xi, yi + 1) - reference.at(xi, yi - 1));
        pixels.push_back({std::max(std::abs(i), std::abs(j)), x - ox, y - oy, gradient, reference.at(xi, yi)});
      }
    return pixels;
  };
  // The window of a radius around a node, shaped by the global motion or by the node's ring where that fits clearly
  // better, and its lowest cost near the node's starts; none where too few of its pixels are the node's or too flat.
  auto fitted_window = [&](uint32_t n, const std::vector<Pixel>& around, int radius, const std::optional<Linear>& ring) {
    Window pixels;  // offsets from the node in the reference
    double gradient = 0;
    for (const Pixel& q : around)
      if (q.ring <= radius) gradient += q.gradient, pixels.push_back({q.dx, q.dy, q.value});
    if (pixels.size() < 32 || gradient < 2.0 * static_cast<double>(pixels.size())) return std::pair<Window, double>{};
    std::pair<Window, double> fit{shaped(pixels, global_shape), 0};
    fit.second = best_near(fit.first, n);
    if (ring) {
      Window fitted = shaped(pixels, *ring);
      if (const double cost = best_near(fitted, n, kRingFitsBetter * fit.second); cost < kRingFitsBetter * fit.second) fit = {std::move(fitted), cost};
    }
    return fit;
  };
  std::vector<Window> windows(p.size());
  for (uint32_t n = 0; n < p.size(); ++n) {
    if (freedom(n) == NodeFreedom::kFixed || outside_[n]) continue;
    const std::optional<Linear> ring = ring_shape(n, p, origin, global);
    const std::vector<Pixel> around = pixels_around(n);
    auto [window, cost] = fitted_window(n, around, kRadius, ring);
    if (window.empty()) continue;
    // Where the content moves as one over a larger window, its more pixels average the video's noise.
    if (auto [larger, larger_cost] = fitted_window(n, around, kLargerRadius, ring); !larger.empty() && larger_cost < cost) window = std::move(larger);
    windows[n] = std::move(window);
  }
  // A descent for each node: to the best of its eight neighbours a pixel away, then half a pixel away, while that lowers the cost.
  for (int pass = 0; pass < kPasses; ++pass) {
    bool moved = false;
    for (uint32_t n = 0; n < p.size(); ++n) {
      if (windows[n].empty()) continue;
      const NodeFreedom f = freedom(n);
      double current = cost_at(windows[n], p[n]);
      if (pass == 0 && started[n] != p[n] && allowed(n, started[n], 1.0) && keeps_shape(n, started[n], p, 1.0))
        if (const double there = cost_at(windows[n], started[n], current); there < current) p[n] = started[n], current = there, moved = true;
      for (const double step : {1.0, 0.5})
        for (bool improved = true; improved;) {
          improved = false;
          Position best_to = p[n];
          double best = current;
          for (int sy = -1; sy <= 1; ++sy)
            for (int sx = -1; sx <= 1; ++sx) {
              if ((sx == 0 && sy == 0) || (f == NodeFreedom::kAlongX && sy != 0) || (f == NodeFreedom::kAlongY && sx != 0)) continue;
              const Position to{p[n][0] + step * sx, p[n][1] + step * sy};
              if (!allowed(n, to, 1.0)) continue;
              if (const double cost = cost_at(windows[n], to, best); cost < best) best = cost, best_to = to;
            }
          if (best_to != p[n] && keeps_shape(n, best_to, p, 1.0)) p[n] = best_to, current = best, improved = moved = true;
        }
    }
    if (!moved) break;
  }
  // The descent's half-pixel grid is coarser than what the window can say: each node goes to the half pixel nearest
  // its window's sub-pixel fit.
  for (uint32_t n = 0; n < p.size(); ++n) {
    if (windows[n].empty()) continue;
    const std::optional<Position> fit = subpixel_fit(picture, windows[n], p[n]);
    if (!fit) continue;
    const NodeFreedom f = freedom(n);
    const Position to{f == NodeFreedom::kAlongY ? p[n][0] : on_half_pixel((*fit)[0]),
                      f == NodeFreedom::kAlongX ? p[n][1] : on_half_pixel((*fit)[1])};
    if (to != p[n] && allowed(n, to, 1.0) && keeps_shape(n, to, p, 1.0)) p[n] = to;
  }
}

const std::vector<Point>& NodeTracker::track(const Luma& frame) {
  if (frame.width != previous_pyramid_[0].width || frame.height != previous_pyramid_[0].height)
    throw Error(ErrorKind::kInput, "", kNoPlane, kNoOffset, "tracking: every frame must have the first frame's size");
  frame_pyramid_ = pyramid(frame, levels_);
  if (options_.reference == TrackingReference::kPrevious) build_samples(previous_pyramid_, positions_);

  // The global motion, from where the last frame's predicts it (constant velocity).
  const bool from_first = options_.reference == TrackingReference::kFirst;
  const Affine guess = from_first && has_velocity_ ? global_.after(global_before_.inverse()).after(global_) : global_;
  const Affine global = global_motion(previous_pyramid_, frame_pyramid_, guess, options_.search);
  std::vector<Position> p = start(global);
  const std::vector<Position> started = p;
  // A node whose start lies out of the frame (by over a 2-pixel margin) has little content to match: it keeps the global motion.
  constexpr double kMargin = 2;
  outside_.resize(p.size());
  for (size_t n = 0; n < p.size(); ++n)
    outside_[n] = p[n][0] < -kMargin || p[n][1] < -kMargin || p[n][0] > frame.width + kMargin || p[n][1] > frame.height + kMargin;
  for (int level = levels_; level >= 0; --level) {
    const double scale = 1.0 / static_cast<double>(1 << level);
    for (Position& q : p) q = {q[0] * scale, q[1] * scale};
    if (level == levels_) translate_polygons(level, p, scale);
    costs_.resize(mesh_.triangles.size());
    for (uint32_t t = 0; t < mesh_.triangles.size(); ++t) costs_[t] = triangle_cost(level, t, p, kNoNode, p[0]);
    descend(level, p, scale, 1.0);
    descend(level, p, scale, 0.5);
    for (Position& q : p) q = {q[0] / scale, q[1] / scale};
  }
  if (from_first) place_on_content(p, started, global);

  global_before_ = global_;
  global_ = global;
  for (size_t n = 0; n < p.size(); ++n) positions_[n] = {static_cast<int32_t>(std::lround(p[n][0] * 2)), static_cast<int32_t>(std::lround(p[n][1] * 2))};
  has_velocity_ = true;
  if (options_.reference == TrackingReference::kPrevious) previous_pyramid_ = std::move(frame_pyramid_);
  return positions_;
}

}  // namespace m4mesh
