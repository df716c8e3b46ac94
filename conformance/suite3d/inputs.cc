#include "conformance/suite3d/inputs.h"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>

#include "common/random.h"
#include "mesh3d/affine_octree.h"

namespace m4mesh::suite3d {

namespace {

// Frames of s.vertex_count positions at random on a 2^−10 grid of the unit box.
void add_random_frames(MeshSequence& s, int frames, SplitMix64& random) {
  for (int f = 0; f < frames; ++f) {
    std::vector<Vec3> frame;
    for (NodeIndex v = 0; v < s.vertex_count; ++v)
      frame.push_back({random.uniform(0, 1023) / 1024.0, random.uniform(0, 1023) / 1024.0, random.uniform(0, 1023) / 1024.0});
    s.frames.push_back(std::move(frame));
  }
}

}  // namespace

MeshSequence box_and_sheet(int frames, int n) {
  MeshSequence s;
  std::vector<Vec3> base;
  std::map<std::array<int, 3>, NodeIndex> index;
  auto vertex = [&](std::array<int, 3> p) {
    auto [it, added] = index.try_emplace(p, static_cast<NodeIndex>(base.size()));
    if (added) base.push_back({static_cast<double>(p[0]) / n, static_cast<double>(p[1]) / n, static_cast<double>(p[2]) / n});
    return it->second;
  };
  // Side (axis a fixed at 0 or n), outward orientation.
  for (int a = 0; a < 3; ++a)
    for (int high = 0; high < 2; ++high)
      for (int u = 0; u < n; ++u)
        for (int v = 0; v < n; ++v) {
          auto at = [&](int du, int dv) {
            std::array<int, 3> p;
            p[a] = high * n;
            p[(a + 1) % 3] = u + du;
            p[(a + 2) % 3] = v + dv;
            return vertex(p);
          };
          const NodeIndex p00 = at(0, 0), p10 = at(1, 0), p11 = at(1, 1), p01 = at(0, 1);
          if (high) {
            s.faces.push_back({{p00, p10, p11}});
            s.faces.push_back({{p00, p11, p01}});
          } else {
            s.faces.push_back({{p00, p11, p10}});
            s.faces.push_back({{p00, p01, p11}});
          }
        }
  const NodeIndex sheet = static_cast<NodeIndex>(base.size());
  for (int y = 0; y <= n; ++y)
    for (int x = 0; x <= n; ++x) base.push_back({2.0 + 0.25 * x, 0.25 * y, 0.5});
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const NodeIndex a = sheet + static_cast<NodeIndex>(y * (n + 1) + x);
      s.faces.push_back({{a, a + 1, a + static_cast<NodeIndex>(n + 2)}});
      s.faces.push_back({{a, a + static_cast<NodeIndex>(n + 2), a + static_cast<NodeIndex>(n + 1)}});
    }
  base.push_back({-1.5, 0.75, 0.25});
  s.vertex_count = static_cast<uint32_t>(base.size());
  for (int f = 0; f < frames; ++f) {
    const double t = 0.125 * f;
    std::vector<Vec3> frame = base;
    for (Vec3& p : frame) {
      const Vec3 o = p;
      p.x = o.x + t * 0.25 * o.y * o.z;
      p.y = o.y + t * (0.125 * o.x * o.x - 0.0625);
      p.z = o.z + t * t * 0.5 * (o.x - 1) * o.y + 0.03125 * f;
    }
    s.frames.push_back(std::move(frame));
  }
  return s;
}

MeshSequence rotating_sheet(int frames) {
  MeshSequence s;
  const int n = 9;
  for (int y = 0; y + 1 < n; ++y)
    for (int x = 0; x + 1 < n; ++x) {
      const NodeIndex a = static_cast<NodeIndex>(y * n + x);
      s.faces.push_back({{a, a + 1, a + static_cast<NodeIndex>(n + 1)}});
      s.faces.push_back({{a, a + static_cast<NodeIndex>(n + 1), a + static_cast<NodeIndex>(n)}});
    }
  s.vertex_count = n * n;
  std::vector<Vec3> frame;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) frame.push_back({static_cast<double>(x), static_cast<double>(y), 1});
  for (int f = 0; f < frames; ++f) {
    s.frames.push_back(frame);
    // A small rotation: cos = 0.96, sin = 0.28 (7² + 24² = 25²).
    for (Vec3& p : frame) p = {0.96 * p.x - 0.28 * p.y, 0.28 * p.x + 0.96 * p.y, p.z};
  }
  return s;
}

