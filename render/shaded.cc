#include "render/shaded.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <vector>

namespace m4mesh {

namespace {

Vec3 sub(const Vec3& a, const Vec3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
double dot(const Vec3& a, const Vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Vec3 cross(const Vec3& a, const Vec3& b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
Vec3 unit(const Vec3& a) {
  const double n = std::sqrt(dot(a, a));
  return n > 0 ? Vec3{a.x / n, a.y / n, a.z / n} : Vec3{0, 0, 1};
}

constexpr Rgb kBackground{250, 250, 250};
constexpr Rgb kGrey{170, 180, 195};

// 3 × 5 glyphs, row by row from the top: digits, capitals (lower case is
// drawn as capitals) and a few signs; other characters are blank.
uint16_t glyph(char c) {
  static const char* const kDigits[10] = {"####.##.##.####", ".#.##..#..#.###", "###..#####..###", "###..####..####", "#.##.####..#..#", "####..###..####", "####..####.####", "###..#..#..#..#", "####.#####.####", "####.####..####"};
  static const char* const kLetters[26] = {".#.#.#####.##.#", "##.#.###.#.###.", ".###..#..#...##", "##.#.##.##.###.", "####..##.#..###", "####..##.#..#..", ".###..#.##.#.##", "#.##.#####.##.#", "###.#..#..#.###", "..#..#..##.#.#.", "#.##.###.#.##.#", "#..#..#..#..###", "#.########.##.#", "##.#.##.##.##.#", ".#.#.##.##.#.#.", "##.#.###.#..#..", ".#.#.##.###..##", "##.#.###.#.##.#", ".###...#...###.", "###.#..#..#..#.", "#.##.##.##.####", "#.##.##.##.#.#.", "#.##.########.#", "#.##.#.#.#.##.#", "#.##.#.#..#..#.", "###..#.#.#..###"};
  const char* pattern = nullptr;
  if (c >= '0' && c <= '9') pattern = kDigits[c - '0'];
  if (c >= 'A' && c <= 'Z') pattern = kLetters[c - 'A'];
  if (c >= 'a' && c <= 'z') pattern = kLetters[c - 'a'];
  if (c == '.') pattern = ".............#.";
  if (c == '-') pattern = "......###......";
  if (c == '+') pattern = "....#.###.#....";
  if (c == ':') pattern = "....#.....#....";
  if (c == '/') pattern = "..#..#.#.#..#..";
  if (c == '(') pattern = ".#.#..#..#...#.";
  if (c == ')') pattern = ".#...#..#..#.#.";
  if (c == '%') pattern = "#.#..#.#.#..#.#";
  if (c == ',') pattern = "..........#.#..";
  uint16_t bits = 0;
  for (int i = 0; pattern && i < 15; ++i)
    if (pattern[i] == '#') bits |= static_cast<uint16_t>(1 << (14 - i));
  return bits;
}

}  // namespace

void draw_text(Image& image, uint32_t x, uint32_t y, const std::string& text, int scale) {
  for (char c : text) {
    const uint16_t bits = glyph(c);
    for (int row = 0; row < 5; ++row)
      for (int col = 0; col < 3; ++col)
        if (bits & (1 << (14 - (row * 3 + col))))
          for (int dy = 0; dy < scale; ++dy)
            for (int dx = 0; dx < scale; ++dx) {
              const uint32_t px = x + static_cast<uint32_t>(col * scale + dx), py = y + static_cast<uint32_t>(row * scale + dy);
              if (px < image.width && py < image.height) image.at(px, py) = {20, 20, 20};
            }
    x += static_cast<uint32_t>(4 * scale);
  }
}

Camera::Camera(const Vec3& lo, const Vec3& hi, double azimuth, double elevation, uint32_t size) : size_(size) {
  const double a = azimuth * std::numbers::pi / 180, e = elevation * std::numbers::pi / 180;
  // y is up; the viewer sits at azimuth a around it, e above the horizon.
  view_ = unit({std::sin(a) * std::cos(e), std::sin(e), std::cos(a) * std::cos(e)});
  right_ = unit(cross({0, 1, 0}, view_));
  up_ = cross(view_, right_);
  centre_ = {(lo.x + hi.x) / 2, (lo.y + hi.y) / 2, (lo.z + hi.z) / 2};
  double extent = 0;
  for (int corner = 0; corner < 8; ++corner) {
    const Vec3 c{corner & 1 ? hi.x : lo.x, corner & 2 ? hi.y : lo.y, corner & 4 ? hi.z : lo.z};
    const Vec3 d = sub(c, centre_);
    extent = std::max({extent, std::abs(dot(d, right_)), std::abs(dot(d, up_))});
  }
  scale_ = extent > 0 ? 0.46 * size / extent : 1;
}

std::array<double, 3> Camera::project(const Vec3& p) const {
  const Vec3 d = sub(p, centre_);
  return {size_ / 2.0 + scale_ * dot(d, right_), size_ / 2.0 - scale_ * dot(d, up_), dot(d, view_)};
}

std::pair<Vec3, Vec3> sequence_box(const MeshSequence& s) {
  Box3 box;
  for (const std::vector<Vec3>& frame : s.frames) box.add(frame);
  return {box.lo, box.hi};
}

std::vector<std::pair<Vec3, Vec3>> view_boxes(const MeshSequence& s, View view) {
  std::vector<std::pair<Vec3, Vec3>> boxes;
  if (view == View::kSequence) return std::vector<std::pair<Vec3, Vec3>>(s.frames.size(), sequence_box(s));
  Vec3 extent{0, 0, 0};  // the largest frame's, per axis
  for (const std::vector<Vec3>& frame : s.frames) {
    const Box3 box = box_of(frame);
    boxes.emplace_back(box.lo, box.hi);
    extent = {std::max(extent.x, box.hi.x - box.lo.x), std::max(extent.y, box.hi.y - box.lo.y), std::max(extent.z, box.hi.z - box.lo.z)};
  }
  if (view == View::kFollow)
    for (auto& [lo, hi] : boxes) {
      const Vec3 centre{(lo.x + hi.x) / 2, (lo.y + hi.y) / 2, (lo.z + hi.z) / 2};
      lo = {centre.x - extent.x / 2, centre.y - extent.y / 2, centre.z - extent.z / 2};
      hi = {centre.x + extent.x / 2, centre.y + extent.y / 2, centre.z + extent.z / 2};
    }
  return boxes;
}

void draw_shaded(Image& image, uint32_t x0, const Camera& camera, std::span<const Vec3> positions, std::span<const Triangle> faces,
                 std::span<const Rgb> colours) {
  const uint32_t size = camera.size();
  std::vector<float> depth(size_t{size} * size, -std::numeric_limits<float>::infinity());
  std::vector<std::array<double, 3>> screen(positions.size());
  for (size_t i = 0; i < positions.size(); ++i) screen[i] = camera.project(positions[i]);
  for (uint32_t y = 0; y < size; ++y)
    for (uint32_t x = 0; x < size; ++x) image.at(x0 + x, y) = kBackground;
  for (const Triangle& t : faces) {
    const auto& a = screen[t.v[0]];
    const auto& b = screen[t.v[1]];
    const auto& c = screen[t.v[2]];
    const double area = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
    if (area == 0) continue;
    // Lambert, both sides lit: the light comes from the viewer, a little from above.
    const Vec3 normal = unit(cross(sub(positions[t.v[1]], positions[t.v[0]]), sub(positions[t.v[2]], positions[t.v[0]])));
    const double light = 0.25 + 0.75 * std::abs(dot(normal, camera.toward_viewer()));
    const int64_t x_lo = std::max<int64_t>(0, static_cast<int64_t>(std::floor(std::min({a[0], b[0], c[0]}))));
    const int64_t x_hi = std::min<int64_t>(size - 1, static_cast<int64_t>(std::ceil(std::max({a[0], b[0], c[0]}))));
    const int64_t y_lo = std::max<int64_t>(0, static_cast<int64_t>(std::floor(std::min({a[1], b[1], c[1]}))));
    const int64_t y_hi = std::min<int64_t>(size - 1, static_cast<int64_t>(std::ceil(std::max({a[1], b[1], c[1]}))));
    for (int64_t y = y_lo; y <= y_hi; ++y)
      for (int64_t x = x_lo; x <= x_hi; ++x) {
        const double px = static_cast<double>(x) + 0.5, py = static_cast<double>(y) + 0.5;
        const double wb = ((px - a[0]) * (c[1] - a[1]) - (py - a[1]) * (c[0] - a[0])) / area;
        const double wc = ((b[0] - a[0]) * (py - a[1]) - (b[1] - a[1]) * (px - a[0])) / area;
        const double wa = 1 - wb - wc;
        if (wa < 0 || wb < 0 || wc < 0) continue;
        const auto z = static_cast<float>(wa * a[2] + wb * b[2] + wc * c[2]);
        float& nearest = depth[static_cast<size_t>(y) * size + static_cast<size_t>(x)];
        if (z <= nearest) continue;
        nearest = z;
        Rgb base = kGrey;
        if (!colours.empty()) {
          const Rgb& ca = colours[t.v[0]];
          const Rgb& cb = colours[t.v[1]];
          const Rgb& cc = colours[t.v[2]];
          auto mix = [&](uint8_t Rgb::*m) { return static_cast<uint8_t>(std::lround(wa * ca.*m + wb * cb.*m + wc * cc.*m)); };
          base = {mix(&Rgb::r), mix(&Rgb::g), mix(&Rgb::b)};
        }
        image.at(x0 + static_cast<uint32_t>(x), static_cast<uint32_t>(y)) = {static_cast<uint8_t>(base.r * light),
                                                                               static_cast<uint8_t>(base.g * light),
                                                                               static_cast<uint8_t>(base.b * light)};
      }
  }
}

Rgb error_colour(double t) {
  // Viridis at five stops, linear between them.
  static const Rgb kStops[5] = {{68, 1, 84}, {59, 82, 139}, {33, 145, 140}, {94, 201, 98}, {253, 231, 37}};
  t = std::clamp(t, 0.0, 1.0) * 4;
  const int i = std::min(static_cast<int>(t), 3);
  const double f = t - i;
  auto mix = [&](uint8_t Rgb::*m) { return static_cast<uint8_t>(std::lround(kStops[i].*m * (1 - f) + kStops[i + 1].*m * f)); };
  return {mix(&Rgb::r), mix(&Rgb::g), mix(&Rgb::b)};
}

void draw_legend(Image& image, uint32_t x0, double max_value) {
  const uint32_t top = image.height / 8, bottom = image.height - image.height / 8, width = 16;
  for (uint32_t x = x0; x < std::min(image.width, x0 + 80); ++x)
    for (uint32_t y = 0; y < image.height; ++y) image.at(x, y) = kBackground;
  for (uint32_t y = top; y < bottom; ++y) {
    const Rgb c = error_colour(static_cast<double>(bottom - 1 - y) / (bottom - top - 1));
    for (uint32_t x = x0 + 8; x < x0 + 8 + width && x < image.width; ++x) image.at(x, y) = c;
  }
  char text[32];
  std::snprintf(text, sizeof text, "%.2e", max_value);
  draw_text(image, x0 + 4, top - 28, "ERROR", 2);
  draw_text(image, x0 + 4, top - 14, text, 2);
  draw_text(image, x0 + 4, bottom + 4, "0", 2);
}

}  // namespace m4mesh
