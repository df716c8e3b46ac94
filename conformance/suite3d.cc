#include "conformance/suite3d.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <string_view>
#include <tuple>

#include "common/atomic_file.h"
#include "common/bit_cast.h"
#include "common/md5.h"
#include "common/random.h"
#include "decoder/mesh3d/container_decoder.h"
#include "encoder/mesh3d/base_mesh.h"
#include "encoder/mesh3d/container_encoder.h"
#include "mesh3d/affine_octree.h"
#include "mesh3d/base_mesh.h"
#include "mesh3d/cpca_wpt.h"
#include "mesh3d/lcc.h"
#include "mesh3d/quantization.h"
#include "syntax/mesh3d/affine_octree.h"
#include "syntax/mesh3d/base_mesh.h"
#include "syntax/mesh3d/bfs3d.h"
#include "syntax/mesh3d/cpca_wpt.h"
#include "syntax/mesh3d/entropy_io.h"
#include "syntax/mesh3d/lcc.h"

namespace m4mesh {

namespace {

// Inputs built with +, − and × of small rationals only, so that every
// platform builds the same doubles: the surface of a box (closed, n × n
// quads per side), a separate open sheet, and a vertex in no face, under a
// polynomial twist and wave.
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

// A flat sheet rotating in its plane by the exact rotation (3/5, 4/5) scaled down.
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

// The faces of an n × rows sheet of quads, row by row, vertex (i, j)
// numbered j (n + 1) + i, each quad cut along the same diagonal.
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

// A cloth-like flag: an n × n sheet in the plane y = 0 (its rest shape,
// frame 0), whose later frames carry a cubic wave travelling along x, and
// a vertex in no face. With `collapse`, one triangle on the coding path
// degenerates in the last frame (two of its vertices meet).
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

// A long strip of n × rows quads, flat in frame 0, then under a slow wave
// along x whose amplitude grows across the strip.
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

// An n × n sheet in the box's middle and `loose` vertices in no face
// beside it, which stay put and now and then (one time in `one_in`), each
// coordinate on its own, jump to ±2^−u · m/8 off their place (u from 2 to
// 23, m from 1 to 8) or back: residuals of many prefix lengths after a
// zero, a short and a long one. Two more vertices in no face hold the unit
// box. Dyadic values only, the same doubles everywhere.
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
    d = std::ldexp(random.uniform(1, 8) / 8.0, -random.uniform(2, 23)) * (random.next() % 2 ? 1 : -1);
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

// A residual of each class of syntax/mesh3d/residual.h (a zero, a
// residual of prefix length 0, one of length 1, at order k = 0), each
// followed by ±2^e for e from 0 to max_e: pattern(class residual, ±2^e)
// for every pair, signs alternating.
template <class Pattern>
void for_each_prefix_pattern(int max_e, Pattern pattern) {
  int32_t sign = 1;
  for (int cls = 0; cls < syntax::ResidualCoder<1>::kClasses; ++cls)
    for (int e = 0; e <= max_e; ++e) {
      pattern(sign * cls, -sign * (int32_t{1} << e));
      sign = -sign;
    }
}

// Residuals that reach every prefix bin of a channel after each class: the
// patterns of for_each_prefix_pattern(), each after a run of zeros long
// enough for the channel's order k to return to 0 (the running sum decays
// by 1/16 per symbol, to below 16).
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

// A sequence on the unit grid of 16 bits (the box 0 … 65,535 held by two
// vertices in no face, so that a grid step is 1) whose `loose` vertices in
// no face, coded directly one after the other, are offset from their place
// in frame 0 by `offset(f, v)` steps on each axis; a 2 × 2 sheet beside
// them stays put.
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

// A 2 × 2 sheet and, in no face, a chain of vertices in the middle of the
// unit grid of 16 bits (as designed_loose()), each one `schedule`'s next
// value of steps on every axis off the one before: the residuals of the
// base mesh's positions predicted by the previous vertex.
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

// Separate quads on the unit grid of 16 bits (as designed_loose()), each
// two faces (a, b, c), (c, b, d) at the same place but for d, which is
// `schedule`'s next value of steps on every axis off the parallelogram
// b + c − a: the residuals of the base mesh's parallelogram prediction.
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

// Three vertices on the unit grid of 16 bits, so few that the root cell
// codes their motion directly, in index order, with contexts fresh per
// frame. Per pattern of for_each_prefix_pattern(), a frame where the first
// vertex moves by the class's residual and the second by ±2^e on every
// axis, then a frame back; the third holds the box.
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

// Two clusters of 5 vertices on the unit grid of 19 bits, in opposite
// octants of the root cube, 2^17 apart within each, so that every
// reconstruction term is exact. Per class and prefix length e (as
// prefix_schedule()), a frame where the first cluster moves by the matrix
// whose 12 residuals from identity are the class's residual and the second
// by one whose residuals are ∓2^e, each its cell's exact fit (for k = 16,
// f = 14), then a frame back to the clusters' places.
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

// The flag's rest shape in a file (the lcc codec's --reference takes one).
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

// A codec with its options, a frame hash unit per frame (the conformance
// streams hash every frame).
Encode3dOptions codec_with(std::string codec, CodecOptionValues values) {
  Encode3dOptions o;
  o.hash_group = 1;
  o.codec = std::move(codec);
  o.codec_options = std::move(values);
  return o;
}

Encode3dOptions lcc(CodecOptionValues values) { return codec_with("lcc", std::move(values)); }

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

// Tight clusters of 6 vertices, in pairs 12, 20, 40 and 80 steps of a
// 24-bit grid apart, inside the unit box: on every odd frame one cluster
// of each pair moves rigidly and the other at random, and on even frames
// both return. Cells split down to depth 20, where the closest pair is a
// leaf of 12 vertices; rigid clusters met deeper than 15 are matrix leaves.
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

// Clusters of 6 vertices in cells of the octree: two in cells of `depth`
// whose vertices jump at random in every frame (leaves of more than 4
// vertices there, coded directly when depth is max_depth), and two pairs
// of sibling cells one level up, one cluster moving rigidly (a matrix leaf
// of more than 4 vertices above max_depth), the other at random.
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
  for (int c = 0; c < 2; ++c) cluster(depth, place(depth), place(depth), place(depth), false);
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

// Affine-Octree at ME `me` percent and k bits per matrix element.
Encode3dOptions affine(const std::string& me, int k = 16) {
  return codec_with("affine-octree", {{"me", me}, {"matrix-bits", std::to_string(k)}});
}

// A stream to decode, with a frame hash unit per frame unless a group is
// given; with `traced`, the encoder's trace of it is kept.
SuiteCase valid(std::string id, std::string purpose, std::vector<std::string> clauses, const MeshSequence& s, Encode3dOptions o,
                bool traced, uint32_t hash_group = 1) {
  std::ostringstream text;
  Trace trace(text);
  if (traced) o.trace = &trace;
  o.hash_group = hash_group;
  SuiteCase c = decode_case(std::move(id), std::move(purpose), std::move(clauses), encode_mesh3d(s, o).stream);
  c.encoder_trace = text.str();
  return c;
}

// A stream to decode whose units (some or all) are written symbol by
// symbol, for what m4mesh's encoder never writes.
SuiteCase written_case(std::string id, std::string purpose, std::vector<std::string> clauses, std::vector<uint8_t> stream) {
  SuiteCase c = decode_case(std::move(id), std::move(purpose), std::move(clauses), std::move(stream));
  c.written = true;
  return c;
}

// A stream to reject with the error a decoder must report (the frame as its plane).
SuiteCase invalid(std::string id, std::string purpose, std::vector<std::string> clauses, std::vector<uint8_t> stream, ErrorKind kind,
                  std::string element, int64_t frame) {
  return reject_case(std::move(id), std::move(purpose), std::move(clauses), std::move(stream), kind, std::move(element), frame);
}

// A stream rebuilt from its parts after `edit` changed them.
template <class Edit>
std::vector<uint8_t> edited(const std::vector<uint8_t>& stream, Edit edit) {
  ContainerParts parts = split_container(stream);
  edit(parts);
  ContainerWriter writer;
  writer.object(parts.object_payload);
  for (const ContainerUnit& unit : parts.units) writer.unit(unit.payload);
  return writer.finish();
}

// The unit of frame `frame` with unit_type `type`.
ContainerUnit& unit_of(ContainerParts& parts, UnitType type, uint32_t frame) {
  for (ContainerUnit& unit : parts.units)
    if (unit.payload[0] == static_cast<uint8_t>(type) && unit.payload[4] == frame && unit.payload[1] == 0 && unit.payload[2] == 0 &&
        unit.payload[3] == 0)
      return unit;
  throw Error(ErrorKind::kStructure, "", kNoPlane, kNoOffset, "suite: no such unit");
}

// The byte of the object payload where a header field starts, found by
// name in the description of the stream's own headers.
template <class Header>
size_t header_byte(const std::vector<uint8_t>& stream, const char* name) {
  const ContainerParts parts = split_container(stream);
  auto [object, header] = read_headers<Header>(parts);
  syntax::CountIO count(name);
  syntax::describe(count, object);
  syntax::describe(count, header);
  return static_cast<size_t>(count.offset_of_watched() / 8);
}

// A bfs3d frame unit's payload with a zero byte after its section k (0 bins
// x, 1 raw x, …, 5 raw z), whose length field grows by one.
std::vector<uint8_t> with_extra_byte(std::vector<uint8_t> payload, int k) {
  const size_t data = (syntax::unit_data_offset() - 32) / 8;
  const size_t field = data + 4 * static_cast<size_t>(k);
  size_t end = data + 24;
  for (int i = 0; i <= k; ++i) {
    const size_t at = data + 4 * static_cast<size_t>(i);
    end += uint32_t{payload[at]} << 24 | uint32_t{payload[at + 1]} << 16 | uint32_t{payload[at + 2]} << 8 | payload[at + 3];
  }
  payload.insert(payload.begin() + static_cast<std::ptrdiff_t>(end), 0x00);
  for (size_t i = field + 3;; --i)
    if (++payload[i] != 0 || i == field) break;  // + 1, big-endian
  return payload;
}

const std::vector<uint8_t>& find(const std::vector<SuiteCase>& cases, const std::string& id) {
  for (const SuiteCase& c : cases)
    if (c.id == id) return c.stream;
  throw Error(ErrorKind::kStructure, "", kNoPlane, kNoOffset, "suite: no case " + id);
}

// A unit: its header (the first bytes of the unit it replaces), then its
// data described.
template <class Data>
std::vector<uint8_t> unit_with(std::vector<uint8_t> unit_header, Data data) {
  BitWriter writer;
  syntax::WriteIO out(writer);
  syntax::describe(out, data);
  unit_header.insert(unit_header.end(), writer.bytes().begin(), writer.bytes().end());
  return unit_header;
}

// An Affine-Octree frame unit with its header and the one cell `cell` of
// `count` vertices, the root, written through `coder` (direct_shift 0).
std::vector<uint8_t> ao_root_unit(const AffineOctreeHeader& coder, uint32_t count, AffineCell cell, std::vector<uint8_t> unit_header) {
  AffineCellCoder cells(coder);
  syntax::EntropyWriteIO<false> symbols(syntax::SectionPlace{});
  cells.describe(symbols, 0, count, cell);
  const std::vector<uint8_t> bins = symbols.finish_bins(), raw = symbols.finish_raw();
  AffineFrame data{0, static_cast<uint32_t>(bins.size()), bins, raw};
  return unit_with(std::move(unit_header), data);
}

// An Affine-Octree frame unit of `stream` whose only cell, the root, is a
// leaf with the identity matrix but element 0 one above what matrix_bits
// allows (written with twice the range at the same fraction bits).
std::vector<uint8_t> ao_matrix_beyond_unit(const std::vector<uint8_t>& stream, std::vector<uint8_t> unit_header) {
  const auto [object, header] = read_headers<AffineOctreeHeader>(split_container(stream));
  AffineOctreeHeader wider = header;
  ++wider.matrix_bits;
  ++wider.matrix_range_log2;
  AffineCell cell;
  for (int i = 0; i < 3; ++i) cell.matrix[static_cast<size_t>(5 * i)] = int32_t{1} << header.fraction_bits();
  cell.matrix[0] = header.matrix_max() + 1;
  return ao_root_unit(wider, object.vertex_count, cell, std::move(unit_header));
}

// An Affine-Octree frame unit of `stream` whose root, of more than 4
// vertices, is a leaf coded directly (m4mesh's encoder splits it instead):
// vertex v moves by v mod 3 − 1 steps on each axis.
std::vector<uint8_t> ao_direct_root_unit(const std::vector<uint8_t>& stream, std::vector<uint8_t> unit_header) {
  const auto [object, header] = read_headers<AffineOctreeHeader>(split_container(stream));
  AffineCell cell;
  cell.direct = true;
  for (uint32_t v = 0; v < object.vertex_count; ++v) {
    const int32_t d = static_cast<int32_t>(v % 3) - 1;
    cell.motion.push_back({d, d, d});
  }
  return ao_root_unit(header, object.vertex_count, cell, std::move(unit_header));
}

// Affine-Octree streams: the paper's settings and the extremes of each header field.
std::vector<SuiteCase> affine_octree_cases(bool traced) {
  const MeshSequence shape = box_and_sheet(6, 4);
  std::vector<SuiteCase> suite;
  suite.push_back(valid("ao-01-me1-k16", "affine-octree at the paper's settings: ME 1 %, k = 16", {"container", "ao-header", "ao-frame", "ao-cell"},
                        shape, affine("1"), traced));
  {
    Encode3dOptions o = affine("25", 8);
    o.codec_options["max-depth"] = "3";
    suite.push_back(valid("ao-02-coarse", "ME 25 %, k = 8, octree depth at most 3", {"ao-header", "ao-cell"}, shape, o, traced));
  }
  {
    Encode3dOptions o = affine("0.1", 16);
    o.codec_options["bits"] = "16";
    o.codec_options["max-depth"] = "20";
    suite.push_back(valid("ao-03-fine", "ME 0.1 %, 16-bit grid, octree depth up to 20", {"ao-cell", "ao-reconstruction"}, shape, o, traced));
  }
  {
    Encode3dOptions o = affine("2", 24);
    o.codec_options["matrix-range-log2"] = "8";
    suite.push_back(valid("ao-04-wide-matrices", "k = 24 over [−128, 128): the widest matrix elements", {"ao-header", "ao-reconstruction"},
                          shape, o, traced));
  }
  {
    Encode3dOptions o = affine("1");
    o.codec_options["intra-period"] = "3";
    suite.push_back(valid("ao-05-intra", "an intra base mesh every 3 frames", {"container-units", "ao-frame"}, box_and_sheet(7, 3), o, traced));
  }
  suite.push_back(valid("ao-06-direct-root", "4 vertices: the root cell codes direct motion", {"ao-cell"}, moving_tetrahedron(5), affine("1"), traced));
  suite.push_back(valid("ao-07-coplanar", "a flat sheet rotating: singular cells, one matrix per frame", {"ao-cell", "ao-reconstruction"},
                        rotating_sheet(5), affine("1"), traced));
  {
    Encode3dOptions o = affine("0.1");
    o.codec_options["bits"] = "24";
    o.codec_options["max-depth"] = "20";
    suite.push_back(valid("ao-08-deep", "cells down to depth 20 (depth contexts 15 with both bins), a leaf of 12 vertices at the deepest depth",
                          {"ao-cell", "ao-reconstruction"}, deep_clusters(5), o, traced));
  }
  {
    Encode3dOptions o = affine("0.1", 24);
    o.codec_options["bits"] = "24";
    o.codec_options["max-depth"] = "20";
    suite.push_back(valid("ao-09-spikes", "vertices that jump by 2^−2 … 2^−23 of the box on a 24-bit grid: matrix and direct residuals of many "
                          "prefix lengths, leaves at every depth", {"ao-cell"}, spiky_sheet(8, 16, 100, 42, 30), o, traced));
  }
  for (int depth = 2; depth <= 15; ++depth) {
    Encode3dOptions o = affine("0.001", 24);
    o.codec_options["bits"] = "24";
    o.codec_options["max-depth"] = std::to_string(depth);
    char id[32];
    std::snprintf(id, sizeof id, "ao-11-depth-%02d", depth);
    suite.push_back(valid(id, "max_depth " + std::to_string(depth) + ": leaves of more than 4 vertices coded directly there, and matrix "
                          "leaves of more than 4 one level up", {"ao-cell"},
                          clustered_jumps(3, depth), o, traced));
  }
  {
    Encode3dOptions o = affine("0.1", 8);
    o.codec_options["bits"] = "4";
    o.codec_options["max-depth"] = "1";
    suite.push_back(valid("ao-10-shallow", "max_depth 1 on a 4-bit grid: leaves of many vertices at depth 1, matrix or direct", {"ao-header", "ao-cell"},
                          spiky_sheet(4, 4, 8, 48, 3), o, traced));
  }
  {
    Encode3dOptions o = affine("0.001");
    o.codec_options["bits"] = "16";
    suite.push_back(valid("ao-12-direct-prefixes", "three vertices whose direct motion takes every prefix length 0 … 13 after each class",
                          {"ao-cell"}, direct_triples(), o, traced));
  }
  {
    Encode3dOptions o = affine("0.001");
    o.codec_options["bits"] = "19";
    suite.push_back(valid("ao-13-matrix-prefixes", "two clusters whose matrices' residuals take every prefix length 0 … 13 after each class",
                          {"ao-cell"}, matrix_pairs(), o, traced));
  }
  {
    // ao-01's first two frames, with frame 1 a root leaf coded directly (no hash units: the frame is written, not encoded).
    Encode3dOptions o = affine("1");
    o.hashes = false;
    const std::vector<uint8_t> base = encode_mesh3d(box_and_sheet(2, 4), o).stream;
    suite.push_back(written_case("ao-14-direct-root", "a root of more than 4 vertices coded directly", {"ao-cell"},
                                edited(base, [&](ContainerParts& p) {
                                  ContainerUnit& unit = unit_of(p, UnitType::kFrame, 1);
                                  unit.payload = ao_direct_root_unit(base, {unit.payload.begin(), unit.payload.begin() + 5});
                                })));
  }
  return suite;
}

// bfs3d streams: both predictions, intra frames.
std::vector<SuiteCase> bfs3d_cases(bool traced) {
  const MeshSequence shape = box_and_sheet(6, 4);
  std::vector<SuiteCase> suite;
  suite.push_back(valid("bfs3d-01-average", "bfs3d with base-edge average prediction", {"container", "bfs3d"}, shape, Encode3dOptions{}, traced));
  {
    Encode3dOptions o;
    o.codec_options = {{"parallelogram", "1"}, {"bits", "10"}, {"intra-period", "4"}};
    suite.push_back(valid("bfs3d-02-parallelogram-intra", "bfs3d, parallelogram prediction, 10 bits, intra every 4 frames",
                          {"bfs3d", "container-units"}, shape, o, traced));
  }
  {
    // bfs3d-01 with frame_count 0 (streaming); its trace is the encoder's with that field's value edited.
    const SuiteCase& counted = suite.front();
    SuiteCase streaming = decode_case("bfs3d-03-streaming", "bfs3d-01 with frame_count 0: a stream of unknown length", {"container", "container-units"},
                                      edited(counted.stream, [](ContainerParts& p) { std::fill_n(p.object_payload.begin() + 10, 4, 0); }));
    std::istringstream lines(counted.encoder_trace);
    for (std::string line; std::getline(lines, line);) {
      if (line.starts_with("object") && line.find(" frame_count ") != std::string::npos) line = line.substr(0, line.find_last_not_of("0123456789") + 1) + "0";
      streaming.encoder_trace += line + "\n";
    }
    suite.push_back(std::move(streaming));
  }
  {
    Encode3dOptions o;
    o.codec_options = {{"bits", "24"}};
    suite.push_back(valid("bfs3d-04-spikes", "vertices that jump by 2^−2 … 2^−23 of the box on a 24-bit grid: motion residuals of every prefix "
                          "length after each class", {"bfs3d"}, spiky_sheet(16, 16, 0, 41, 60), o, traced));
  }
  {
    Encode3dOptions o;
    o.codec_options = {{"bits", "4"}};
    suite.push_back(valid("bfs3d-05-four-bits", "the coarsest grid, 4 bits", {"bfs3d"}, spiky_sheet(4, 4, 8, 49, 3), o, traced));
  }
  {
    // Vertices in no face, predicted from no motion: each frame's motion
    // of the loose vertices follows prefix_schedule().
    const std::vector<int32_t> schedule = prefix_schedule();
    constexpr int kLoose = 429;  // 10 frames of the schedule
    const int frames = static_cast<int>(schedule.size() + kLoose - 1) / kLoose + 1;
    auto offset = [&](int f, int v) {
      int32_t sum = 0;
      for (size_t i = static_cast<size_t>(v); i < std::min(schedule.size(), static_cast<size_t>(f * kLoose)); i += kLoose) sum += schedule[i];
      return sum;
    };
    Encode3dOptions o;
    o.codec_options = {{"bits", "16"}};
    suite.push_back(valid("bfs3d-06-motion-prefixes", "vertices in no face whose motion takes every prefix length 0 … 13 after each class",
                          {"bfs3d"}, designed_loose(frames, kLoose, offset), o, traced));
  }
  return suite;
}

// An lcc frame unit (stream mode) with its header and the symbols of
// `residuals`, an anchor's or a predicted frame's, written with the
// residual limit `rh_limit` (the header's, or more to write a value
// beyond it).
std::vector<uint8_t> lcc_unit(const LccHeader& header, bool predicted, LccIndices residuals, int32_t rh_limit,
                              std::vector<uint8_t> unit_header) {
  syntax::ResidualCoder<syntax::kLccChannels> coder;
  syntax::EntropyWriteIO<false> symbols(syntax::SectionPlace{});
  syntax::describe_symbols(symbols, coder, predicted, residuals.direct, residuals.steps, int32_t{1} << header.theta_bits, rh_limit);
  const std::vector<uint8_t> bins = symbols.finish_bins(), raw = symbols.finish_raw();
  LccFrameData data{static_cast<uint32_t>(bins.size()), bins, raw};
  return unit_with(std::move(unit_header), data);
}

// An lcc frame unit of `stream` (stream mode), an anchor or a frame
// predicted between two, whose residuals are 0 but every rho's, `times`
// 2^rh_bits + `extra` (written even beyond what the syntax allows).
std::vector<uint8_t> lcc_rho_unit(const std::vector<uint8_t>& stream, std::vector<uint8_t> unit_header, bool predicted, int32_t times,
                                  int32_t extra) {
  const auto [object, header] = read_headers<LccHeader>(split_container(stream));
  const LccOrder order = lcc_order(decode_mesh3d(stream).faces, object.vertex_count);
  LccIndices residuals{std::vector<int32_t>(3 * order.direct.size()), std::vector<int32_t>(3 * order.steps.size())};
  const int32_t rho = times * (int32_t{1} << header.rh_bits) + extra;
  for (size_t i = 1; i < residuals.steps.size(); i += 3) residuals.steps[i] = rho;
  // The writer's limit, raised to let rho through (a predicted frame's residuals may reach twice the limit).
  const int32_t limit = std::max(int32_t{1} << header.rh_bits, predicted ? (rho + 1) / 2 : rho);
  return lcc_unit(header, predicted, std::move(residuals), limit, std::move(unit_header));
}

// An lcc stream (stream mode, temporal prediction with gop 2, b_θ 15,
// b_rh 20, no hash units) of a strip of two quads, written symbol by
// symbol: per pattern p of for_each_prefix_pattern(), the anchor at frame
// 2p + 1 and the frame predicted at 2p + 2 take the pattern's values as
// the residuals of their first two steps' θ, ρ and ζ.
std::vector<uint8_t> lcc_written_stream() {
  std::vector<std::pair<int32_t, int32_t>> patterns;
  for_each_prefix_pattern(13, [&](int32_t first, int32_t second) { patterns.emplace_back(first, second); });
  MeshSequence strip;
  strip.faces = sheet_faces(2, 1);
  strip.vertex_count = 6;
  for (size_t f = 0; f < 2 * patterns.size() + 2; ++f)
    strip.frames.push_back({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 0, 1}, {1, 0.25, 1}, {2, 0, 1}});
  Encode3dOptions o = lcc({{"theta-bits", "15"}, {"rh-bits", "20"}, {"temporal", "1"}, {"gop", "2"}});
  o.hashes = false;
  const std::vector<uint8_t> encoded = encode_mesh3d(strip, o).stream;
  const LccHeader header = read_headers<LccHeader>(split_container(encoded)).second;
  const LccOrder order = lcc_order(strip.faces, strip.vertex_count);
  return edited(encoded, [&](ContainerParts& p) {
    for (ContainerUnit& unit : p.units) {
      if (unit.payload[0] != static_cast<uint8_t>(UnitType::kFrame)) continue;
      const uint32_t frame = unit.payload[4];
      const bool predicted = frame % 2 == 0 && frame + 1 < strip.frames.size();
      const size_t pattern = predicted ? frame / 2 - 1 : (frame - 1) / 2;
      LccIndices residuals{std::vector<int32_t>(3 * order.direct.size()), std::vector<int32_t>(3 * order.steps.size())};
      if (pattern < patterns.size())
        for (size_t i = 0; i < 3; ++i) {
          residuals.steps[i] = patterns[pattern].first;
          residuals.steps[3 + i] = patterns[pattern].second;
        }
      unit.payload = lcc_unit(header, predicted, std::move(residuals), int32_t{1} << header.rh_bits, {unit.payload.begin(), unit.payload.begin() + 5});
    }
  });
}

// An lcc stream (b_θ 12, b_rh 20, σ 2^14, a 24-bit grid of unit steps, no
// hash units) whose frame 1 is written symbol by symbol: per angle entry
// from 7/8 to 9/8 of the first octant (where a sine or cosine series cut
// short errs first), a quad whose directly coded triangle, axis-aligned,
// moves so that the vertex placed from it at that angle lands within
// 2^−29 of its distance from the triangle of the planes x = 0 and z = 0:
// its binary32 x and z then follow the last bit of the entry's cosine and
// sine.
std::vector<uint8_t> lcc_rounding_edges_stream() {
  constexpr int kThetaBits = 12, kRhBits = 20;
  constexpr uint32_t kFirstEntry = 896, kLastEntry = 1152;  // the first octant ends at entry 1024
  constexpr double kMiddle = 1 << 23, kEdge = 1 << 10;
  MeshSequence quads;
  std::vector<Vec3> frame;
  for (uint32_t m = kFirstEntry; m <= kLastEntry; ++m) {
    const NodeIndex a = static_cast<NodeIndex>(frame.size());
    quads.faces.push_back({{a, a + 1, a + 2}});
    quads.faces.push_back({{a + 2, a + 1, a + 3}});
    frame.push_back({kMiddle - kEdge, kMiddle, kMiddle});
    frame.push_back({kMiddle, kMiddle, kMiddle});
    frame.push_back({kMiddle, kMiddle + kEdge, kMiddle});
    frame.push_back({kMiddle + kEdge, kMiddle + kEdge / 2, kMiddle});  // in the plane, across the edge: height 0
  }
  frame.push_back({0, 0, 0});  // the box of a grid step 1
  frame.push_back({(1 << 24) - 1, (1 << 24) - 1, (1 << 24) - 1});
  quads.vertex_count = static_cast<uint32_t>(frame.size());
  quads.frames = {frame, frame};
  Encode3dOptions o = lcc({{"theta-bits", std::to_string(kThetaBits)}, {"rh-bits", std::to_string(kRhBits)}, {"bits", "24"}});
  o.hashes = false;
  std::vector<uint8_t> stream = encode_mesh3d(quads, o).stream;
  const size_t rh_range_at = header_byte<LccHeader>(stream, "rh_range");
  stream = edited(stream, [&](ContainerParts& p) {
    const uint32_t sigma = bit_cast<uint32_t>(16384.0f);  // radii up to 2^14 edge lengths
    for (size_t i = 0; i < 4; ++i) p.object_payload[rh_range_at + i] = static_cast<uint8_t>(sigma >> (24 - 8 * i));
  });
  const LccHeader header = read_headers<LccHeader>(split_container(stream)).second;
  const std::vector<Triangle> faces = decode_mesh3d(stream).faces;
  const LccModel model(faces, frame, kThetaBits, kRhBits, header.rh_range_value());
  const LccOrder& order = model.order();
  LccIndices residuals{std::vector<int32_t>(3 * order.direct.size()), std::vector<int32_t>(3 * order.steps.size())};
  std::vector<size_t> direct_slot(frame.size());
  for (size_t i = 0; i < order.direct.size(); ++i) direct_slot[order.direct[i]] = i;
  for (size_t k = 0; k < order.steps.size(); ++k) {
    const LccStep& step = order.steps[k];
    const int32_t theta = static_cast<int32_t>(kFirstEntry + step.d / 4) - (int32_t{1} << kThetaBits);
    std::vector<Vec3> moved = frame;
    for (int32_t rho = int32_t{1} << kRhBits;; --rho) {
      const Vec3 far = model.place(k, frame, theta, rho, 0);
      const Vec3 shift{-std::nearbyint(far.x), 0, -std::nearbyint(far.z)};
      for (NodeIndex v : {step.a, step.b, step.c}) moved[v] = {frame[v].x + shift.x, frame[v].y, frame[v].z + shift.z};
      const Vec3 near = model.place(k, moved, theta, rho, 0);
      const double origin_x = frame[step.b].x, origin_z = frame[step.b].z;  // the edge's middle, before the move
      if (std::fabs(near.x) > std::ldexp(std::fabs(far.x - origin_x), -29) || std::fabs(near.z) > std::ldexp(std::fabs(far.z - origin_z), -29))
        continue;
      for (NodeIndex v : {step.a, step.b, step.c}) {
        residuals.direct[3 * direct_slot[v]] = static_cast<int32_t>(shift.x);
        residuals.direct[3 * direct_slot[v] + 2] = static_cast<int32_t>(shift.z);
      }
      residuals.steps[3 * k] = theta;
      residuals.steps[3 * k + 1] = rho;
      break;
    }
  }
  return edited(stream, [&](ContainerParts& p) {
    ContainerUnit& unit = unit_of(p, UnitType::kFrame, 1);
    unit.payload = lcc_unit(header, false, std::move(residuals), int32_t{1} << kRhBits, {unit.payload.begin(), unit.payload.begin() + 5});
  });
}

// The cloth codec's streams: both modes, a rest-shape reference, the
// smallest and largest bit counts, a degenerate triangle on the path,
// temporal prediction in both modes.
std::vector<SuiteCase> lcc_cases(bool traced) {
  const MeshSequence flag = waving_flag(6, 8, false);
  MeshSequence moving = flag;
  moving.frames.erase(moving.frames.begin());  // frame 0 waves already: coded against itself as the reference
  const std::string rest = rest_shape_file(flag);
  std::vector<SuiteCase> suite;
  suite.push_back(valid("lcc-01-stream", "lcc, stream mode, b_θ 6, b_rh from Eq. 1", {"container", "lcc"}, moving, lcc({}), traced));
  suite.push_back(valid("lcc-02-download", "lcc, download mode: contexts and direct vertices carried across frames", {"lcc"}, moving,
                        lcc({{"mode", "download"}}), traced));
  suite.push_back(valid("lcc-03-rest-shape", "lcc against a rest shape that is not a frame: frame 0 coded too", {"lcc"}, flag,
                        lcc({{"reference", rest}, {"theta-bits", "5"}}), traced));
  suite.push_back(valid("lcc-04-fewest-bits", "b_θ 2, b_rh 1", {"lcc"}, moving, lcc({{"theta-bits", "2"}, {"rh-bits", "1"}, {"bits", "4"}}), traced));
  suite.push_back(valid("lcc-05-most-bits", "b_θ 15, b_rh 20, a 16-bit grid", {"lcc"}, moving,
                        lcc({{"theta-bits", "15"}, {"rh-bits", "20"}, {"bits", "16"}}), traced));
  suite.push_back(valid("lcc-06-degenerate", "a triangle on the coding path with a zero edge", {"lcc"}, waving_flag(4, 6, true), lcc({}), traced));
  MeshSequence longer = waving_flag(13, 8, false);
  suite.push_back(valid("lcc-07-temporal-stream", "lcc, stream mode, temporal prediction: anchors every 4 frames and the last, midpoints between",
                        {"lcc", "lcc-temporal"}, MeshSequence{longer.vertex_count, longer.faces, {longer.frames.begin() + 1, longer.frames.end()}},
                        lcc({{"temporal", "1"}, {"gop", "4"}}), traced));
  suite.push_back(valid("lcc-08-temporal-download", "lcc, download mode, temporal prediction every 8 frames against a rest shape",
                        {"lcc", "lcc-temporal"}, longer, lcc({{"temporal", "1"}, {"gop", "8"}, {"mode", "download"}, {"reference", rest}}),
                        traced));
  // A 1-ulp difference in an angle or a frame axis moves a decoded binary64
  // position by far less than a binary32 step: it shows in the output only
  // after a long chain of steps, and then in a few coordinates.
  suite.push_back(valid("lcc-11-spikes", "vertices that jump by 2^−2 … 2^−23 of the box on a 24-bit grid, b_θ 15, b_rh 20", {"lcc"},
                        spiky_sheet(8, 16, 100, 44, 40), lcc({{"theta-bits", "15"}, {"rh-bits", "20"}, {"bits", "24"}}), traced));
  suite.push_back(valid("lcc-12-spikes-temporal", "lcc-11's jumps under temporal prediction, an anchor every 4 frames", {"lcc", "lcc-temporal"},
                        spiky_sheet(9, 16, 100, 45, 40), lcc({{"theta-bits", "15"}, {"rh-bits", "20"}, {"bits", "24"}, {"temporal", "1"}, {"gop", "4"}}),
                        traced));
  {
    // The first face, coded directly, on a line parallel to z in the last
    // frame: the steps from it take the tie rule's axis x.
    MeshSequence line = waving_flag(4, 6, false);
    std::vector<Vec3>& last = line.frames.back();
    for (int k = 0; k < 3; ++k) last[line.faces[0].v[static_cast<size_t>(k)]] = {0.5, 0.25, 0.25 * k};
    suite.push_back(valid("lcc-13-vertical-line", "a triangle on a line parallel to z: the degenerate frame's axis by the tie rule", {"lcc"}, line,
                          lcc({}), traced));
  }
  {
    // Directly coded vertices whose residuals follow prefix_schedule(), in
    // stream mode (contexts reset per frame, residuals against the
    // reference), then under temporal prediction: anchors at odd frames
    // (frame 0 is the reference), midpoints at even frames whose residual
    // is their offset less the mean of their anchors'.
    const std::vector<int32_t> schedule = prefix_schedule();
    constexpr int kLoose = 429;  // 10 frames of the schedule
    const int per_frame = static_cast<int>(schedule.size() + kLoose - 1) / kLoose;
    auto at = [&](int j, int v) { return static_cast<size_t>(j * kLoose + v) < schedule.size() ? schedule[static_cast<size_t>(j * kLoose + v)] : 0; };
    suite.push_back(valid("lcc-14-direct-prefixes", "vertices in no face whose grid residuals take every prefix length 0 … 13 after each class",
                          {"lcc"}, designed_loose(per_frame + 1, kLoose, [&](int f, int v) { return at(f - 1, v); }), lcc({{"bits", "16"}}),
                          traced));
    auto anchor = [&](int f, int v) { return at((f - 1) / 2, v); };
    auto temporal = [&](int f, int v) {
      return f % 2 ? anchor(f, v) : static_cast<int32_t>((int64_t{anchor(f - 1, v)} + anchor(f + 1, v)) >> 1) + at(f / 2 - 1, v);
    };
    suite.push_back(valid("lcc-15-direct-prefixes-temporal", "lcc-14's residuals at anchors and again at the midpoints between them, gop 2",
                          {"lcc", "lcc-temporal"}, designed_loose(2 * per_frame + 2, kLoose, temporal),
                          lcc({{"bits", "16"}, {"temporal", "1"}, {"gop", "2"}}), traced));
  }
  suite.push_back(written_case("lcc-16-written", "a stream written symbol by symbol: θ, ρ and ζ residuals of every prefix length 0 … 13 "
                              "after each class, at anchors and at frames predicted between them", {"lcc", "lcc-temporal"}, lcc_written_stream()));
  suite.push_back(written_case("lcc-17-rounding-edges", "vertices whose binary32 x and z follow the last bit of the cosine and sine of "
                               "the angle entries around the first octant's end (written symbol by symbol)", {"lcc"},
                               lcc_rounding_edges_stream()));
  suite.push_back(valid("lcc-09-long-chains", "a 200 × 3 strip at b_θ 12: chains of 600 steps, where a 1-ulp angle or axis changes the output",
                        {"lcc"}, waving_strip(6, 200, 3), lcc({{"theta-bits", "12"}}), traced));
  suite.push_back(valid("lcc-10-long-chains-coarse", "a 400 × 3 strip at b_θ 2: every angle a multiple of π/4, the table's octant ends",
                        {"lcc"}, waving_strip(6, 400, 3), lcc({{"theta-bits", "2"}}), traced));
  std::filesystem::remove(rest);
  return suite;
}

// Writes bins as EntropyWriteIO does, but every prefix bin as 1, so that a
// residual's prefix never ends; stops where a decoder must fail.
class EndlessPrefixIO {
 public:
  static constexpr bool kReading = false;
  struct Stop {};
  explicit EndlessPrefixIO(syntax::EntropyWriteIO<false>& io) : io_(io) {}
  void bin(const char* name, BinContext& state, int context, bool& value) {
    if (std::string_view(name).ends_with("_prefix")) value = true;
    io_.bin(name, state, context, value);
  }
  void raw(const char* name, int bits, uint32_t& value) { io_.raw(name, bits, value); }
  [[noreturn]] void fail(ErrorKind, const char*, const std::string&) const { throw Stop{}; }