std::vector<Triangle> sheet_faces(int n, int rows) {
  std::vector<Triangle> faces;
  auto at = [n](int i, int j) { return static_cast<NodeIndex>(j * (n + 1) + i); };
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < n; ++i) {
      faces.push_back({{at(i, j), at(i + 1, j), at(i + 1, j + 1)}});
      faces.push_back({{at(i, j), at(i + 1, j + 1), at(i, j + 1)}});
    }
  return faces;
}

MeshSequence waving_flag(int frames, int n, bool collapse) {
  MeshSequence s;
  auto at = [n](int i, int j) { return static_cast<NodeIndex>(j * (n + 1) + i); };
  s.faces = sheet_faces(n, n);
  s.vertex_count = static_cast<uint32_t>((n + 1) * (n + 1) + 1);
  for (int f = 0; f < frames; ++f) {
    std::vector<Vec3> frame;
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) {
        const double x = static_cast<double>(i) / n, z = static_cast<double>(j) / n;
        const double p = x - 0.125 * f;
        const double wave = f == 0 ? 0 : 0.5 * p * (1 - p) * (p - 0.5) * (1 + 0.25 * z);
        frame.push_back({x - 0.0625 * wave * wave, wave, z});
      }
    frame.push_back({-0.5, 0.25 * f, 0.75});
    if (collapse && f == frames - 1) frame[at(1, 1)] = frame[at(2, 1)];
    s.frames.push_back(std::move(frame));
  }
  return s;
}

MeshSequence waving_strip(int frames, int n, int rows) {
  MeshSequence s;
  s.faces = sheet_faces(n, rows);
  s.vertex_count = static_cast<uint32_t>((n + 1) * (rows + 1));
  for (int f = 0; f < frames; ++f) {
    std::vector<Vec3> frame;
    for (int j = 0; j <= rows; ++j)
      for (int i = 0; i <= n; ++i) {
        const double x = static_cast<double>(i) / n, z = static_cast<double>(j) / rows, p = x - 0.125 * f / 8;
        const double wave = f == 0 ? 0 : 0.5 * p * (1 - p) * (p - 0.5) * (1 + 0.25 * z) * (1 + 0.3 * z * z);
        frame.push_back({x - 0.0625 * wave * wave, wave, static_cast<double>(j) / n});
      }
    s.frames.push_back(std::move(frame));
  }
  return s;
}

MeshSequence spiky_sheet(int frames, int n, int loose, uint64_t seed, int one_in) {
  MeshSequence s;
  s.faces = sheet_faces(n, n);
  const int moving = (n + 1) * (n + 1) + loose;
  s.vertex_count = static_cast<uint32_t>(moving + 2);
  SplitMix64 random(seed);
  std::vector<Vec3> offset(static_cast<size_t>(moving));
  auto jump = [&](double& d) {
    if (random.next() % static_cast<uint64_t>(one_in)) return;
    if (d != 0 && random.next() % 2) {
      d = 0;
      return;
    }
    // Drawn one at a time: the order of a call's arguments is the compiler's.
    const int exponent = random.uniform(2, 23);
    const double mantissa = random.uniform(1, 8) / 8.0;
    const double sign = random.next() % 2 ? 1 : -1;
    d = std::ldexp(mantissa, -exponent) * sign;
  };
  for (int f = 0; f < frames; ++f) {
    std::vector<Vec3> frame;
    for (int v = 0; v < moving; ++v) {
      Vec3& d = offset[static_cast<size_t>(v)];
      jump(d.x);
      jump(d.y);
      jump(d.z);
      const int i = v % (n + 1), j = v / (n + 1);  // the loose vertices continue the sheet's rows, a quarter higher
      frame.push_back({0.25 + 0.5 * i / n + d.x, 0.25 + 0.5 * j / n + d.y, (j > n ? 0.75 : 0.5) + d.z});
    }
    frame.push_back({0, 0, 0});
    frame.push_back({1, 1, 1});
    s.frames.push_back(std::move(frame));
  }
  return s;
}

