#include "decoder/mesh3d/codec_decoders.h"

#include <map>

#include "codecs3d/registry.h"
#include "common/error.h"

namespace m4mesh {

// Defined in each codec's file.
std::unique_ptr<CodecDecoder3d> make_bfs3d_decoder(const ObjectHeader&, syntax::ReadIO&);
std::unique_ptr<CodecDecoder3d> make_affine_octree_decoder(const ObjectHeader&, syntax::ReadIO&);
std::unique_ptr<CodecDecoder3d> make_lcc_decoder(const ObjectHeader&, syntax::ReadIO&);
std::unique_ptr<CodecDecoder3d> make_cpca_wpt_decoder(const ObjectHeader&, syntax::ReadIO&);

namespace {

std::map<uint32_t, MakeDecoder3d>& table() {
  static std::map<uint32_t, MakeDecoder3d> rows = {
      {kBfs3dId, make_bfs3d_decoder}, {kAffineOctreeId, make_affine_octree_decoder}, {kLccId, make_lcc_decoder}, {kCpcaWptId, make_cpca_wpt_decoder}};
  return rows;
}

}  // namespace

const MakeDecoder3d* find_decoder3d(uint32_t codec_id) {
  const auto row = table().find(codec_id);
  return row == table().end() ? nullptr : &row->second;
}

void register_decoder3d(uint32_t codec_id, MakeDecoder3d make) {
  if (!find_codec3d(codec_id) || find_decoder3d(codec_id) || !make)
    throw usage_error("codec_id " + std::to_string(codec_id) + ": register the codec first, and its decoder once");
  table().emplace(codec_id, std::move(make));
}

}  // namespace m4mesh