 private:
  syntax::EntropyWriteIO<false>& io_;
};

// Writes as EntropyWriteIO does and stops at the first rule the symbols
// break, where a decoder must fail.
class StopAtFailureIO {
 public:
  static constexpr bool kReading = false;
  struct Stop {};
  explicit StopAtFailureIO(syntax::EntropyWriteIO<false>& io) : io_(io) {}
  void bin(const char* name, BinContext& state, int context, bool& value) { io_.bin(name, state, context, value); }
  void raw(const char* name, int bits, uint32_t& value) { io_.raw(name, bits, value); }
  [[noreturn]] void fail(ErrorKind, const char*, const std::string&) const { throw Stop{}; }

 private:
  syntax::EntropyWriteIO<false>& io_;
};

// Answers the traversal's questions for a base mesh that breaks a rule: a
// first seed of new vertices but for `old_corner` (vertex 0, when it is
// not −1), then every gate answered `answer`: by default the far vertex 3
// (the first seed's vertices are 0, 1 and 2, so 3 is not numbered yet).
struct BrokenBaseMesh {
  int old_corner = -1;
  GateAnswer answer{GateSymbol::kFarVertex, 0, 3};
  bool seed_corner(int corner, uint32_t& vertex) {
    vertex = 0;
    return corner == old_corner;
  }
  void numbered(uint32_t) {}
  GateAnswer gate(HalfEdge, std::span<const uint32_t>) { return answer; }
};

// A base mesh unit for frame 0 from its unit header and its symbols.
std::vector<uint8_t> base_mesh_unit(std::vector<uint8_t> unit_header, syntax::EntropyWriteIO<false>& symbols, uint32_t vertex_order) {
  const std::vector<uint8_t> bins = symbols.finish_bins(), raw = symbols.finish_raw();
  BaseMeshData data;
  data.vertex_order = vertex_order;
  data.arithmetic_bytes = static_cast<uint32_t>(bins.size());
  data.bins = bins;
  data.raw = raw;
  return unit_with(std::move(unit_header), data);
}

// A base mesh unit for frame 0 of an object of `vertex_count` vertices and
// `face_count` faces whose traversal the oracle breaks; or, when the
// traversal completes, with no loose face and the vertex order (order 1)
// given by `order_differences`, which breaks it.
std::vector<uint8_t> broken_base_mesh_unit(std::vector<uint8_t> unit_header, uint32_t vertex_count, uint32_t face_count, BrokenBaseMesh oracle,
                                           std::vector<int32_t> order_differences = {}) {
  syntax::EntropyWriteIO<false> symbols(syntax::SectionPlace{});
  StopAtFailureIO io(symbols);
  syntax::BaseMeshContexts contexts;
  GateTraversal traversal(face_count);
  try {
    describe_traversal(io, contexts, traversal, vertex_count, face_count, &oracle);
    describe_loose_faces(io, vertex_count, std::span<Triangle>());
    for (int32_t& d : order_differences) contexts.order.describe(io, 0, d, syntax::kOrderNames);
  } catch (const StopAtFailureIO::Stop&) {
  }
  return base_mesh_unit(std::move(unit_header), symbols, order_differences.empty() ? kVertexOrderCoding : kVertexOrderFromGate);
}

// A one-frame bfs3d stream (no hash unit) of `vertex_count` vertices and
// `face_count` faces whose base mesh is written symbol by symbol: the
// traversal the oracle answers, no loose face, the vertex order given by
// `order_differences` (coding order without), every position at the
// grid's origin.
template <class Oracle>
std::vector<uint8_t> written_base_mesh_stream(uint32_t vertex_count, uint32_t face_count, Oracle& oracle,
                                              std::vector<int32_t> order_differences = {}) {
  MeshSequence points;  // any object of this vertex count: its base mesh unit and face count are replaced
  points.vertex_count = vertex_count;
  points.faces = {{{0, 1, 2}}};
  points.frames.emplace_back(vertex_count, Vec3{0, 0, 0});
  points.frames[0][0] = {1, 1, 1};
  Encode3dOptions o;
  o.hashes = false;
  const std::vector<uint8_t> encoded = encode_mesh3d(points, o).stream;
  syntax::EntropyWriteIO<false> symbols(syntax::SectionPlace{});
  syntax::BaseMeshContexts contexts;
  GateTraversal traversal(face_count);
  describe_traversal(symbols, contexts, traversal, vertex_count, face_count, &oracle);
  describe_loose_faces(symbols, vertex_count, std::span<Triangle>());
  for (int32_t& d : order_differences) contexts.order.describe(symbols, 0, d, syntax::kOrderNames);
  std::vector<IntPoint3> positions(vertex_count);
  describe_positions(symbols, contexts, traversal.faces(), positions);
  const size_t faces_at = header_byte<Bfs3dHeader>(encoded, "face_count");
  return edited(encoded, [&](ContainerParts& p) {
    for (size_t i = 0; i < 4; ++i) p.object_payload[faces_at + i] = static_cast<uint8_t>(face_count >> (24 - 8 * i));
    ContainerUnit& unit = unit_of(p, UnitType::kBaseMesh, 0);
    unit.payload = base_mesh_unit({unit.payload.begin(), unit.payload.begin() + 5}, symbols,
                                  order_differences.empty() ? kVertexOrderCoding : kVertexOrderFromGate);
  });
}

// Answers for a strip of new vertices, then one far vertex: vertex 0 from
// the first gate leaving vertex `from` or a later one, so that the unit's
// first far residual is 0 − from; then the traversal ends (the face count
// is reached).
struct FirstFarOracle {
  uint32_t from = 0;
  uint32_t visited = 0;
  bool seed_corner(int, uint32_t&) { return false; }
  void numbered(uint32_t v) { visited = v + 1; }
  GateAnswer gate(HalfEdge gate, std::span<const uint32_t>) {
    if (gate.from >= from) return {GateSymbol::kFarVertex, 0, 0};
    return {visited <= gate.to + 1 ? GateSymbol::kNewVertex : GateSymbol::kBorder, 0, 0};
  }
};

// The base of the oracles below: the vertices numbered and the faces
// answered so far, to keep the answers valid. Seeds take new vertices.
class FaceTracker {
 public:
  // A seed's corner is asked for; numbered() hears the vertex.
  bool seed_corner(int corner, uint32_t&) {
    corner_ = corner;
    return false;
  }
  // A vertex just numbered: a gate's new vertex or a seed's corner, the seed face complete at its third.
  void numbered(uint32_t v) {
    visited_ = v + 1;
    if (corner_ < 0) return;
    seed_.v[static_cast<size_t>(corner_)] = v;
    if (corner_ == 2) {
      add(seed_);
      corner_ = -1;
    }
  }
  // Whether the face (gate.to, gate.from, c) repeats no vertex and no directed edge.
  bool can_attach(HalfEdge gate, uint32_t c) const {
    return c != gate.from && c != gate.to && !edges_.count({gate.to, gate.from}) && !edges_.count({gate.from, c}) && !edges_.count({c, gate.to});
  }
  void add(const Triangle& face) {
    ++faces_;
    for (int i = 0; i < 3; ++i) edges_.insert({face.v[static_cast<size_t>(i)], face.v[static_cast<size_t>((i + 1) % 3)]});
  }
  // The face behind the gate for an answer.
  void add(HalfEdge gate, const GateAnswer& answer, std::span<const uint32_t> candidates, uint32_t new_vertex) {
    if (answer.symbol == GateSymbol::kBorder) return;
    const uint32_t c = answer.symbol == GateSymbol::kNewVertex ? new_vertex
                       : answer.symbol == GateSymbol::kCandidate ? candidates[answer.candidate]
                                                                 : answer.far_vertex;
    add({{gate.to, gate.from, c}});
  }
  uint32_t faces() const { return faces_; }
  uint32_t vertices() const { return visited_; }