std::vector<int32_t> prefix_schedule() {
  constexpr int kQuiet = 100;  // a sum of 2^13 + 2 decays below 16 in 100 symbols
  std::vector<int32_t> schedule;
  for_each_prefix_pattern(13, [&](int32_t first, int32_t second) {
    schedule.insert(schedule.end(), kQuiet, 0);
    schedule.push_back(first);
    schedule.push_back(second);
  });
  return schedule;
}

MeshSequence designed_loose(int frames, int loose, const std::function<int32_t(int, int)>& offset) {
  MeshSequence s;
  s.faces = sheet_faces(2, 2);
  const int sheet = 9;
  s.vertex_count = static_cast<uint32_t>(sheet + loose + 2);
  for (int f = 0; f < frames; ++f) {
    std::vector<Vec3> frame;
    for (int v = 0; v < sheet; ++v) frame.push_back({1000.0 * (v % 3), 1000.0 * (v / 3), 0});
    for (int v = 0; v < loose; ++v) {
      const double d = f == 0 ? 0 : offset(f, v);
      frame.push_back({20000.0 + 16 * (v % 64) + d, 20000.0 + 16 * (v / 64) + d, 30000 + d});
    }
    frame.push_back({0, 0, 0});
    frame.push_back({65535, 65535, 65535});
    s.frames.push_back(std::move(frame));
  }
  return s;
}

MeshSequence loose_chain(const std::vector<int32_t>& schedule) {
  MeshSequence s = designed_loose(1, 0, {});
  s.vertex_count += static_cast<uint32_t>(schedule.size());
  std::vector<Vec3>& frame = s.frames[0];
  Vec3 at{32768, 32768, 32768};
  for (int32_t step : schedule) {
    at = {at.x + step, at.y + step, at.z + step};
    frame.push_back(at);
  }
  s.frames.push_back(frame);
  return s;
}

MeshSequence parallelogram_quads(const std::vector<int32_t>& schedule) {
  MeshSequence s = designed_loose(1, 0, {});
  std::vector<Vec3>& frame = s.frames[0];
  for (int32_t step : schedule) {
    const NodeIndex a = static_cast<NodeIndex>(frame.size());
    s.faces.push_back({{a, a + 1, a + 2}});
    s.faces.push_back({{a + 2, a + 1, a + 3}});
    frame.push_back({32768, 32768, 32768});
    frame.push_back({32784, 32768, 32768});
    frame.push_back({32768, 32784, 32768});
    frame.push_back({32784.0 + step, 32784.0 + step, 32768.0 + step});
  }
  s.vertex_count = static_cast<uint32_t>(frame.size());
  s.frames.push_back(frame);
  return s;
}

MeshSequence direct_triples() {
  const std::vector<Vec3> place = {{0, 0, 0}, {32768, 32768, 32768}, {65535, 65535, 65535}};
  MeshSequence s;
  s.faces = {{{0, 1, 2}}};
  s.vertex_count = 3;
  s.frames.push_back(place);
  for_each_prefix_pattern(13, [&](int32_t first, int32_t second) {
    std::vector<Vec3> moved = place;
    moved[0] = {1.0 * first, 1.0 * first, 1.0 * first};
    moved[1] = {32768.0 + second, 32768.0 + second, 32768.0 + second};
    s.frames.push_back(moved);
    s.frames.push_back(place);
  });
  return s;
}

