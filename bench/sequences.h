// The benchmark sequences: the real ones in ../shared/data, or a synthetic
// rippling sheet when they are absent.
#pragma once

#include <cmath>
#include <filesystem>
#include <map>
#include <string>

#include "mesh3d/sequence.h"

namespace m4mesh::bench {

namespace fs = std::filesystem;

inline const fs::path kData = fs::path(M4MESH_SOURCE_DIR) / ".." / "shared" / "data";

// An n × n grid of vertices in row-major order, two triangles per cell; no frames.
inline MeshSequence grid_sheet(int n) {
  MeshSequence s;
  s.vertex_count = static_cast<uint32_t>(n * n);
  for (int y = 0; y + 1 < n; ++y)
    for (int x = 0; x + 1 < n; ++x) {
      const NodeIndex a = static_cast<NodeIndex>(y * n + x);
      s.faces.push_back({{a, a + 1, a + static_cast<NodeIndex>(n) + 1}});
      s.faces.push_back({{a, a + static_cast<NodeIndex>(n) + 1, a + static_cast<NodeIndex>(n)}});
    }
  return s;
}

// A rippling 128×128 sheet, when the real data is absent.
inline MeshSequence synthetic() {
  const int n = 128;
  MeshSequence s = grid_sheet(n);
  for (int f = 0; f < 40; ++f) {
    std::vector<Vec3> frame;
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x)
        frame.push_back({x / 64.0, y / 64.0, 0.1 * std::sin(0.2 * x + 0.3 * f) * std::cos(0.1 * y)});
    s.frames.push_back(std::move(frame));
  }
  return s;
}

inline const MeshSequence& sequence(const std::string& name) {
  static std::map<std::string, MeshSequence> cache;
  auto it = cache.find(name);
  if (it == cache.end()) {
    const fs::path path = kData / name;
    it = cache.emplace(name, fs::exists(path) ? load_sequence(path.string()) : synthetic()).first;
  }
  return it->second;
}

inline const char* const kNames[] = {"horse-gallop", "pcow"};

// The sequence's name, or "synthetic" when its data is absent.
inline std::string label(const std::string& name) { return fs::exists(kData / name) ? name : "synthetic"; }
inline std::string label(int64_t index) { return label(std::string(kNames[index])); }

}  // namespace m4mesh::bench