 protected:
  uint32_t visited_ = 0;

 private:
  std::set<std::pair<uint32_t, uint32_t>> edges_;
  uint32_t faces_ = 0;
  int corner_ = -1;
  Triangle seed_{};
};

// Answers for components of a base mesh, each from its own random seed:
// seed faces of new vertices, then at each gate a border, a new vertex, a
// candidate or a far vertex of the component (each with the component's
// own odds, among the answers that make a valid face) until the component
// has `kFaces` faces, then borders. Past the last seed, std::out_of_range.
class ComponentOracle : public FaceTracker {
 public:
  static constexpr uint32_t kFaces = 40;

  explicit ComponentOracle(std::vector<uint64_t> seeds) : seeds_(std::move(seeds)), random_(0) {}

  bool seed_corner(int corner, uint32_t& vertex) {
    if (corner == 0) {
      random_ = SplitMix64(seeds_.at(component_++));
      for (uint32_t& odds : odds_) odds = static_cast<uint32_t>(1 + random_.next() % 8);
      first_ = visited_;
      first_face_ = faces();
    }
    return FaceTracker::seed_corner(corner, vertex);
  }

  GateAnswer gate(HalfEdge gate, std::span<const uint32_t> candidates) {
    std::vector<GateAnswer> answers[4];  // border, new vertex, candidate, far vertex
    answers[0].push_back({GateSymbol::kBorder, 0, 0});
    if (faces() - first_face_ < kFaces) {
      if (can_attach(gate, visited_)) answers[1].push_back({GateSymbol::kNewVertex, 0, 0});
      for (uint32_t i = 0; i < candidates.size(); ++i)
        if (can_attach(gate, candidates[i])) answers[2].push_back({GateSymbol::kCandidate, i, 0});
      const uint32_t far = first_ + static_cast<uint32_t>(random_.next() % (visited_ - first_));
      if (can_attach(gate, far)) answers[3].push_back({GateSymbol::kFarVertex, 0, far});
    }
    uint32_t total = 0;
    for (int k = 0; k < 4; ++k) total += answers[k].empty() ? 0 : odds_[k];
    uint32_t pick = static_cast<uint32_t>(random_.next() % total);
    int kind = 0;
    while (answers[kind].empty() || pick >= odds_[kind]) {
      if (!answers[kind].empty()) pick -= odds_[kind];
      ++kind;
    }
    const GateAnswer answer = answers[kind][random_.next() % answers[kind].size()];
    add(gate, answer, candidates, visited_);
    return answer;
  }

