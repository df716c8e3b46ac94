// m4mesh gltf: a glTF 2.0 file whose morph-target animations (and, with
// bake_skins, skin animations) are replaced by m4mesh streams in the
// M4MESH_vertex_animation extension (docs/extensions/), everything else of
// the file kept as it was.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "cli/encode3d.h"
#include "cli/gltf.h"

namespace m4mesh {

inline constexpr const char* kGltfExtensionName = "M4MESH_vertex_animation";
// The quality target of --codec auto when none is given (KG, percent).
inline constexpr double kDefaultGltfTargetKg = 0.1;

struct GltfCompressArgs {
  std::string input, output;  // .glb or .gltf in; .glb out
  Encode3dArgs encoding;      // --codec, the quality target, the codecs' options
  bool required = false;      // the extension in extensionsRequired too
  bool bake_skins = false;    // a skin's animations baked into streams too, the skin taken from its node
  GltfLimits limits;          // what one primitive's baking may take
};

// One stream the compressor wrote: where its frames come from and what it measured.
struct GltfStreamReport {
  int animation = -1, node = -1, mesh = -1, primitive = -1;
  std::string codec;
  uint32_t frames = 0, vertices = 0;
  uint64_t stream_bytes = 0, replaced_bytes = 0;  // the stream; the targets', weights', joints' and skin weights' data it replaces
  double kg = 0, psnr = 0, max_error = 0;
};

struct GltfCompressResult {
  std::vector<uint8_t> glb;
  std::vector<GltfStreamReport> streams;
  std::vector<std::string> warnings;
};

// The compressed file of a .glb or .gltf (`path`, its buffers read by
// tinygltf: beside it or inside). An input error names the mesh and
// primitive, the animation or the extension it cannot take.
GltfCompressResult compress_gltf(const std::string& path, const GltfCompressArgs& args);
// The same of a GLB in memory (no file beside it); `name` for the errors.
GltfCompressResult compress_glb(std::span<const uint8_t> bytes, const std::string& name, const GltfCompressArgs& args);

int run_gltf_compress(const GltfCompressArgs& args);

}  // namespace m4mesh