MeshSequence matrix_pairs() {
  constexpr int kFraction = 14;
  constexpr int64_t kFar = (1 << 19) - 1, kApart = 1 << 17;
  const std::array<int64_t, 3> shape[5] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 0}};
  std::vector<IntPoint3> place;
  for (int cluster = 0; cluster < 2; ++cluster)
    for (const auto& corner : shape) {
      IntPoint3 p;
      for (int axis = 0; axis < 3; ++axis) p[axis] = static_cast<int32_t>(cluster ? kFar - kApart * corner[axis] : kApart * corner[axis]);
      place.push_back(p);
    }
  const RootCube cube = root_cube(place);
  auto frame_of = [](std::span<const IntPoint3> grid) {
    std::vector<Vec3> frame;
    for (const IntPoint3& p : grid) frame.push_back({1.0 * p[0], 1.0 * p[1], 1.0 * p[2]});
    return frame;
  };
  MeshSequence s;
  s.faces = {{{0, 1, 2}}, {{5, 6, 7}}};
  s.vertex_count = 10;
  s.frames.push_back(frame_of(place));
  for_each_prefix_pattern(13, [&](int32_t first, int32_t second) {
    const int32_t residual[2] = {first, second};
    std::vector<IntPoint3> moved = place;
    for (int cluster = 0; cluster < 2; ++cluster) {
      AffineMatrix q;
      q.fill(residual[cluster]);
      for (int axis = 0; axis < 3; ++axis) q[static_cast<size_t>(5 * axis)] += 1 << kFraction;
      const std::array<int64_t, 3> corner{cube.min[0] + cluster * (cube.side >> 1), cube.min[1] + cluster * (cube.side >> 1),
                                          cube.min[2] + cluster * (cube.side >> 1)};
      for (size_t v = 5 * static_cast<size_t>(cluster); v < 5 * static_cast<size_t>(cluster) + 5; ++v) {
        const std::array<int64_t, 3> p = apply_affine(q, kFraction, corner, cube.side, place[v]);
        moved[v] = {static_cast<int32_t>(p[0]), static_cast<int32_t>(p[1]), static_cast<int32_t>(p[2])};
      }
    }
    s.frames.push_back(frame_of(moved));
    s.frames.push_back(frame_of(place));
  });
  return s;
}

std::string rest_shape_file(const MeshSequence& flag) {
  MeshSequence rest = flag;
  rest.frames.resize(1);
  // A name of this process's own: suites are built by tests running side by side.
  static int made = 0;
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("m4mesh-suite3d-rest-shape-" + std::to_string(::getpid()) + "-" + std::to_string(made++) + ".m4seq"))
                               .string();
  write_binary_sequence(rest, path);
  return path;
}

MeshSequence moving_tetrahedron(int frames) {
  MeshSequence s;
  s.vertex_count = 4;
  s.faces = {{{0, 2, 1}}, {{0, 1, 3}}, {{1, 2, 3}}, {{2, 0, 3}}};
  for (int f = 0; f < frames; ++f) {
    const double t = 0.25 * f;
    s.frames.push_back({{t, 0, 0}, {1 + t * t, 0, 0}, {0, 1 - 0.5 * t, 0}, {0.5 * t, 0, 1}});
  }
  return s;
}

MeshSequence deep_clusters(int frames) {
  constexpr double kStep = 1.0 / (1 << 24);
  MeshSequence s;
  std::vector<Vec3> base = {{0, 0, 0}, {1, 1, 1}, {1, 0, 0}};
  s.faces.push_back({{0, 1, 2}});
  const Vec3 centres[4] = {{0.3125, 0.6875, 0.4375}, {0.8125, 0.1875, 0.5625}, {0.5, 0.5, 0.5}, {0.25, 0.25, 0.75}};
  const int apart[4] = {12, 20, 40, 80};
  std::vector<NodeIndex> first;
  for (int c = 0; c < 4; ++c)
    for (int half = 0; half < 2; ++half) {
      const NodeIndex start = static_cast<NodeIndex>(base.size());
      first.push_back(start);
      for (int j = 0; j < 6; ++j)
        base.push_back({centres[c].x + kStep * (j % 2 + half * apart[c]), centres[c].y + kStep * (j / 2 % 2), centres[c].z + kStep * (j / 4)});
      for (NodeIndex j = 1; j < 5; ++j) s.faces.push_back({{start, start + j, start + j + 1}});
    }
  s.vertex_count = static_cast<uint32_t>(base.size());
  SplitMix64 random(8);
  for (int f = 0; f < frames; ++f) {
    std::vector<Vec3> frame = base;
    if (f % 2 == 1)
      for (size_t k = 0; k < first.size(); ++k) {
        const Vec3 shift{random.uniform(-64, 64) / 1024.0, random.uniform(-64, 64) / 1024.0, random.uniform(-64, 64) / 1024.0};
        for (NodeIndex v = first[k]; v < first[k] + 6; ++v) {
          const bool rigid = k % 2 == 0;
          const Vec3 d = rigid ? shift : Vec3{random.uniform(-64, 64) / 1024.0, random.uniform(-64, 64) / 1024.0, random.uniform(-64, 64) / 1024.0};
          frame[v] = {base[v].x + d.x, base[v].y + d.y, base[v].z + d.z};
        }
      }
    s.frames.push_back(std::move(frame));
  }
  return s;
}