 private:
  std::vector<uint64_t> seeds_;
  size_t component_ = 0;
  SplitMix64 random_;
  uint32_t odds_[4] = {};
  uint32_t first_ = 0, first_face_ = 0;  // the component's first vertex and face
};
// Writes nothing: records the (element, context, value) of every bin.
class BinRecorder {
 public:
  static constexpr bool kReading = false;
  void bin(const char* name, BinContext&, int context, bool& value) { bins.insert({name, context, value}); }
  void raw(const char*, int, uint32_t&) {}
  [[noreturn]] void fail(ErrorKind kind, const char* element, const std::string& message) const {
    throw Error(kind, element, kNoPlane, kNoOffset, "suite: " + message);
  }
  std::set<std::tuple<std::string, int, bool>> bins;
};

// What an oracle's traversal makes, run until the oracle throws
// std::out_of_range (it has no more to say): the faces and vertices, and
// the bins it reaches.
struct Traversed {
  uint32_t faces = 0, vertices = 0;
  std::set<std::tuple<std::string, int, bool>> bins;
};
template <class Oracle>
Traversed traversed(Oracle oracle) {
  BinRecorder recorder;
  syntax::BaseMeshContexts contexts;
  GateTraversal traversal(0);
  try {
    constexpr uint32_t kUnbounded = std::numeric_limits<uint32_t>::max();
    describe_traversal(recorder, contexts, traversal, kUnbounded, kUnbounded, &oracle);
  } catch (const std::out_of_range&) {
  }
  return {static_cast<uint32_t>(traversal.faces().size()), oracle.vertices(), std::move(recorder.bins)};
}

// Answers for a fan of `fan` vertices, then far vertices whose
// differences from their gate's vertex follow the patterns of
// for_each_prefix_pattern() after a zero class's (a far residual is never
// 0), each after a run of ±1 long enough for the far channel's order k to
// return to 0: a border where the difference fits neither way. Past the
// last, std::out_of_range.
class FarScheduleOracle : public FaceTracker {
 public:
  explicit FarScheduleOracle(uint32_t fan) : fan_(fan) {
    for_each_prefix_pattern(13, [&](int32_t first, int32_t second) {
      if (first == 0) return;
      for (int i = 0; i < 100; ++i) schedule_.push_back(1);
      schedule_.push_back(std::abs(first));
      schedule_.push_back(std::abs(second));
    });
  }
  GateAnswer gate(HalfEdge gate, std::span<const uint32_t> candidates) {
    GateAnswer answer{GateSymbol::kBorder, 0, 0};
    if (visited_ < fan_) {
      if (visited_ == gate.to + 1) answer.symbol = GateSymbol::kNewVertex;
    } else {
      const int64_t d = schedule_.at(next_);
      for (int64_t c : {int64_t{gate.from} + d, int64_t{gate.from} - d})
        if (c >= 0 && c < visited_ && can_attach(gate, static_cast<uint32_t>(c))) {
          answer = {GateSymbol::kFarVertex, 0, static_cast<uint32_t>(c)};
          ++next_;
          break;
        }
    }
    add(gate, answer, candidates, visited_);
    return answer;
  }
 private:
  uint32_t fan_;
  std::vector<int64_t> schedule_;
  size_t next_ = 0;
};

// Seeds of components that reach the gate and candidate contexts: per
// round, of 2,000 seeds tried, the component that reaches the most bins not
// reached before, until a round adds none.
std::vector<uint64_t> covering_component_seeds() {
  std::vector<uint64_t> chosen;
  std::set<std::tuple<std::string, int, bool>> reached;
  SplitMix64 random(57);
  for (;;) {
    uint64_t best = 0;
    size_t most = 0;
    for (int trial = 0; trial < 2000; ++trial) {
      const uint64_t seed = random.next();
      size_t fresh = 0;
      for (const auto& bin : traversed(ComponentOracle({seed})).bins) fresh += !reached.count(bin);
      if (fresh > most) {
        most = fresh;
        best = seed;
      }
    }
    if (most == 0) return chosen;
    chosen.push_back(best);
    const Traversed t = traversed(ComponentOracle({best}));
    reached.insert(t.bins.begin(), t.bins.end());
  }
}

// Vertex order differences that follow prefix_schedule() for `count`
// vertices in no face (each predicted by the input number after the one
// before), towards the side with more numbers not taken, then 0.
std::vector<int32_t> order_schedule(uint32_t count) {
  std::vector<uint32_t> unused(count);
  for (uint32_t i = 0; i < count; ++i) unused[i] = i;
  const std::vector<int32_t> schedule = prefix_schedule();
  std::vector<int32_t> differences;
  int64_t previous = -1;
  for (uint32_t i = 0; i < count; ++i) {
    const int64_t predicted = std::clamp<int64_t>(previous + 1, 0, count - 1);
    const int64_t from = std::lower_bound(unused.begin(), unused.end(), static_cast<uint32_t>(predicted)) - unused.begin();
    const int64_t room_above = static_cast<int64_t>(unused.size()) - from;
    int32_t d = i < schedule.size() ? std::abs(schedule[i]) : 0;
    if (room_above <= from) d = -d;
    if (room_above == 0 && d == 0) d = -1;  // the prediction is past every number left
    differences.push_back(d);
    previous = unused[static_cast<size_t>(from + d)];
    unused.erase(unused.begin() + from + d);
  }
  return differences;
}

// A bfs3d frame unit whose first x residual has a prefix of 31 ones, one
// past the longest code (e + k ≤ 30).
std::vector<uint8_t> bfs3d_endless_prefix_unit(std::vector<uint8_t> unit_header) {
  const syntax::SectionPlace place;
  syntax::EntropyWriteIO<false> symbols(place);
  EndlessPrefixIO endless(symbols);
  syntax::ResidualCoder<1> coder;
  int32_t residual = 1;
  try {
    coder.describe(endless, 0, residual, syntax::kMotionResidual);
  } catch (const EndlessPrefixIO::Stop&) {
  }
  const std::vector<uint8_t> bins = symbols.finish_bins();
  Bfs3dFrame frame;
  frame.arithmetic_bytes[0] = static_cast<uint32_t>(bins.size());
  frame.bins[0] = bins;
  return unit_with(std::move(unit_header), frame);
}

// cpca-wpt with the paper's tools (shape components, basis predicted in
// index order) unless `values` name others.
Encode3dOptions cpca(CodecOptionValues values) {
  for (const auto& [option, value] : CodecOptionValues{{"model", "shape"}, {"basis", "index"}})
    if (!values.contains(option)) values[option] = value;
  return codec_with("cpca-wpt", std::move(values));
}

// The position of the n-th refinement unit (n from 0) among a stream's units.
size_t refinement_unit(const ContainerParts& parts, size_t n) {
  for (size_t k = 0; k < parts.units.size(); ++k)
    if (parts.units[k].payload[0] == static_cast<uint8_t>(UnitType::kRefinement) && n-- == 0) return k;
  throw Error(ErrorKind::kStructure, "", kNoPlane, kNoOffset, "suite: no such refinement unit");
}

// A refinement unit's cluster and kind (bytes 5 and 6 of its payload).
constexpr size_t kClusterByte = 5, kKindByte = 6;

// A refinement unit (frame 0) of cluster `cluster` with the bins and raw
// bits of its symbols.
std::vector<uint8_t> refinement_bytes(uint32_t cluster, uint32_t kind, uint32_t shift, syntax::EntropyWriteIO<false>& symbols) {
  const std::vector<uint8_t> bins = symbols.finish_bins(), raw = symbols.finish_raw();
  BitWriter writer;
  syntax::WriteIO io(writer);
  UnitHeader header{static_cast<uint32_t>(UnitType::kRefinement), 0};
  syntax::describe(io, header);
  CpcaRefinement r{cluster, kind, shift, static_cast<uint32_t>(bins.size()), bins, raw};
  syntax::describe(io, r);
  return writer.take_bytes();
}

// A refinement unit (frame 0, shift 16) whose symbols are the residuals
// given, channel and value, in order: values the encoder's description
// refuses to write, for the decoder to reject.
std::vector<uint8_t> crafted_refinement(uint32_t cluster, uint32_t kind, const std::vector<std::pair<int, int32_t>>& residuals) {
  syntax::ResidualCoder<4> coder;
  syntax::EntropyWriteIO<false> symbols(syntax::SectionPlace{});
  for (auto [channel, value] : residuals) coder.describe(symbols, channel, value, syntax::kCpcaBasis);
  return refinement_bytes(cluster, kind, kCpcaShiftBias, symbols);
}

// The start of a clustered-PCA stream written symbol by symbol: the
// encoder's object header and base mesh for `s` (one cluster, no hash
// units), the header's cluster map replaced by `cluster_of` (and F by
// `fraction_bits` when given); refinement units follow.
ContainerWriter cpca_written_start(const MeshSequence& s, const std::vector<uint32_t>& cluster_of, uint32_t clusters,
                                   std::optional<uint32_t> fraction_bits) {
  Encode3dOptions o = cpca({{"clusters", "1"}});
  o.hashes = false;
  ContainerParts parts = split_container(encode_mesh3d(s, o).stream);
  auto [object, header] = read_headers<CpcaHeader>(parts);
  syntax::EntropyWriteIO<false> map(syntax::SectionPlace{});
  std::vector<uint32_t> clusters_of = cluster_of;
  syntax::describe_cluster_map(map, clusters_of, clusters);
  const std::vector<uint8_t> map_bins = map.finish_bins(), map_raw = map.finish_raw();
  header.cluster_count = clusters;
  if (fraction_bits) header.fraction_bits = *fraction_bits;
  header.map_bins_bytes = static_cast<uint32_t>(map_bins.size());
  header.map_bins = map_bins;
  header.map_raw_bytes = static_cast<uint32_t>(map_raw.size());
  header.map_raw = map_raw;
  BitWriter payload;
  syntax::WriteIO out(payload);
  syntax::describe(out, object);
  syntax::describe(out, header);
  ContainerWriter writer;
  writer.object(payload.take_bytes());
  writer.unit(unit_of(parts, UnitType::kBaseMesh, 0).payload);
  return writer;
}

// A clustered-PCA stream of 2 frames written symbol by symbol (no hash
// units) over a base mesh the encoder wrote: 255 clusters, F = 16, and
// - a cluster map of clusters 0 … 254 in turn, then per pattern of
//   for_each_prefix_pattern() up to e = 7 (cluster differences reach 254)
//   200 vertices of cluster 64 and steps up by the pattern's two values;
// - per pattern p (e up to 13), cluster p's start (shift 17) whose
//   translation on every axis is the pattern's first value in frame 0 and
//   moves by its second in frame 1;
// - cluster 64's component whose basis steps through prefix_schedule() on
//   every axis;
// - per pattern pair 2c, 2c + 1, two components of cluster c whose
//   coefficients step by the pattern's values.
std::vector<uint8_t> cpca_written_stream() {
  constexpr uint32_t kClusters = kCpcaMaxClusters, kQuietCluster = 64;
  std::vector<uint32_t> cluster_of;
  for (uint32_t c = 0; c < kClusters; ++c) cluster_of.push_back(c);
  for_each_prefix_pattern(7, [&](int32_t first, int32_t second) {
    cluster_of.insert(cluster_of.end(), 200, kQuietCluster);
    cluster_of.push_back(kQuietCluster + static_cast<uint32_t>(std::abs(first)));
    cluster_of.push_back(cluster_of.back() + static_cast<uint32_t>(std::abs(second)));
  });
  const int loose = static_cast<int>(cluster_of.size()) - 11;  // designed_loose()'s sheet and box hold 11
  ContainerWriter writer =
      cpca_written_start(designed_loose(2, loose, [](int, int) { return 0; }), cluster_of, kClusters, kCpcaMaxFractionBits);

  const std::vector<std::vector<NodeIndex>> members = cpca_members(cluster_of, kClusters);
  auto start = [&](uint32_t cluster, std::vector<int32_t> translation) {
    syntax::EntropyWriteIO<false> symbols(syntax::SectionPlace{});
    syntax::describe_start(symbols, translation);
    writer.unit(refinement_bytes(cluster, kCpcaStart, kCpcaShiftBias + 1, symbols));
  };
  auto component = [&](uint32_t cluster, std::vector<int32_t> basis, std::vector<int32_t> coefficients) {
    basis.resize(3 * members[cluster].size());
    syntax::EntropyWriteIO<false> symbols(syntax::SectionPlace{});
    syntax::describe_operator(symbols, basis, coefficients);
    writer.unit(refinement_bytes(cluster, kCpcaComponent, kCpcaShiftBias, symbols));
  };
  std::vector<std::pair<int32_t, int32_t>> patterns;
  for_each_prefix_pattern(13, [&](int32_t first, int32_t second) { patterns.emplace_back(first, second); });
  for (uint32_t c = 0; c < patterns.size(); ++c) {
    const auto [first, second] = patterns[c];
    start(c, {first, first, first, first + second, first + second, first + second});
  }
  start(kQuietCluster, std::vector<int32_t>(6));
  std::vector<int32_t> basis;
  int32_t value = 0;
  for (int32_t step : prefix_schedule()) {
    value += step;
    basis.insert(basis.end(), 3, value);
  }
  component(kQuietCluster, basis, {1, 1});
  for (uint32_t c = 0; 2 * c < patterns.size(); ++c)
    for (uint32_t k = 2 * c; k < std::min<size_t>(2 * c + 2, patterns.size()); ++k)
      component(c, {1, 1, 1}, {patterns[k].first, patterns[k].first + patterns[k].second});
  return writer.finish();
}

// A clustered-PCA stream of 2 frames written symbol by symbol (no hash
// units) with a component of unit_kind 2 (shapes over the mesh) and one of
// unit_kind 3 (trajectories) per cluster below, each carrying the same
// values, over the separate quads of parallelogram_quads() at one place
// and as many vertices in no face:
// - cluster 0, the quads: a component whose basis is 0 at a quad's first
//   three vertices and prefix_schedule()'s next value at its fourth, so
//   that the parallelogram channels carry the schedule;
// - cluster 1, the vertices in no face (each predicted by the one before):
//   a component whose basis steps through prefix_schedule();
// - clusters 2 … 43, one vertex each: per pattern of
//   for_each_prefix_pattern(), a component whose coefficients step by the
//   pattern's values on every lane.
std::vector<uint8_t> cpca_mesh_written_stream() {
  const std::vector<int32_t> schedule = prefix_schedule();
  std::vector<std::pair<int32_t, int32_t>> patterns;
  for_each_prefix_pattern(13, [&](int32_t first, int32_t second) { patterns.emplace_back(first, second); });
  MeshSequence s = parallelogram_quads(std::vector<int32_t>(schedule.size(), 0));
  const uint32_t quads_end = s.vertex_count;
  for (size_t i = 0; i < schedule.size() + patterns.size(); ++i) s.frames[0].push_back({40000.0 + static_cast<double>(i % 64), 40000, 40000});
  s.vertex_count = static_cast<uint32_t>(s.frames[0].size());
  s.frames = {s.frames[0], s.frames[0]};
  std::vector<uint32_t> cluster_of(s.vertex_count, 0);
  for (uint32_t v = quads_end; v < quads_end + schedule.size(); ++v) cluster_of[v] = 1;
  for (uint32_t p = 0; p < patterns.size(); ++p) cluster_of[quads_end + schedule.size() + p] = 2 + p;
  const uint32_t clusters = 2 + static_cast<uint32_t>(patterns.size());

  ContainerWriter writer = cpca_written_start(s, cluster_of, clusters, std::nullopt);

  const BaseMeshPlan plan = plan_base_mesh(s.faces, s.vertex_count, false);
  const CpcaMeshPrediction mesh(plan.faces, plan.input_of, cluster_of, clusters);
  const std::vector<std::vector<NodeIndex>> members = cpca_members(cluster_of, clusters);
  // One value per member (every axis alike), one per frame (every lane alike).
  auto component = [&](uint32_t kind, uint32_t cluster, const std::vector<int32_t>& values, std::pair<int32_t, int32_t> frames) {
    const size_t per_member = kind == kCpcaTrajectory ? 1 : 3;
    std::vector<int32_t> basis, coefficients;
    for (int32_t v : values) basis.insert(basis.end(), per_member, v);
    coefficients.insert(coefficients.end(), 3 / per_member, frames.first);
    coefficients.insert(coefficients.end(), 3 / per_member, frames.second);
    syntax::EntropyWriteIO<false> symbols(syntax::SectionPlace{});
    if (kind == kCpcaTrajectory)
      mesh.describe_operator<1>(symbols, cluster, basis, coefficients);
    else
      mesh.describe_operator<3>(symbols, cluster, basis, coefficients);
    writer.unit(refinement_bytes(cluster, kind, kCpcaShiftBias, symbols));
  };
  for (uint32_t c = 0; c < clusters; ++c) {
    syntax::EntropyWriteIO<false> symbols(syntax::SectionPlace{});
    std::vector<int32_t> translation(6);
    syntax::describe_start(symbols, translation);
    writer.unit(refinement_bytes(c, kCpcaStart, kCpcaShiftBias, symbols));
  }
  std::vector<int32_t> quads(members[0].size(), 0);
  size_t next = 0;
  for (size_t i = 0; i < members[0].size(); ++i)
    if (members[0][i] >= 11 && (members[0][i] - 11) % 4 == 3) quads[i] = schedule[next++];  // a quad's fourth vertex
  std::vector<int32_t> chain;
  int32_t value = 0;
  for (int32_t step : schedule) chain.push_back(value += step);
  for (const uint32_t kind : {kCpcaMeshComponent, kCpcaTrajectory}) {
    component(kind, 0, quads, {1, 1});
    component(kind, 1, chain, {1, 1});
    for (uint32_t p = 0; p < patterns.size(); ++p)
      component(kind, 2 + p, {1}, {patterns[p].first, patterns[p].first + patterns[p].second});
  }
  return writer.finish();
}

// One cluster with more components of both kinds than either limit: the
// units of a moving tetrahedron's shape components (3 over 3 frames, the
// limit), then those of its trajectory components (3: its 4 vertices less
// their mean), no hash units.
std::vector<uint8_t> cpca_mixed_kinds_stream() {
  auto units = [](const char* model) {
    Encode3dOptions o = cpca({{"clusters", "1"}, {"noise", "-4"}, {"model", model}});
    o.hashes = false;
    return split_container(encode_mesh3d(moving_tetrahedron(3), o).stream);
  };
  ContainerParts shapes = units("shape");
  const ContainerParts trajectories = units("trajectory");
  for (const ContainerUnit& unit : trajectories.units)
    if (unit.payload[0] == static_cast<uint8_t>(UnitType::kRefinement) && unit.payload[kKindByte] == kCpcaTrajectory) shapes.units.push_back(unit);
  ContainerWriter writer;
  writer.object(shapes.object_payload);
  for (const ContainerUnit& unit : shapes.units) writer.unit(unit.payload);
  return writer.finish();
}

// The clustered-PCA codec's streams: both orders, a prefix cut at a unit
// boundary, the finest and coarsest quantization, one cluster, F = 0.
std::vector<SuiteCase> cpca_cases(bool traced) {
  const MeshSequence flag = waving_flag(9, 8, false);
  std::vector<SuiteCase> suite;
  suite.push_back(valid("cpca-01-wpt", "cpca-wpt, 4 clusters, weighted progressive order", {"cpca", "container-units"}, flag,
                        cpca({{"clusters", "4"}}), traced));
  suite.push_back(valid("cpca-02-rpt", "cpca-wpt, round robin over the clusters", {"cpca"}, flag, cpca({{"clusters", "4"}, {"order", "rpt"}}),
                        traced));
  {
    // The prefix of cpca-01 through its twelfth unit (no hash units, no
    // end code), traced as the encoder traced those units.
    const SuiteCase& full = suite.front();
    const ContainerParts parts = split_container(full.stream);
    SuiteCase prefix = decode_case(
        "cpca-03-prefix", "the first 12 units of cpca-01: a prefix cut at a unit boundary decodes", {"cpca", "cpca-prefix"},
        std::vector<uint8_t>(full.stream.begin(), full.stream.begin() + static_cast<std::ptrdiff_t>(parts.units[12].byte_offset)));
    if (traced) prefix.encoder_trace = full.encoder_trace.substr(0, full.encoder_trace.find("\nunit 12 ") + 1);
    suite.push_back(std::move(prefix));
  }
  suite.push_back(valid("cpca-04-fine", "every component at the finest noise step, a 16-bit grid", {"cpca"}, flag,
                        cpca({{"clusters", "3"}, {"components", "4096"}, {"noise", "-4"}, {"bits", "16"}}), traced));
  suite.push_back(valid("cpca-05-coarse", "the coarsest noise step on a 4-bit grid", {"cpca"}, flag,
                        cpca({{"clusters", "3"}, {"noise", "12"}, {"bits", "4"}}), traced));
  suite.push_back(valid("cpca-06-one-cluster", "one cluster", {"cpca"}, flag, cpca({{"clusters", "1"}}), traced));
  suite.push_back(valid("cpca-08-spikes", "vertices that jump by 2^−2 … 2^−23 of the box on a 24-bit grid", {"cpca"},
                        spiky_sheet(8, 16, 0, 43, 30), cpca({{"clusters", "3"}, {"bits", "24"}, {"noise", "-4"}, {"components", "4096"}}), traced));
  suite.push_back(valid("cpca-09-many-clusters", "200 clusters over 389 vertices: cluster numbers far apart", {"cpca"},
                        spiky_sheet(4, 16, 100, 47, 3), cpca({{"clusters", "200"}, {"bits", "24"}}), traced));
  suite.push_back(written_case("cpca-10-written", "a stream written symbol by symbol: every prefix length 0 … 13 after each class in "
                              "translations, basis values and coefficients, cluster differences up to 254, F = 16, start shifts above 16",
                              {"cpca"}, cpca_written_stream()));
  suite.push_back(valid("cpca-11-mesh-basis", "shape components whose basis is predicted over the base mesh (unit_kind 2)", {"cpca"}, flag,
                        cpca({{"clusters", "4"}, {"basis", "mesh"}}), traced));
  suite.push_back(valid("cpca-12-trajectories", "trajectory components (unit_kind 3)", {"cpca"}, flag,
                        cpca({{"clusters", "4"}, {"model", "trajectory"}}), traced));
  suite.push_back(valid("cpca-13-trajectories-scattered", "trajectory components of 200 clusters over a sheet: members without neighbours",
                        {"cpca"}, spiky_sheet(4, 16, 100, 47, 3), cpca({{"clusters", "200"}, {"bits", "24"}, {"model", "trajectory"}}), traced));
  suite.push_back(written_case("cpca-14-mesh-written", "unit_kind 2 and 3 written symbol by symbol: every prefix length 0 … 13 after "
                              "each class on the parallelogram, neighbour and coefficient channels", {"cpca"}, cpca_mesh_written_stream()));
  suite.push_back(written_case("cpca-16-mixed-kinds", "one cluster of 4 vertices over 3 frames: 3 shape components (its limit, "
                              "min(3M, N) = 3) and 3 trajectory components (of min(M, 3N) = 4), counted apart", {"cpca"}, cpca_mixed_kinds_stream()));
  suite.push_back(valid("cpca-07-no-fraction", "a 24-bit grid: fraction_bits 0", {"cpca"}, flag, cpca({{"clusters", "2"}, {"bits", "24"}}),
                        traced));
  return suite;
}

// The clustered-PCA codec's streams to reject: header ranges, and the unit
// rules (cluster, start, component count).
std::vector<SuiteCase> cpca_rejected_cases(const std::vector<SuiteCase>& valid) {
  std::vector<SuiteCase> suite;
  const std::vector<uint8_t> base = find(valid, "cpca-01-wpt");
  auto field = [&base](const char* name) { return header_byte<CpcaHeader>(base, name); };
  const struct {
    const char* id;
    const char* purpose;
    const char* field;
    uint8_t value;
    ErrorKind kind;
    const char* element;
  } header_cases[] = {
      {"x-26-cpca-no-cluster", "cluster_count 0", "cluster_count", 0, ErrorKind::kOutOfRange, "cluster_count"},
      {"x-27-cpca-fraction-bits", "fraction_bits 17", "fraction_bits", 17, ErrorKind::kOutOfRange, "fraction_bits"},
      {"x-28-cpca-map-beyond", "cluster_count 3 while the map names cluster 3", "cluster_count", 3, ErrorKind::kOutOfRange, "cluster_of_vertex"},
      {"x-29-cpca-empty-cluster", "cluster_count 5 while the map names clusters 0 … 3", "cluster_count", 5, ErrorKind::kStructure, "cluster_count"},
      {"x-37-cpca-quantization-bits", "quantization_bits 3", "quantization_bits", 3, ErrorKind::kOutOfRange, "quantization_bits"},
  };
  for (const auto& c : header_cases)
    suite.push_back(invalid(c.id, c.purpose, {"cpca"}, edited(base, [&](ContainerParts& p) { p.object_payload[field(c.field)] = c.value; }),
                            c.kind, c.element, kNoPlane));
  suite.push_back(invalid("x-30-cpca-no-frame-count", "frame_count 0 (unknown)", {"cpca"},
                          edited(base,
                                 [&](ContainerParts& p) {
                                   for (size_t i = 0; i < 4; ++i) p.object_payload[field("frame_count") + i] = 0;
                                 }),
                          ErrorKind::kStructure, "frame_count", kNoPlane));
  suite.push_back(invalid("x-31-cpca-cluster-beyond", "a refinement unit for cluster 4 of 4", {"cpca"},
                          edited(base, [](ContainerParts& p) { p.units[refinement_unit(p, 0)].payload[kClusterByte] = 4; }),
                          ErrorKind::kOutOfRange, "cluster", 0));
  suite.push_back(invalid("x-32-cpca-unit-kind", "unit_kind 4", {"cpca"},
                          edited(base, [](ContainerParts& p) { p.units[refinement_unit(p, 0)].payload[kKindByte] = 4; }),
                          ErrorKind::kOutOfRange, "unit_kind", 0));
  // The first component unit of a kind moves before every refinement unit (they follow the base mesh).
  auto component_first = [](uint32_t kind) {
    return [kind](ContainerParts& p) {
      size_t k = refinement_unit(p, 0);
      while (p.units[k].payload[kKindByte] != kind) ++k;
      ContainerUnit component = p.units[k];
      p.units.erase(p.units.begin() + static_cast<std::ptrdiff_t>(k));
      p.units.insert(p.units.begin() + static_cast<std::ptrdiff_t>(refinement_unit(p, 0)), component);
    };
  };
  suite.push_back(invalid("x-33-cpca-not-started", "a component of a cluster before the cluster's start", {"cpca"},
                          edited(base, component_first(kCpcaComponent)), ErrorKind::kStructure, "unit_kind", 0));
  suite.push_back(invalid("x-65-cpca-mesh-not-started", "a unit_kind 2 component of a cluster before the cluster's start", {"cpca"},
                          edited(find(valid, "cpca-11-mesh-basis"), component_first(kCpcaMeshComponent)), ErrorKind::kStructure, "unit_kind", 0));
  suite.push_back(invalid("x-66-cpca-trajectory-not-started", "a trajectory component of a cluster before the cluster's start", {"cpca"},
                          edited(find(valid, "cpca-12-trajectories"), component_first(kCpcaTrajectory)), ErrorKind::kStructure, "unit_kind",
                          0));
  suite.push_back(invalid("x-34-cpca-second-start", "a cluster's start sent twice", {"cpca"},
                          edited(base,
                                 [](ContainerParts& p) {
                                   const size_t first = refinement_unit(p, 0);
                                   p.units.insert(p.units.begin() + static_cast<std::ptrdiff_t>(first) + 1, p.units[first]);
                                 }),
                          ErrorKind::kStructure, "unit_kind", 0));
  suite.push_back(invalid("x-35-cpca-refinement-frame", "a refinement unit naming frame 1", {"cpca"},
                          edited(base, [](ContainerParts& p) { p.units[refinement_unit(p, 0)].payload[4] = 1; }),
                          ErrorKind::kStructure, "frame_index", 1));
  suite.push_back(invalid("x-38-cpca-shift", "shift 64", {"cpca"},
                          edited(base, [](ContainerParts& p) { p.units[refinement_unit(p, 0)].payload[kKindByte + 1] = 64; }),
                          ErrorKind::kOutOfRange, "shift", 0));
  {
    // Values beyond their ranges, in the first refinement units: cluster
    // 0's start, then one of its components.
    const ContainerParts parts = split_container(base);
    const size_t start = refinement_unit(parts, 0);
    const uint32_t cluster = parts.units[start].payload[kClusterByte];
    // The cluster's size, from the header's cluster map.
    const auto [object, header] = read_headers<CpcaHeader>(parts);
    const std::vector<uint32_t> cluster_of = syntax::read_cluster_map<false>(header, object.vertex_count, syntax::SectionPlace{});
    std::vector<std::pair<int, int32_t>> coefficient_beyond(3 * static_cast<size_t>(std::count(cluster_of.begin(), cluster_of.end(), cluster)));
    for (size_t j = 0; j < coefficient_beyond.size(); ++j) coefficient_beyond[j] = {static_cast<int>(j % 3), 0};
    coefficient_beyond.emplace_back(syntax::kCpcaCoefficientChannel, (1 << 23) + 1);
    const struct {
      const char* id;
      const char* purpose;
      uint32_t kind;
      std::vector<std::pair<int, int32_t>> residuals;
      const char* element;
    } ranges[] = {
        {"x-39-cpca-translation-range", "a start whose first translation is 2^29 + 1", kCpcaStart, {{0, (1 << 29) + 1}}, "translation"},
        {"x-40-cpca-basis-range", "a component whose first basis value is 2^15 + 1", kCpcaComponent, {{0, (1 << 15) + 1}}, "basis"},
        {"x-41-cpca-coefficient-range", "a component whose first coefficient is 2^23 + 1", kCpcaComponent, coefficient_beyond, "coefficient"},
        // The first member in coding order has no member before it: channel D, from 0.
        {"x-63-cpca-mesh-basis-range", "a unit_kind 2 component whose first basis value is 2^15 + 1", kCpcaMeshComponent,
         {{3, (1 << 15) + 1}}, "mesh_basis"},
        {"x-64-cpca-trajectory-basis-range", "a trajectory component whose first basis value is 2^15 + 1", kCpcaTrajectory,
         {{1, (1 << 15) + 1}}, "trajectory_basis"},
    };
    for (const auto& c : ranges)
      suite.push_back(invalid(c.id, c.purpose, {"cpca"},
                              edited(base,
                                     [&](ContainerParts& p) {
                                       const std::vector<uint8_t> unit = crafted_refinement(cluster, c.kind, c.residuals);
                                       // A start replaces cluster's start; a component follows it.
                                       if (c.kind == kCpcaStart)
                                         p.units[start].payload = unit;
                                       else
                                         p.units.insert(p.units.begin() + static_cast<std::ptrdiff_t>(start) + 1, ContainerUnit{0, 0, unit});
                                     }),
                              ErrorKind::kOutOfRange, c.element, 0));
  }
  {
    // One cluster over 3 frames has 3 components: its fourth is one too many.
    const std::vector<uint8_t> short_stream = encode_mesh3d(moving_tetrahedron(3), cpca({{"clusters", "1"}, {"noise", "-4"}})).stream;
    suite.push_back(invalid("x-36-cpca-beyond-components", "a fourth component of a cluster over 3 frames", {"cpca"},
                            edited(short_stream,
                                   [](ContainerParts& p) {
                                     size_t last = refinement_unit(p, 0), components = 0;
                                     for (size_t k = 0; k < p.units.size(); ++k)
                                       if (p.units[k].payload[0] == static_cast<uint8_t>(UnitType::kRefinement)) {
                                         last = k;
                                         components += p.units[k].payload[kKindByte] == kCpcaComponent;
                                       }
                                     const ContainerUnit copy = p.units[last];
                                     for (size_t extra = components; extra < 4; ++extra)
                                       p.units.insert(p.units.begin() + static_cast<std::ptrdiff_t>(last) + 1, copy);
                                   }),
                            ErrorKind::kStructure, "cluster", 0));
  }
  {
    // One cluster of 4 vertices has at most 4 trajectory components: a fifth is one too many.
    const std::vector<uint8_t> short_stream =
        encode_mesh3d(moving_tetrahedron(3), cpca({{"clusters", "1"}, {"noise", "-4"}, {"model", "trajectory"}})).stream;
    suite.push_back(invalid("x-62-cpca-beyond-trajectories", "a fifth trajectory component of a cluster of 4 vertices", {"cpca"},
                            edited(short_stream,
                                   [](ContainerParts& p) {
                                     size_t last = 0, components = 0;
                                     for (size_t k = 0; k < p.units.size(); ++k)
                                       if (p.units[k].payload[0] == static_cast<uint8_t>(UnitType::kRefinement) &&
                                           p.units[k].payload[kKindByte] == kCpcaTrajectory) {
                                         last = k;
                                         ++components;
                                       }
                                     if (components == 0) throw Error(ErrorKind::kStructure, "", kNoPlane, kNoOffset, "suite: no trajectory unit");
                                     const ContainerUnit copy = p.units[last];
                                     for (size_t extra = components; extra < 5; ++extra)
                                       p.units.insert(p.units.begin() + static_cast<std::ptrdiff_t>(last) + 1, copy);
                                   }),
                            ErrorKind::kStructure, "cluster", 0));
  }
  return suite;
}

// What real meshes have, in one sequence numbered out of any traversal's
// order: a closed octahedron, an open sheet, two fans sharing a vertex, a
// third face on an edge, a degenerate face, a repeated face, a face turned
// the wrong way, and vertices in no face; coordinates small integers.
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

// A wheel of 2k faces around a top vertex, whose rim is the top of k
// strips (arms) rising from a fan at the bottom; arm i is shorter by
// min(i, k − i), so that the traversal, spreading both ways around the
// fan, reaches every arm's top in the same wave. The top vertex then has
// an open half-edge per arm, and the wheel's faces between arms close on
// candidates 1 … 7, or, past the 8-candidate cut, far vertices. Last, a
// loose face (v, v, u) on the seed's third corner v and first corner u.
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

// An n × n grid whose quads split along either diagonal at random: vertex
// degrees from 2 to 8, so that gates meet most pairs of degrees, each pair
// and its mirror many times.
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

// The same sequence with its vertices numbered at random.
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

// The irregular grid, 16 × 16 = 2^8 vertices numbered at random (so that
// the gate's vertex predicts input numbers better than parallelograms),
// with loose faces: a degenerate one, and faces repeating a directed edge
// of the grid with another third vertex, so that parallelograms across
// those edges take the first face of the edge.
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

// Frames of s.vertex_count positions at random on a 2^−10 grid of the unit box.
void add_random_frames(MeshSequence& s, int frames, SplitMix64& random) {
  for (int f = 0; f < frames; ++f) {
    std::vector<Vec3> frame;
    for (NodeIndex v = 0; v < s.vertex_count; ++v)
      frame.push_back({random.uniform(0, 1023) / 1024.0, random.uniform(0, 1023) / 1024.0, random.uniform(0, 1023) / 1024.0});
    s.frames.push_back(std::move(frame));
  }
}

// A chain of faces, each across an edge of the one before, whose third
// vertex is new or, half of the time, an earlier vertex at random: far
// vertices at every distance from the gate's (up to the vertex count),
// after far vertices near and far.
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

// Faces on few vertices at random, no directed edge twice: vertices with
// many open half-edges around them, so that gates meet 3 and more
// candidates at every pair of degrees and take every index.
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

// The base mesh: every kind of face and vertex, in the input order and in
// coding order; a row-major sheet, whose input numbers parallelograms predict.
std::vector<SuiteCase> base_mesh_cases(bool traced) {
  std::vector<SuiteCase> suite;
  const MeshSequence awkward = awkward_mesh(4);
  suite.push_back(valid("base-01-awkward", "components, borders, vertices in no face, non-manifold, degenerate and repeated faces",
                        {"base-mesh"}, awkward, Encode3dOptions{}, traced));
  Encode3dOptions reorder;
  reorder.reorder = true;
  suite.push_back(valid("base-02-coding-order", "the same mesh numbered in coding order (encode3d --reorder)", {"base-mesh"}, awkward,
                        reorder, traced));
  suite.push_back(valid("base-03-row-major", "a row-major sheet: input numbers predicted by parallelograms", {"base-mesh"},
                        rotating_sheet(3), Encode3dOptions{}, traced));
  suite.push_back(valid("base-04-crown", "gates with up to 8 candidates: candidate indices 1 … 7, the cut at 8, and a loose face (v, v, u)",
                        {"base-mesh"}, crown(2, 12, 12), Encode3dOptions{}, traced));
  suite.push_back(valid("base-05-irregular", "a grid of random diagonals: gate and candidate contexts over most pairs of degrees, both ways",
                        {"base-mesh"}, irregular_grid(2, 16), Encode3dOptions{}, traced));
  Encode3dOptions bits24;
  bits24.codec_options = {{"bits", "24"}};
  suite.push_back(valid("base-06-shuffled", "256 vertices numbered at random (vertex order 1), loose faces on a 2^8 index, parallelograms "
                        "across edges that loose faces repeat", {"base-mesh"}, shuffled_grid(2), Encode3dOptions{}, traced));
  {
    MeshSequence spiky = spiky_sheet(2, 32, 200, 46, 4);
    renumber_at_random(spiky, 1289);
    suite.push_back(valid("base-07-spikes", "1,291 vertices numbered at random, a quarter of them off their place by 2^−2 … 2^−23 of the box on a "
                          "24-bit grid: position and order residuals of every prefix length", {"base-mesh"}, spiky, bits24, traced));
  }
  Encode3dOptions bits16;
  bits16.codec_options = {{"bits", "16"}};
  suite.push_back(valid("base-08-far-chain", "a chain of faces whose third vertices are often earlier ones at random: far vertices at "
                        "every distance, after near and far ones", {"base-mesh"}, far_chain(3000, 51), Encode3dOptions{}, traced));
  suite.push_back(valid("base-09-dense-soup", "300 faces on 32 vertices at random: gates with 3 and more candidates at every pair of "
                        "degrees, every candidate index", {"base-mesh"}, dense_soup(32, 300, 54), Encode3dOptions{}, traced));
  suite.push_back(valid("base-10-loose-chain", "vertices in no face, each off the one before by a residual of every prefix length 0 … 13 "
                        "after each class", {"base-mesh"}, loose_chain(prefix_schedule()), bits16, traced));
  suite.push_back(valid("base-11-parallelograms", "separate quads whose fourth vertex is off the parallelogram by a residual of every "
                        "prefix length 0 … 13 after each class", {"base-mesh"}, parallelogram_quads(prefix_schedule()), bits16, traced));
  suite.push_back(written_case("base-12-order-prefixes", "a face and 23,997 vertices in no face whose vertex order differences take every "
                              "prefix length 0 … 13 after each class (written symbol by symbol)", {"base-mesh"},
                              [] {
                                constexpr uint32_t kVertices = 24000;
                                FirstFarOracle seed;  // the one face: a seed of new vertices
                                return written_base_mesh_stream(kVertices, 1, seed, order_schedule(kVertices));
                              }()));
  {
    const std::vector<uint64_t> seeds = covering_component_seeds();
    const Traversed size = traversed(ComponentOracle(seeds));
    ComponentOracle oracle(seeds);
    suite.push_back(written_case("base-13-gate-contexts", "components of random answers, chosen among many for the gate and candidate "
                                "contexts they reach (written symbol by symbol)", {"base-mesh"},
                                written_base_mesh_stream(size.vertices, size.faces, oracle)));
  }
  // The first far residual of a unit is the only one after a zero class: one prefix length per unit.
  for (int e = 4; e <= 12; ++e) {
    FirstFarOracle oracle{static_cast<uint32_t>(3 << (e - 1))};
    char id[40];
    std::snprintf(id, sizeof id, "base-14-first-far-%02d", e);
    suite.push_back(written_case(id, "a fan whose first far vertex takes a residual of prefix length " + std::to_string(e) + " (written symbol by symbol)",
                                {"base-mesh"}, written_base_mesh_stream(oracle.from + 2, oracle.from + 1, oracle)));
  }
  {
    FarScheduleOracle oracle(20000);
    const Traversed size = traversed(oracle);
    suite.push_back(written_case("base-15-far-prefixes", "a fan of 20,000 vertices, then faces on far vertices whose residuals take every "
                                "prefix length 0 … 13 after a residual of length 0 and of length 1 (written symbol by symbol)", {"base-mesh"},
                                written_base_mesh_stream(size.vertices, size.faces, oracle)));
  }
  return suite;
}

// Group hash units: after frame-by-frame units, and after frames decoded
// out of display order.
std::vector<SuiteCase> group_hash_cases(bool traced) {
  std::vector<SuiteCase> suite;
  suite.push_back(valid("hash-01-groups", "bfs3d with a group hash unit per 4 frames, the last group shorter", {"container-hash"},
                        box_and_sheet(10, 3), Encode3dOptions{}, traced, 4));
  const MeshSequence flag = waving_flag(13, 8, false);
  suite.push_back(valid("hash-02-groups-out-of-order", "lcc with temporal prediction and a group hash unit per 3 frames", {"container-hash"},
                        flag, lcc({{"temporal", "1"}, {"gop", "4"}}), traced, 3));
  return suite;
}

// Streams to reject, each made from a valid one.
std::vector<SuiteCase> rejected_cases(const std::vector<SuiteCase>& valid) {
  std::vector<SuiteCase> suite;
  const std::vector<uint8_t> base = find(valid, "ao-01-me1-k16");
  suite.push_back(invalid("x-01-codec-unknown", "codec_id 5 is not registered", {"container"},
                          edited(base, [](ContainerParts& p) { p.object_payload[1] = 5; }), ErrorKind::kReservedValue, "codec_id", kNoPlane));
  suite.push_back(invalid("x-02-codec-zero", "codec_id 0 is reserved", {"container"},
                          edited(base, [](ContainerParts& p) { p.object_payload[1] = 0; }), ErrorKind::kReservedValue, "codec_id", kNoPlane));
  // The object payload: 18 bytes of object header, quantization_bits, 3 origins, step, then matrix_bits.
  suite.push_back(invalid("x-03-matrix-bits", "matrix_bits 30", {"ao-header"},
                          edited(base, [](ContainerParts& p) { p.object_payload[18 + 1 + 12 + 4] = 30; }), ErrorKind::kOutOfRange,
                          "matrix_bits", kNoPlane));
  suite.push_back(invalid("x-04-direct-shift", "direct_shift 27", {"ao-frame"},
                          edited(base, [](ContainerParts& p) { unit_of(p, UnitType::kFrame, 1).payload[5] = 27; }),
                          ErrorKind::kOutOfRange, "direct_shift", 1));
  suite.push_back(invalid("x-05-arithmetic-bytes", "arithmetic_bytes longer than the frame", {"ao-frame"},
                          edited(base, [](ContainerParts& p) { unit_of(p, UnitType::kFrame, 2).payload[6] = 0x7F; }),
                          ErrorKind::kOutOfRange, "arithmetic_bytes", 2));
  suite.push_back(invalid("x-06-frame-cut", "a frame unit cut after 3 bytes of data", {"ao-frame"},
                          edited(base, [](ContainerParts& p) { unit_of(p, UnitType::kFrame, 1).payload.resize(8); }),
                          ErrorKind::kTruncated, "arithmetic_bytes", 1));
  suite.push_back(invalid("x-07-frame-gap", "frame 2 labelled frame 3", {"container-units"},
                          edited(base, [](ContainerParts& p) { unit_of(p, UnitType::kFrame, 2).payload[4] = 3; }),
                          ErrorKind::kStructure, "frame_index", 2));
  suite.push_back(invalid("x-08-missing-frames", "frame_count 6, the stream ends after frame 3", {"container-units"},
                          edited(base, [](ContainerParts& p) {
                            while (p.units.back().payload[4] > 3) p.units.pop_back();
                          }),
                          ErrorKind::kTruncated, "mesh3d_unit_start_code", 4));
  {
    // An intra base mesh whose faces are not frame 0's.
    MeshSequence other = box_and_sheet(6, 4);
    std::swap(other.faces[0], other.faces[1]);
    const std::vector<uint8_t> other_stream = encode_mesh3d(other, affine("1")).stream;
    const std::vector<uint8_t> intra = split_container(other_stream).units[0].payload;
    suite.push_back(invalid("x-09-intra-other-faces", "an intra base mesh with other faces", {"container-units"},
                            edited(base,
                                   [&](ContainerParts& p) {
                                     ContainerUnit& unit = unit_of(p, UnitType::kFrame, 2);
                                     unit.payload = intra;
                                     unit.payload[4] = 2;
                                   }),
                            ErrorKind::kStructure, "base_mesh", 2));
  }
  // bfs3d frame data: six u(32) lengths after the unit header, raw_bytes_z last.
  const std::vector<uint8_t> bfs3d = find(valid, "bfs3d-01-average");
  suite.push_back(invalid("x-10-bfs3d-lengths", "raw_bytes_z longer than the frame", {"bfs3d"},
                          edited(bfs3d, [](ContainerParts& p) { unit_of(p, UnitType::kFrame, 1).payload[(syntax::unit_data_offset() - 32) / 8 + 20] = 0x7F; }),
                          ErrorKind::kOutOfRange, "raw_bytes_z", 1));
  suite.push_back(invalid("x-11-bfs3d-trailing", "a byte after the six streams", {"bfs3d"},
                          edited(bfs3d, [](ContainerParts& p) { unit_of(p, UnitType::kFrame, 3).payload.push_back(0x55); }),
                          ErrorKind::kStructure, "raw_bytes_z", 3));
  const struct {
    const char* id;
    const char* purpose;
    int section;
  } left_over[] = {{"x-12-bfs3d-bins-left-over", "a byte after the last bin of bins_x, counted by arithmetic_bytes_x", 0},
                   {"x-13-bfs3d-raw-left-over", "a byte after the last raw bits of raw_y, counted by raw_bytes_y", 3}};
  for (const auto& c : left_over)
    suite.push_back(invalid(c.id, c.purpose, {"bfs3d"},
                            edited(bfs3d,
                                   [&](ContainerParts& p) {
                                     ContainerUnit& unit = unit_of(p, UnitType::kFrame, 2);
                                     unit.payload = with_extra_byte(unit.payload, c.section);
                                   }),
                            ErrorKind::kStructure, "motion_residual", 2));
  // The lcc header's fields, found by name in the description of the stream's own headers.
  const std::vector<uint8_t> cloth = find(valid, "lcc-01-stream");
  auto lcc_field = [&cloth](const char* name) { return header_byte<LccHeader>(cloth, name); };
  suite.push_back(invalid("x-14-lcc-theta-bits", "theta_bits 16", {"lcc"},
                          edited(cloth, [&](ContainerParts& p) { p.object_payload[lcc_field("theta_bits")] = 16; }), ErrorKind::kOutOfRange,
                          "theta_bits", kNoPlane));
  suite.push_back(invalid("x-15-lcc-rh-range-zero", "rh_range 0", {"lcc"},
                          edited(cloth,
                                 [&](ContainerParts& p) {
                                   for (size_t i = 0; i < 4; ++i) p.object_payload[lcc_field("rh_range") + i] = 0;
                                 }),
                          ErrorKind::kOutOfRange, "rh_range", kNoPlane));
  suite.push_back(invalid("x-16-lcc-second-base-mesh", "a second base mesh unit in place of frame 2", {"lcc"},
                          edited(cloth,
                                 [](ContainerParts& p) {
                                   std::vector<uint8_t> again = unit_of(p, UnitType::kBaseMesh, 0).payload;
                                   again[4] = 2;
                                   unit_of(p, UnitType::kFrame, 2).payload = again;
                                 }),
                          ErrorKind::kStructure, "unit_type", 2));
  const struct {
    const char* id;
    const char* purpose;
    const char* field;
    uint8_t value;
  } lcc_ranges[] = {{"x-17-lcc-quantization-bits", "quantization_bits 25", "quantization_bits", 25},
                    {"x-18-lcc-reference-mode", "reference_mode 2", "reference_mode", 2},
                    {"x-19-lcc-coding-mode", "coding_mode 2", "coding_mode", 2},
                    {"x-20-lcc-rh-bits", "rh_bits 21", "rh_bits", 21},
                    {"x-21-lcc-gop-one", "temporal_gop 1 (no temporal prediction is 0)", "temporal_gop", 1},
                    {"x-22-lcc-gop-65", "temporal_gop 65", "temporal_gop", 65}};
  for (const auto& c : lcc_ranges)
    suite.push_back(invalid(c.id, c.purpose, {"lcc"}, edited(cloth, [&](ContainerParts& p) { p.object_payload[lcc_field(c.field)] = c.value; }),
                            ErrorKind::kOutOfRange, c.field, kNoPlane));
  const std::vector<uint8_t> temporal = find(valid, "lcc-07-temporal-stream");
  suite.push_back(invalid("x-23-lcc-temporal-no-frame-count", "temporal prediction with frame_count 0 (unknown)", {"lcc-temporal"},
                          edited(temporal,
                                 [&](ContainerParts& p) {
                                   for (size_t i = 0; i < 4; ++i) p.object_payload[lcc_field("frame_count") + i] = 0;
                                 }),
                          ErrorKind::kStructure, "temporal_gop", kNoPlane));
  suite.push_back(invalid("x-24-lcc-temporal-display-order", "a unit labelled frame 2 where the order has anchor 9", {"lcc-temporal"},
                          edited(temporal,
                                 [](ContainerParts& p) {
                                   unit_of(p, UnitType::kFrame, 9).payload[4] = 2;
                                 }),
                          ErrorKind::kStructure, "frame_index", 9));
  // Frame 3, predicted from frames 1 and 5, with every rho residual
  // 2^(rh_bits+1): prediction plus residual leave the range.
  suite.push_back(invalid("x-25-lcc-rho-beyond-prediction", "predicted frame 3 whose rho residuals push rho beyond ±2^rh_bits",
                          {"lcc-temporal"}, edited(temporal, [&](ContainerParts& p) {
                            ContainerUnit& unit = unit_of(p, UnitType::kFrame, 3);
                            unit.payload = lcc_rho_unit(temporal, {unit.payload.begin(), unit.payload.begin() + 5}, true, 2, 0);
                          }),
                          ErrorKind::kOutOfRange, "rho", 3));
  // Frame 1 of a stream without temporal prediction, an anchor, with every
  // rho residual 2^rh_bits + 1: one beyond an anchor's range, within a
  // predicted frame's.
  suite.push_back(invalid("x-56-lcc-anchor-rho", "an anchor whose rho residuals are 2^rh_bits + 1", {"lcc"},
                          edited(cloth, [&](ContainerParts& p) {
                            ContainerUnit& unit = unit_of(p, UnitType::kFrame, 1);
                            unit.payload = lcc_rho_unit(cloth, {unit.payload.begin(), unit.payload.begin() + 5}, false, 1, 1);
                          }),
                          ErrorKind::kOutOfRange, "rho", 1));
  for (SuiteCase& c : cpca_rejected_cases(valid)) suite.push_back(std::move(c));
  // Group hash units (after hash-01's frame 3, a group of frames 0 … 3).
  const std::vector<uint8_t> grouped = find(valid, "hash-01-groups");
  auto first_group = [](ContainerParts& p) -> ContainerUnit& {
    for (ContainerUnit& unit : p.units)
      if (unit.payload[0] == static_cast<uint8_t>(UnitType::kGroupHash)) return unit;
    throw Error(ErrorKind::kStructure, "", kNoPlane, kNoOffset, "suite: no group hash unit");
  };
  const size_t group_frames_byte = (syntax::unit_data_offset() - 32) / 8 + 1;  // the low byte of group_frames
  suite.push_back(invalid("x-42-group-ahead", "a group hash of frames 0 … 4 after frame 3", {"container-hash"},
                          edited(grouped, [&](ContainerParts& p) { first_group(p).payload[group_frames_byte] = 5; }), ErrorKind::kStructure,
                          "group_frames", 0));
  suite.push_back(invalid("x-43-group-empty", "group_frames 0", {"container-hash"},
                          edited(grouped, [&](ContainerParts& p) { first_group(p).payload[group_frames_byte] = 0; }), ErrorKind::kOutOfRange,
                          "group_frames", 0));
  suite.push_back(invalid("x-44-group-beyond", "a group of frames 8 … 10 where frame_count is 10: one frame past the end", {"container-hash"},
                          edited(grouped,
                                 [&](ContainerParts& p) {
                                   ContainerUnit& last = p.units[p.units.size() - 1];
                                   last.payload[group_frames_byte] = 3;  // frames 8 and 9 are the last group
                                 }),
                          ErrorKind::kStructure, "group_frames", 8));
  suite.push_back(invalid("x-45-group-md5-cut", "a group hash unit one byte short", {"container-hash"},
                          edited(grouped, [&](ContainerParts& p) { first_group(p).payload.pop_back(); }), ErrorKind::kOutOfRange,
                          "group_md5", 0));
  // The base mesh unit's fields: vertex_order, loose_face_count, arithmetic_bytes, then the sections.
  const std::vector<uint8_t> awkward = find(valid, "base-01-awkward");
  const size_t order_byte = (syntax::unit_data_offset() - 32) / 8;
  auto base_unit = [](ContainerParts& p) -> std::vector<uint8_t>& { return unit_of(p, UnitType::kBaseMesh, 0).payload; };
  suite.push_back(invalid("x-46-base-vertex-order", "vertex_order 3", {"base-mesh"},
                          edited(awkward, [&](ContainerParts& p) { base_unit(p)[order_byte] = 3; }), ErrorKind::kOutOfRange,
                          "vertex_order", 0));
  suite.push_back(invalid("x-47-base-loose-faces", "loose_face_count one more than face_count", {"base-mesh"},
                          edited(awkward,
                                 [&](ContainerParts& p) {
                                   const uint8_t* faces = &p.object_payload[6];  // face_count, after version, codec_id, vertex_count
                                   const uint32_t count = (uint32_t{faces[0]} << 24 | uint32_t{faces[1]} << 16 | uint32_t{faces[2]} << 8 | faces[3]) + 1;
                                   for (int i = 0; i < 4; ++i) base_unit(p)[order_byte + 1 + static_cast<size_t>(i)] = static_cast<uint8_t>(count >> (24 - 8 * i));
                                 }),
                          ErrorKind::kOutOfRange, "loose_face_count", 0));
  suite.push_back(invalid("x-48-base-raw-left-over", "a byte after the raw bits", {"base-mesh"},
                          edited(awkward, [&](ContainerParts& p) { base_unit(p).push_back(0x00); }), ErrorKind::kStructure, "base_mesh", 0));
  suite.push_back(invalid("x-49-base-bins-left-over", "a zero byte after the last bin, counted by arithmetic_bytes", {"base-mesh"},
                          edited(awkward,
                                 [&](ContainerParts& p) {
                                   std::vector<uint8_t>& unit = base_unit(p);
                                   const size_t length = order_byte + 5;
                                   const uint32_t bins = uint32_t{unit[length]} << 24 | uint32_t{unit[length + 1]} << 16 |
                                                         uint32_t{unit[length + 2]} << 8 | unit[length + 3];
                                   unit.insert(unit.begin() + static_cast<std::ptrdiff_t>(length + 4 + bins), 0x00);
                                   ++unit[length + 3];  // fewer than 255 bytes of bins
                                 }),
                          ErrorKind::kStructure, "base_mesh", 0));
  // Each at the edge of its rule, so that a decoder whose check is one off accepts it.
  suite.push_back(invalid("x-50-frame-index-at-count", "a seventh frame unit labelled frame 6 where frame_count is 6", {"container-units"},
                          edited(base,
                                 [](ContainerParts& p) {
                                   ContainerUnit extra = unit_of(p, UnitType::kFrame, 5);
                                   extra.payload[4] = 6;
                                   p.units.push_back(std::move(extra));
                                 }),
                          ErrorKind::kStructure, "frame_index", 6));
  {
    std::vector<uint8_t> trailing = base;
    trailing.push_back(0x00);
    suite.push_back(invalid("x-51-trailing-byte", "a zero byte after the end code", {"container"}, trailing, ErrorKind::kTrailingData,
                            "mesh_object_end_code", kNoPlane));
  }
  suite.push_back(invalid("x-52-version", "version 2", {"container"}, edited(base, [](ContainerParts& p) { p.object_payload[0] = 2; }),
                          ErrorKind::kReservedValue, "version", kNoPlane));
  suite.push_back(invalid("x-53-vertex-count-short", "vertex_count 3 for a tetrahedron: its fourth vertex is one too many", {"base-mesh"},
                          edited(find(valid, "ao-06-direct-root"), [](ContainerParts& p) { p.object_payload[5] = 3; }), ErrorKind::kStructure,
                          "gate_new_vertex", 0));
  suite.push_back(invalid("x-57-ao-matrix-beyond", "a root leaf whose matrix element 0 is one above matrix_bits' range", {"ao-cell"},
                          edited(base,
                                 [&](ContainerParts& p) {
                                   ContainerUnit& unit = unit_of(p, UnitType::kFrame, 1);
                                   unit.payload = ao_matrix_beyond_unit(base, {unit.payload.begin(), unit.payload.begin() + 5});
                                 }),
                          ErrorKind::kOutOfRange, "matrix_residual", 1));
  const size_t max_depth = header_byte<AffineOctreeHeader>(base, "max_depth");
  suite.push_back(invalid("x-54-max-depth-21", "max_depth 21", {"ao-header"},
                          edited(base, [max_depth](ContainerParts& p) { p.object_payload[max_depth] = 21; }), ErrorKind::kOutOfRange,
                          "max_depth", kNoPlane));
  suite.push_back(invalid("x-58-residual-prefix-31", "a residual whose prefix has 31 bins '1': one past the longest code", {"container"},
                          edited(bfs3d,
                                 [](ContainerParts& p) {
                                   ContainerUnit& unit = unit_of(p, UnitType::kFrame, 1);
                                   unit.payload = bfs3d_endless_prefix_unit({unit.payload.begin(), unit.payload.begin() + 5});
                                 }),
                          ErrorKind::kInvalidCode, "motion_residual", 1));
  {
    // Base mesh units of the box and sheet (ao-01) broken by the traversal's answers.
    const ObjectHeader object = read_headers<AffineOctreeHeader>(split_container(base)).first;
    auto broken = [&](BrokenBaseMesh oracle) {
      return edited(base, [&](ContainerParts& p) {
        ContainerUnit& unit = unit_of(p, UnitType::kBaseMesh, 0);
        unit.payload = broken_base_mesh_unit({unit.payload.begin(), unit.payload.begin() + 5}, object.vertex_count, object.face_count, oracle);
      });
    };
    BrokenBaseMesh seed_repeats;
    seed_repeats.old_corner = 1;
    suite.push_back(invalid("x-59-base-seed-repeats", "a seed face whose second corner is its first vertex again", {"base-mesh"},
                            broken(seed_repeats), ErrorKind::kStructure, "seed_vertex", 0));
    suite.push_back(invalid("x-60-base-far-unnumbered", "a far vertex equal to the count of vertices numbered so far", {"base-mesh"},
                            broken(BrokenBaseMesh{}), ErrorKind::kOutOfRange, "far_vertex", 0));
  }
  {
    // One triangle (a seed, three border gates) whose last vertex takes the
    // rank one past the single input number left.
    MeshSequence triangle;
    triangle.vertex_count = 3;
    triangle.faces = {{{0, 1, 2}}};
    triangle.frames = {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 0, 1}, {1, 0, 1}, {0, 1, 1}}};
    BrokenBaseMesh borders;
    borders.answer = {GateSymbol::kBorder, 0, 0};
    suite.push_back(invalid("x-61-base-order-past", "a vertex order whose last difference is one past the input numbers not taken", {"base-mesh"},
                            edited(encode_mesh3d(triangle, Encode3dOptions{}).stream,
                                   [&](ContainerParts& p) {
                                     ContainerUnit& unit = unit_of(p, UnitType::kBaseMesh, 0);
                                     unit.payload = broken_base_mesh_unit({unit.payload.begin(), unit.payload.begin() + 5}, 3, 1, borders, {0, 0, 1});
                                   }),
                            ErrorKind::kOutOfRange, "vertex_order_difference", 0));
  }
  const size_t prediction = header_byte<Bfs3dHeader>(bfs3d, "prediction_mode");
  suite.push_back(invalid("x-55-bfs3d-prediction-2", "prediction_mode 2", {"bfs3d"},
                          edited(bfs3d, [prediction](ContainerParts& p) { p.object_payload[prediction] = 2; }), ErrorKind::kOutOfRange,
                          "prediction_mode", kNoPlane));
  return suite;
}

}  // namespace

std::vector<SuiteCase> build_suite3d(bool traced) {
  std::vector<SuiteCase> suite = affine_octree_cases(traced);
  for (SuiteCase& c : bfs3d_cases(traced)) suite.push_back(std::move(c));
  for (SuiteCase& c : lcc_cases(traced)) suite.push_back(std::move(c));
  for (SuiteCase& c : cpca_cases(traced)) suite.push_back(std::move(c));
  for (SuiteCase& c : group_hash_cases(traced)) suite.push_back(std::move(c));
  for (SuiteCase& c : base_mesh_cases(traced)) suite.push_back(std::move(c));
  for (SuiteCase& c : rejected_cases(suite)) suite.push_back(std::move(c));
  return suite;
}

}  // namespace m4mesh
