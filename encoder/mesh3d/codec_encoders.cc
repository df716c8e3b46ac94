#include "encoder/mesh3d/codec_encoders.h"

#include <map>

#include "common/error.h"

namespace m4mesh {

// Defined in each codec's files.
std::unique_ptr<CodecEncoder3d> make_bfs3d_encoder(const FrameSource&, const CodecSettings&);
std::vector<CodecOption> bfs3d_options();
std::unique_ptr<CodecEncoder3d> make_affine_octree_encoder(const FrameSource&, const CodecSettings&);
std::vector<CodecOption> affine_octree_options();
std::unique_ptr<CodecEncoder3d> make_lcc_encoder(const FrameSource&, const CodecSettings&);
std::vector<CodecOption> lcc_options();
std::unique_ptr<CodecEncoder3d> make_cpca_wpt_encoder(const FrameSource&, const CodecSettings&);
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

std::map<uint32_t, CodecEncoding>& table() {
  static std::map<uint32_t, CodecEncoding> rows = {
      {kBfs3dId, {bfs3d_options(), {"bits", values(4, 24), {}}, make_bfs3d_encoder}},
      {kAffineOctreeId,
       {affine_octree_options(),
        {"me", {"50", "30", "20", "12", "8", "5", "3", "2", "1.2", "0.8", "0.5", "0.3", "0.2", "0.1"}, {}},
        make_affine_octree_encoder}},
      {kLccId, {lcc_options(), {"theta-bits", values(2, 15), {}}, make_lcc_encoder}},
      {kCpcaWptId, {cpca_wpt_options(), {"noise", values(12, -4), {{"components", "4096"}}}, make_cpca_wpt_encoder}},
  };
  return rows;
}

}  // namespace

const CodecEncoding& codec_encoding(const Codec3d& codec) {
  const auto row = table().find(codec.id);
  if (row == table().end()) throw usage_error("codec " + codec.name + " has no encoder");
  return row->second;
}

void register_encoder3d(uint32_t codec_id, CodecEncoding encoding) {
  if (!find_codec3d(codec_id) || table().count(codec_id) || !encoding.make_encoder)
    throw usage_error("codec_id " + std::to_string(codec_id) + ": register the codec first, and its encoder once");
  table().emplace(codec_id, std::move(encoding));
}

}  // namespace m4mesh