MeshSequence clustered_jumps(int frames, int depth) {
  MeshSequence s;
  SplitMix64 random(static_cast<uint64_t>(100 + depth));
  std::vector<Vec3> base = {{0, 0, 0}, {1, 1, 1}, {1, 0, 0}};
  s.faces.push_back({{0, 1, 2}});
  struct Cluster {
    NodeIndex start;
    double cell;
    bool rigid;
  };
  std::vector<Cluster> clusters;
  auto cluster = [&](int level, int x, int y, int z, bool rigid) {
    const double cell = std::ldexp(1.0, -level);
    const NodeIndex start = static_cast<NodeIndex>(base.size());
    for (int j = 0; j < 6; ++j)
      base.push_back({(x + random.uniform(1, 7) / 8.0) * cell, (y + random.uniform(1, 7) / 8.0) * cell, (z + random.uniform(1, 7) / 8.0) * cell});
    for (NodeIndex j = 1; j < 5; ++j) s.faces.push_back({{start, start + j, start + j + 1}});
    clusters.push_back({start, cell, rigid});
  };
  auto place = [&](int level) { return random.uniform(0, (1 << level) - 1); };
  for (int c = 0; c < 2; ++c) {
    const int z = place(depth), y = place(depth), x = place(depth);  // drawn in this order, not in the arguments' unspecified one
    cluster(depth, x, y, z, false);
  }
  for (int c = 0; c < 2; ++c) {
    const int up = depth - 1, x = place(up) & ~1, y = place(up), z = place(up);
    cluster(up, x, y, z, true);
    cluster(up, x + 1, y, z, false);
  }
  s.vertex_count = static_cast<uint32_t>(base.size());
  for (int f = 0; f < frames; ++f) {
    std::vector<Vec3> frame = base;
    for (const Cluster& c : clusters) {
      if (f == 0) break;
      const Vec3 shift{c.cell * random.uniform(-8, 8) / 64, c.cell * random.uniform(-8, 8) / 64, c.cell * random.uniform(-8, 8) / 64};
      for (NodeIndex v = c.start; v < c.start + 6; ++v) {
        const Vec3 d = c.rigid ? shift : Vec3{c.cell * random.uniform(-32, 32) / 64, c.cell * random.uniform(-32, 32) / 64, c.cell * random.uniform(-32, 32) / 64};
        frame[v] = {base[v].x + d.x, base[v].y + d.y, base[v].z + d.z};
      }
    }
    s.frames.push_back(std::move(frame));
  }
  return s;
}

