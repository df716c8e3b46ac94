#include "codecs3d/registry.h"

#include <algorithm>

#include "common/error.h"

namespace m4mesh {

namespace {

std::vector<Codec3d>& table() {
  static std::vector<Codec3d> rows = {
      {kBfs3dId, "bfs3d", "Method II in 3D: breadth-first motion prediction, lossless on the grid", "docs/codec_bfs3d.md",
       {UnitType::kBaseMesh, UnitType::kFrame}},
      {kAffineOctreeId, "affine-octree", "an octree of affine motion cells, closed loop", "docs/codec_affine_octree.md", {UnitType::kBaseMesh, UnitType::kFrame}},
      {kLccId, "lcc", "cloth in local cylindrical coordinates: dihedral angle, radius and height against a reference mesh", "docs/codec_lcc.md",
       {UnitType::kBaseMesh, UnitType::kFrame}},
      {kCpcaWptId, "cpca-wpt", "clustered PCA, progressive: every refinement unit adds one principal component of one cluster to every frame",
       "docs/codec_cpca_wpt.md", {UnitType::kBaseMesh, UnitType::kRefinement}},
  };
  return rows;
}

}  // namespace

bool Codec3d::uses(UnitType type) const { return std::find(unit_types.begin(), unit_types.end(), type) != unit_types.end(); }

std::span<const Codec3d> codecs3d() { return table(); }

const Codec3d* find_codec3d(uint32_t id) {
  for (const Codec3d& c : table())
    if (c.id == id) return &c;
  return nullptr;
}

const Codec3d& codec3d_by_name(const std::string& name) {
  std::string names;
  for (const Codec3d& c : table()) {
    if (c.name == name) return c;
    names += (names.empty() ? "" : ", ") + c.name;
  }
  throw usage_error("unknown codec '" + name + "' (available: " + names + ")");
}

void register_codec3d(Codec3d codec) {
  if (codec.id == 0 || codec.id > 255 || find_codec3d(codec.id))
    throw usage_error("codec_id " + std::to_string(codec.id) + " is taken or outside 1 … 255");
  table().push_back(std::move(codec));
}

}  // namespace m4mesh
