#include "render/texture_warp.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace m4mesh {

namespace {

constexpr Rgb kBackground{40, 40, 48};
constexpr Rgb kWire{255, 230, 60};
constexpr double kOnEdge = 1e-9;

int64_t floor_half(int64_t v) { return v >= 0 ? v / 2 : -((-v + 1) / 2); }

void line(Image& image, double x0, double y0, double x1, double y1) {
  const int steps = static_cast<int>(std::ceil(std::max(std::abs(x1 - x0), std::abs(y1 - y0)))) + 1;
  for (int i = 0; i <= steps; ++i) {
    const double t = static_cast<double>(i) / steps;
    const double x = x0 + (x1 - x0) * t, y = y0 + (y1 - y0) * t;
    if (x >= 0 && y >= 0 && x < image.width && y < image.height) image.at(static_cast<uint32_t>(x), static_cast<uint32_t>(y)) = kWire;
  }
}

}  // namespace

Canvas canvas_over(std::span<const Point> nodes) {
  if (nodes.empty()) return {};
  int64_t lx = nodes[0].x, hx = lx, ly = nodes[0].y, hy = ly;
  for (const Point& p : nodes) {
    lx = std::min<int64_t>(lx, p.x);
    hx = std::max<int64_t>(hx, p.x);
    ly = std::min<int64_t>(ly, p.y);
    hy = std::max<int64_t>(hy, p.y);
  }
  const int64_t x0 = floor_half(lx), y0 = floor_half(ly);
  return {x0, y0, static_cast<uint32_t>(floor_half(hx) + 1 - x0), static_cast<uint32_t>(floor_half(hy) + 1 - y0)};
}

Canvas united(const Canvas& a, const Canvas& b) {
  if (a.width == 0) return b;
  if (b.width == 0) return a;
  const int64_t x0 = std::min(a.x0, b.x0), y0 = std::min(a.y0, b.y0);
  const int64_t x1 = std::max(a.x0 + a.width, b.x0 + b.width), y1 = std::max(a.y0 + a.height, b.y0 + b.height);
  return {x0, y0, static_cast<uint32_t>(x1 - x0), static_cast<uint32_t>(y1 - y0)};
}

Image checkerboard(uint32_t width, uint32_t height, uint32_t square) {
  Image image(width, height);
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x) {
      const bool light = ((x / square) + (y / square)) % 2 == 0;
      // A gradient across the board, so that a warp shows which way it went.
      const auto shade = static_cast<uint8_t>(60 + 140 * x / std::max<uint32_t>(width - 1, 1));
      image.at(x, y) = light ? Rgb{255, 255, 255} : Rgb{shade, 90, static_cast<uint8_t>(200 - shade / 2)};
    }
  return image;
}

TextureWarp::TextureWarp(std::span<const Point> intra_nodes, std::span<const Triangle> triangles, const Image& texture, const Canvas& canvas)
    : TextureWarp(intra_nodes, triangles, texture, canvas_over(intra_nodes), canvas) {}

TextureWarp::TextureWarp(std::span<const Point> intra_nodes, std::span<const Triangle> triangles, const Image& texture, const Canvas& box,
                         const Canvas& canvas)
    : triangles_(triangles.begin(), triangles.end()), texture_(texture), canvas_(canvas) {
  const double su = static_cast<double>(texture.width) / box.width, sv = static_cast<double>(texture.height) / box.height;
  // A node at X half pixels lies at pixel X / 2; pixel centres sit at k + 1/2, texel centres at k.
  for (const Point& p : intra_nodes)
    texels_.push_back({(p.x / 2.0 - static_cast<double>(box.x0)) * su - 0.5, (p.y / 2.0 - static_cast<double>(box.y0)) * sv - 0.5});
}

Image TextureWarp::render(std::span<const Point> nodes, bool wireframe, std::vector<uint8_t>* covered) const {
  Image image(canvas_.width, canvas_.height, kBackground);
  if (covered) covered->assign(image.pixels.size(), 0);
  auto pixel = [&](const Point& p) {
    return std::pair<double, double>{p.x / 2.0 - static_cast<double>(canvas_.x0), p.y / 2.0 - static_cast<double>(canvas_.y0)};
  };
  for (const Triangle& t : triangles_) {
    const auto [ax, ay] = pixel(nodes[t.v[0]]);
    const auto [bx, by] = pixel(nodes[t.v[1]]);
    const auto [cx, cy] = pixel(nodes[t.v[2]]);
    const double area = (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
    if (area == 0) continue;
    const int64_t x_lo = std::max<int64_t>(0, static_cast<int64_t>(std::floor(std::min({ax, bx, cx}))));
    const int64_t x_hi = std::min<int64_t>(canvas_.width - 1, static_cast<int64_t>(std::ceil(std::max({ax, bx, cx}))));
    const int64_t y_lo = std::max<int64_t>(0, static_cast<int64_t>(std::floor(std::min({ay, by, cy}))));
    const int64_t y_hi = std::min<int64_t>(canvas_.height - 1, static_cast<int64_t>(std::ceil(std::max({ay, by, cy}))));
    const Texel& ta = texels_[t.v[0]];
    const Texel& tb = texels_[t.v[1]];
    const Texel& tc = texels_[t.v[2]];
    for (int64_t y = y_lo; y <= y_hi; ++y)
      for (int64_t x = x_lo; x <= x_hi; ++x) {
        const double px = static_cast<double>(x) + 0.5, py = static_cast<double>(y) + 0.5;
        // Barycentric weights of the pixel centre (either orientation).
        const double wb = ((px - ax) * (cy - ay) - (py - ay) * (cx - ax)) / area;
        const double wc = ((bx - ax) * (py - ay) - (by - ay) * (px - ax)) / area;
        const double wa = 1 - wb - wc;
        // Pixel centres on an edge belong to the triangle (division rounds them either way).
        if (wa < -kOnEdge || wb < -kOnEdge || wc < -kOnEdge) continue;
        image.at(static_cast<uint32_t>(x), static_cast<uint32_t>(y)) =
            bilinear(texture_, wa * ta.u + wb * tb.u + wc * tc.u, wa * ta.v + wb * tb.v + wc * tc.v);
        if (covered) (*covered)[static_cast<size_t>(y) * canvas_.width + static_cast<size_t>(x)] = 1;
      }
  }
  if (wireframe)
    for (const Triangle& t : triangles_)
      for (int i = 0; i < 3; ++i) {
        const auto [x0, y0] = pixel(nodes[t.v[i]]);
        const auto [x1, y1] = pixel(nodes[t.v[(i + 1) % 3]]);
        line(image, x0, y0, x1, y1);
      }
  return image;
}

}  // namespace m4mesh