MeshSequence awkward_mesh(int frames) {
  MeshSequence s;
  std::vector<Vec3> base;
  const int n = 4;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) base.push_back({static_cast<double>(x), static_cast<double>(y), 0});
  for (int y = 0; y + 1 < n; ++y)
    for (int x = 0; x + 1 < n; ++x) {
      const NodeIndex a = static_cast<NodeIndex>(y * n + x);
      s.faces.push_back({{a, a + 1, a + n + 1}});
      s.faces.push_back({{a, a + n + 1, a + n}});
    }
  const NodeIndex o = static_cast<NodeIndex>(base.size());
  for (const Vec3& p : {Vec3{6, 0, 0}, Vec3{8, 0, 0}, Vec3{7, 1, 0}, Vec3{7, -1, 0}, Vec3{7, 0, 1}, Vec3{7, 0, -1}}) base.push_back(p);
  const NodeIndex octahedron[8][3] = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  for (const auto& f : octahedron) s.faces.push_back({{o + f[0], o + f[1], o + f[2]}});
  const NodeIndex h = static_cast<NodeIndex>(base.size());
  for (const Vec3& p : {Vec3{0, 5, 0}, Vec3{1, 5, 0}, Vec3{1, 6, 0}, Vec3{0, 6, 0}, Vec3{-1, 5, 0}, Vec3{-1, 4, 0}, Vec3{0, 4, 0},
                        Vec3{1, 7, 1}, Vec3{0, 2, 2}, Vec3{9, 9, 9}, Vec3{9, 8, 9}, Vec3{2, 6, 1}, Vec3{-3, -3, 0}, Vec3{5, 5, 5}})
    base.push_back(p);
  const std::array<NodeIndex, 3> extra[] = {{h, h + 1, h + 2}, {h, h + 2, h + 3}, {h, h + 4, h + 5}, {h, h + 5, h + 6},  // fans at h
                                            {0, 1, h + 8},                                                                  // edge 0 → 1 again
                                            {h + 9, h + 9, h + 10},                                                         // degenerate
                                            {h, h + 1, h + 2},                                                              // repeated
                                            {h + 2, h + 1, h + 11},                                                         // consistent
                                            {h + 1, h + 2, h + 7}};                                                         // the wrong way
  for (const auto& f : extra) s.faces.push_back({f});
  // Numbered backwards, so that the input order is not the coding order.
  s.vertex_count = static_cast<uint32_t>(base.size());
  for (Triangle& t : s.faces)
    for (NodeIndex& v : t.v) v = s.vertex_count - 1 - v;
  std::reverse(base.begin(), base.end());
  for (int f = 0; f < frames; ++f) {
    std::vector<Vec3> frame = base;
    for (Vec3& p : frame) p = {p.x + 0.25 * f * p.y, p.y - 0.125 * f, p.z + 0.5 * f * p.x * p.y};
    s.frames.push_back(std::move(frame));
  }
  return s;
}

MeshSequence crown(int frames, int k, int length) {
  MeshSequence s;
  std::vector<Vec3> base = {{0, 0, 2}, {0, 0, -1}};
  std::vector<std::vector<NodeIndex>> columns(static_cast<size_t>(2 * k));
  for (int j = 0; j < 2 * k; ++j) {
    const int arm = j / 2, rows = length - std::min(arm, k - arm);
    for (int t = 0; t <= rows; ++t) {
      columns[static_cast<size_t>(j)].push_back(static_cast<NodeIndex>(base.size()));
      base.push_back({static_cast<double>(j) * 0.25, static_cast<double>(j % 2) * 0.125 + 0.0625 * t, 1 - static_cast<double>(t) / rows});
    }
  }
  auto column = [&](int j) -> const std::vector<NodeIndex>& { return columns[static_cast<size_t>(j % (2 * k))]; };
  for (int j = 0; j < 2 * k; ++j) s.faces.push_back({{1, column(j + 1).back(), column(j).back()}});
  for (int arm = 0; arm < k; ++arm) {
    const std::vector<NodeIndex>&l = column(2 * arm), &r = column(2 * arm + 1);
    for (size_t t = 0; t + 1 < l.size(); ++t) {
      s.faces.push_back({{l[t], l[t + 1], r[t + 1]}});
      s.faces.push_back({{l[t], r[t + 1], r[t]}});
    }
  }
  for (int j = 0; j < 2 * k; ++j) s.faces.push_back({{0, column(j).front(), column(j + 1).front()}});
  s.faces.push_back({{column(0).back(), column(0).back(), 1}});
  s.vertex_count = static_cast<uint32_t>(base.size());
  for (int f = 0; f < frames; ++f) {
    std::vector<Vec3> frame = base;
    for (Vec3& p : frame) p = {p.x + 0.125 * f * p.z, p.y - 0.0625 * f * p.x, p.z};
    s.frames.push_back(std::move(frame));
  }
  return s;
}

MeshSequence irregular_grid(int frames, int n) {
  MeshSequence s;
  auto at = [n](int x, int y) { return static_cast<NodeIndex>(y * (n + 1) + x); };
  SplitMix64 random(16);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const NodeIndex a = at(x, y), b = at(x + 1, y), c = at(x + 1, y + 1), d = at(x, y + 1);
      if (random.next() % 2) {
        s.faces.push_back({{a, b, c}});
        s.faces.push_back({{a, c, d}});
      } else {
        s.faces.push_back({{a, b, d}});
        s.faces.push_back({{b, c, d}});
      }
    }
  s.vertex_count = static_cast<uint32_t>((n + 1) * (n + 1));
  for (int f = 0; f < frames; ++f) {
    std::vector<Vec3> frame;
    for (int y = 0; y <= n; ++y)
      for (int x = 0; x <= n; ++x) frame.push_back({static_cast<double>(x), y + 0.125 * f, 0.125 * ((7 * x + 3 * y) % 5)});
    s.frames.push_back(std::move(frame));
  }
  return s;
}

