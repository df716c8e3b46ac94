#include "codecs3d/registry.h"

#include <algorithm>

#include "common/error.h"

namespace m4mesh {

// Each codec's factories and option declarations, defined in its own files.
std::unique_ptr<CodecDecoder3d> make_bfs3d_decoder(const ObjectHeader&, syntax::ReadIO&);
std::unique_ptr<CodecEncoder3d> make_bfs3d_encoder(const MeshSequence&, const CodecSettings&);
std::vector<CodecOption> bfs3d_options();
std::unique_ptr<CodecDecoder3d> make_affine_octree_decoder(const ObjectHeader&, syntax::ReadIO&);
std::unique_ptr<CodecEncoder3d> make_affine_octree_encoder(const MeshSequence&, const CodecSettings&);
std::vector<CodecOption> affine_octree_options();
std::unique_ptr<CodecDecoder3d> make_lcc_decoder(const ObjectHeader&, syntax::ReadIO&);
std::unique_ptr<CodecEncoder3d> make_lcc_encoder(const MeshSequence&, const CodecSettings&);
std::vector<CodecOption> lcc_options();
std::unique_ptr<CodecDecoder3d> make_cpca_wpt_decoder(const ObjectHeader&, syntax::ReadIO&);
std::unique_ptr<CodecEncoder3d> make_cpca_wpt_encoder(const MeshSequence&, const CodecSettings&);
std::vector<CodecOption> cpca_wpt_options();

namespace {

// The integers from `first` to `last`, as text.
std::vector<std::string> values(int first, int last) {
  std::vector<std::string> out;
  for (int v = first;; v += first < last ? 1 : -1) {
    out.push_back(std::to_string(v));
    if (v == last) return out;
  }
}

std::vector<Codec3d>& table() {
  static std::vector<Codec3d> rows = {
      {1, "bfs3d", "Method II in 3D: breadth-first motion prediction, lossless on the grid", "docs/codec_bfs3d.md",
       {UnitType::kBaseMesh, UnitType::kFrame}, bfs3d_options(), {"bits", values(4, 24), {}}, make_bfs3d_decoder, make_bfs3d_encoder},
      {2, "affine-octree", "an octree of affine motion cells, closed loop", "docs/codec_affine_octree.md",
       {UnitType::kBaseMesh, UnitType::kFrame}, affine_octree_options(),
       {"me", {"50", "30", "20", "12", "8", "5", "3", "2", "1.2", "0.8", "0.5", "0.3", "0.2", "0.1"}, {}}, make_affine_octree_decoder,
       make_affine_octree_encoder},
      {3, "lcc", "cloth in local cylindrical coordinates: dihedral angle, radius and height against a reference mesh", "docs/codec_lcc.md",
       {UnitType::kBaseMesh, UnitType::kFrame}, lcc_options(), {"theta-bits", values(2, 15), {}}, make_lcc_decoder, make_lcc_encoder},
      {4, "cpca-wpt", "clustered PCA, progressive: every refinement unit adds one principal component of one cluster to every frame",
       "docs/codec_cpca_wpt.md", {UnitType::kBaseMesh, UnitType::kRefinement}, cpca_wpt_options(),
       {"noise", values(12, -4), {{"components", "4096"}}}, make_cpca_wpt_decoder, make_cpca_wpt_encoder},
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
  throw Error(ErrorKind::kUsage, "", kNoPlane, kNoOffset, "unknown codec '" + name + "' (available: " + names + ")");
}

void register_codec3d(Codec3d codec) {
  if (codec.id == 0 || codec.id > 255 || find_codec3d(codec.id))
    throw Error(ErrorKind::kUsage, "", kNoPlane, kNoOffset, "codec_id " + std::to_string(codec.id) + " is taken or outside 1 … 255");
  if (!codec.make_decoder || !codec.make_encoder)
    throw Error(ErrorKind::kUsage, "", kNoPlane, kNoOffset, "codec " + codec.name + " needs a decoder and an encoder");
  table().push_back(std::move(codec));
}

}  // namespace m4mesh
