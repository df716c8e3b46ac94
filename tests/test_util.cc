#include "tests/test_util.h"

#include <gtest/gtest.h>
#include <unistd.h>
#ifdef __linux__
#include <sched.h>
#endif

#include <cmath>
#include <fstream>
#include <numbers>
#include <set>
#include <stdexcept>
#include <thread>

#include "decoder/mesh3d/container_decoder.h"
#include "decoder/mesh_object_decoder.h"
#include "encoder/mesh_object_encoder.h"
#include "mesh/cdt.h"

namespace m4mesh::test {

bool on_one_core(const std::function<void()>& work) {
#ifdef __linux__
  bool pinned = false;
  std::thread([&] {
    cpu_set_t set;
    if (sched_getaffinity(0, sizeof set, &set) != 0) return;
    int first = 0;
    while (!CPU_ISSET(first, &set)) ++first;
    CPU_ZERO(&set);
    CPU_SET(first, &set);
    if (sched_setaffinity(0, sizeof set, &set) != 0) return;
    pinned = true;
    work();
  }).join();
  return pinned;
#else
  (void)work;
  return false;
#endif
}

TempDir::TempDir() {
  const ::testing::TestInfo* test = ::testing::UnitTest::GetInstance()->current_test_info();
  path_ = std::filesystem::temp_directory_path() /
          ("m4mesh-test-" + std::to_string(::getpid()) + "-" + (test ? std::string(test->test_suite_name()) + "." + test->name() : "outside-a-test"));
  std::filesystem::create_directories(path_);
}

TempDir::~TempDir() {
  std::error_code ignored;
  std::filesystem::remove_all(path_, ignored);
}

std::string TempDir::write(const std::string& name, const std::string& text) const {
  const std::filesystem::path file = path_ / name;
  std::ofstream(file) << text;
  return file.string();
}

std::vector<uint8_t> bytes_from_bits(std::string_view bits) {
  std::vector<uint8_t> bytes;
  int count = 0;
  uint32_t current = 0;
  for (char c : bits) {
    if (c == ' ' || c == '|' || c == '\n') continue;
    if (c != '0' && c != '1') throw std::invalid_argument("bit string with a character other than 0/1");
    current = (current << 1) | static_cast<uint32_t>(c == '1');
    if (++count % 8 == 0) {
      bytes.push_back(static_cast<uint8_t>(current));
      current = 0;
    }
  }
  if (count % 8 != 0) throw std::invalid_argument("bit string not a whole number of bytes");
  return bytes;
}

std::string bits_of(const std::vector<uint8_t>& bytes) {
  std::string s;
  for (uint8_t b : bytes)
    for (int i = 7; i >= 0; --i) s += ((b >> i) & 1) ? '1' : '0';
  return s;
}

bool strictly_inside(const std::vector<Point>& nodes, uint32_t boundary, const Point& p) {
  bool inside = false;
  for (uint32_t i = 0, j = boundary - 1; i < boundary; j = i++) {
    const Point &a = nodes[i], &b = nodes[j];
    if (orient(a, b, p) == 0 && std::min(a.x, b.x) <= p.x && p.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= p.y &&
        p.y <= std::max(a.y, b.y))
      return false;
    if ((a.y > p.y) != (b.y > p.y)) {
      const double x = a.x + static_cast<double>(p.y - a.y) * (b.x - a.x) / (b.y - a.y);
      if (p.x < x) inside = !inside;
    }
  }
  return inside;
}

std::vector<Point> random_polygon_with_interior(uint64_t seed, uint32_t boundary, uint32_t interior, int32_t min_radius,
                                                int32_t max_radius) {
  Random random(seed);
  for (int attempt = 0;; ++attempt) {
    std::vector<Point> nodes;
    std::set<std::pair<int, int>> used;
    for (uint32_t k = 0; k < boundary; ++k) {
      const double angle = 2 * std::numbers::pi * (k + 0.1 + 0.8 * static_cast<double>(random.next() % 1000) / 1000) / boundary;
      const double radius = random.uniform(min_radius, max_radius);
      const Point p{static_cast<int32_t>(std::lround(512 + radius * std::cos(angle))),
                    static_cast<int32_t>(std::lround(512 - radius * std::sin(angle)))};
      if (used.insert({p.x, p.y}).second) nodes.push_back(p);
    }
    const uint32_t b = static_cast<uint32_t>(nodes.size());
    while (nodes.size() < b + interior) {
      const Point p{random.uniform(0, 1023), random.uniform(0, 1023)};
      if (!used.count({p.x, p.y}) && strictly_inside(nodes, b, p)) {
        used.insert({p.x, p.y});
        nodes.push_back(p);
      }
    }
    const std::vector<NodeIndex> order = delaunay_node_order(nodes, b);
    std::vector<Point> ordered;
    for (NodeIndex i : order) ordered.push_back(nodes[i]);
    try {
      validate_delaunay_nodes(ordered, b);
      if (b == boundary) return ordered;
    } catch (const Error&) {
      if (attempt > 100) throw;
    }
  }
}

std::string decoded_text(const std::vector<uint8_t>& stream) {
  std::string text;
  decode_to_text(stream, {}, [&](std::string_view chunk) { text.append(chunk); });
  return text;
}

MeshSequence test_sequence(int frames, uint64_t seed) {
  MeshSequence s;
  std::vector<Vec3> base;
  const int rings = 8, segments = 12;
  base.push_back({0, 0, 1});
  for (int r = 1; r < rings; ++r)
    for (int k = 0; k < segments; ++k) {
      const double theta = std::numbers::pi * r / rings, phi = 2 * std::numbers::pi * k / segments;
      base.push_back({std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)});
    }
  base.push_back({0, 0, -1});
  const NodeIndex south = static_cast<NodeIndex>(base.size() - 1);
  auto ring = [&](int r, int k) { return static_cast<NodeIndex>(1 + (r - 1) * segments + (k % segments)); };
  for (int k = 0; k < segments; ++k) s.faces.push_back({{0, ring(1, k), ring(1, k + 1)}});
  for (int r = 1; r + 1 < rings; ++r)
    for (int k = 0; k < segments; ++k) {
      s.faces.push_back({{ring(r, k), ring(r + 1, k), ring(r + 1, k + 1)}});
      s.faces.push_back({{ring(r, k), ring(r + 1, k + 1), ring(r, k + 1)}});
    }
  for (int k = 0; k < segments; ++k) s.faces.push_back({{south, ring(rings - 1, k + 1), ring(rings - 1, k)}});
  const NodeIndex sheet = static_cast<NodeIndex>(base.size());
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 5; ++x) base.push_back({2.0 + 0.3 * x, 0.3 * y, 0.0});
  for (int y = 0; y + 1 < 4; ++y)
    for (int x = 0; x + 1 < 5; ++x) {
      const NodeIndex a = sheet + static_cast<NodeIndex>(y * 5 + x);
      s.faces.push_back({{a, a + 1, a + 6}});
      s.faces.push_back({{a, a + 6, a + 5}});
    }
  base.push_back({-3, 1, 0.5});  // in no face
  s.vertex_count = static_cast<uint32_t>(base.size());
  Random random(seed);
  for (int f = 0; f < frames; ++f) {
    std::vector<Vec3> frame = base;
    for (size_t i = 0; i < frame.size(); ++i) {
      const double t = 0.15 * f;
      frame[i].x += 0.2 * std::sin(t + frame[i].y) + 1e-4 * random.uniform(-5, 5);
      frame[i].y += 0.1 * std::cos(2 * t + frame[i].z);
      frame[i].z += 0.05 * f;
    }
    s.frames.push_back(std::move(frame));
  }
  return s;
}

int decode_damaged_mesh3d(const std::vector<uint8_t>& stream, size_t step, uint64_t seed) {
  int rejected = 0;
  for (size_t size = 0; size < stream.size(); size += step) {
    try {
      decode_mesh3d(std::vector<uint8_t>(stream.begin(), stream.begin() + static_cast<std::ptrdiff_t>(size)));
    } catch (const Error&) {
      ++rejected;
    }
  }
  Random random(seed);
  for (int trial = 0; trial < 300; ++trial) {
    std::vector<uint8_t> bad = stream;
    bad[static_cast<size_t>(random.uniform(0, static_cast<int32_t>(bad.size()) - 1))] ^= static_cast<uint8_t>(1 << random.uniform(0, 7));
    try {
      decode_mesh3d(bad);
    } catch (const Error&) {
    }
  }
  return rejected;
}

}  // namespace m4mesh::test