void renumber_at_random(MeshSequence& s, uint64_t seed) {
  std::vector<NodeIndex> number(s.vertex_count);
  for (NodeIndex v = 0; v < s.vertex_count; ++v) number[v] = v;
  SplitMix64 random(seed);
  for (size_t i = number.size() - 1; i > 0; --i) std::swap(number[i], number[static_cast<size_t>(random.next() % (i + 1))]);
  for (Triangle& t : s.faces)
    for (NodeIndex& v : t.v) v = number[v];
  for (std::vector<Vec3>& frame : s.frames) {
    std::vector<Vec3> shuffled(frame.size());
    for (size_t v = 0; v < frame.size(); ++v) shuffled[number[v]] = frame[v];
    frame = std::move(shuffled);
  }
}

MeshSequence shuffled_grid(int frames) {
  MeshSequence s = irregular_grid(frames, 15);
  const size_t grid_faces = s.faces.size();
  // The top edge c → d of a quad's second face, again with the seed's first
  // vertex: the parallelogram of the vertex above crosses it.
  for (size_t f = 37; f < grid_faces; f += 82) s.faces.push_back({{s.faces[f].v[1], s.faces[f].v[2], s.faces[0].v[0]}});
  s.faces.push_back({{5, 5, 6}});
  renumber_at_random(s, 256);
  return s;
}

MeshSequence far_chain(int faces, uint64_t seed) {
  MeshSequence s;
  SplitMix64 random(seed);
  std::set<std::pair<NodeIndex, NodeIndex>> edges;
  auto free = [&](NodeIndex a, NodeIndex b, NodeIndex c) { return !edges.count({a, b}) && !edges.count({b, c}) && !edges.count({c, a}); };
  auto add = [&](NodeIndex a, NodeIndex b, NodeIndex c) {
    s.faces.push_back({{a, b, c}});
    edges.insert({a, b});
    edges.insert({b, c});
    edges.insert({c, a});
  };
  NodeIndex count = 3;
  add(0, 1, 2);
  while (s.faces.size() < static_cast<size_t>(faces)) {
    // Across an edge of the last face that no face has reversed yet.
    const Triangle last = s.faces.back();
    const int first = static_cast<int>(random.next() % 3);
    int e = 0;
    while (e < 3 && edges.count({last.v[(first + e + 1) % 3], last.v[(first + e) % 3]})) ++e;
    if (e == 3) break;
    const NodeIndex a = last.v[(first + e) % 3], b = last.v[(first + e + 1) % 3];
    NodeIndex c = count;
    if (random.next() % 2) c = static_cast<NodeIndex>(random.next() % count);
    if (c == a || c == b || !free(b, a, c)) c = count;
    if (c == count) ++count;
    add(b, a, c);
  }
  s.vertex_count = count;
  add_random_frames(s, 2, random);
  return s;
}

MeshSequence dense_soup(uint32_t vertices, int faces, uint64_t seed) {
  MeshSequence s;
  SplitMix64 random(seed);
  std::set<std::pair<NodeIndex, NodeIndex>> edges;
  for (int attempt = 0; attempt < 100 * faces && s.faces.size() < static_cast<size_t>(faces); ++attempt) {
    const NodeIndex a = static_cast<NodeIndex>(random.next() % vertices), b = static_cast<NodeIndex>(random.next() % vertices),
                    c = static_cast<NodeIndex>(random.next() % vertices);
    if (a == b || b == c || c == a || edges.count({a, b}) || edges.count({b, c}) || edges.count({c, a})) continue;
    s.faces.push_back({{a, b, c}});
    edges.insert({a, b});
    edges.insert({b, c});
    edges.insert({c, a});
  }
  s.vertex_count = vertices;
  add_random_frames(s, 2, random);
  return s;
}

}  // namespace m4mesh::suite3d
