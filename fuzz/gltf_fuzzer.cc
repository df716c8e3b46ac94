// libFuzzer target: a GLB animation baked (encode3d's glTF input), at its
// keyframes and at a given rate, and compressed (m4mesh gltf, bfs3d), its
// skins left and baked, within limits a fuzzer's time allows.
#include <cstddef>
#include <cstdint>
#include <span>

#include "cli/gltf.h"
#include "cli/gltf_compress.h"
#include "common/error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace m4mesh;
  for (const std::optional<double> fps : {std::optional<double>{}, std::optional<double>{7.0}}) {
    try {
      read_glb(std::span<const uint8_t>(data, size), "fuzz.glb", {.mesh = "", .animation = "", .fps = fps}, {.most_positions = 1 << 16, .most_work = 1 << 20});
    } catch (const Error&) {
    }
  }
  GltfCompressArgs compressing;
  compressing.encoding.codec = "bfs3d";
  compressing.limits = {.most_positions = 1 << 16, .most_work = 1 << 20};
  for (const bool skins : {false, true}) {
    compressing.bake_skins = skins;
    try {
      compress_glb(std::span<const uint8_t>(data, size), "fuzz.glb", compressing);
    } catch (const Error&) {
    }
  }
  return 0;
}
