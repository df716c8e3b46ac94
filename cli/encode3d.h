// m4mesh encode3d: an animated 3D mesh to a mesh3d stream, by one codec or
// the smallest stream at a quality target.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <utility>

#include "encoder/mesh3d/codec_options.h"
#include "encoder/mesh3d/container_encoder.h"

namespace CLI {
class App;
}

namespace m4mesh {

struct Encode3dArgs {
  std::string input;
  std::string output;
  std::string codec = "bfs3d";       // or "auto": every codec at the target, the smallest kept
  CodecOptionValues codec_options;  // only those given
  std::optional<double> target_kg, target_psnr, max_error;  // a quality target
  bool no_hash = false;
  bool reorder = false;      // vertices renumbered in coding order
  std::string position_blend = "auto";  // the base meshes' blend: auto or 0 … 16
  uint32_t hash_group = 16;  // frames per group hash unit; 1: a frame hash unit per frame
  // The stream's frame rate (default 25); a glTF input is sampled at it
  // (default: at its keyframes, whose rate the stream takes).
  std::optional<double> fps;
  std::string gltf_mesh, gltf_animation;  // glTF: --mesh, --animation
  bool trace = false;
  unsigned threads = 0;  // --codec auto: codecs searched at once; 0: every core
};
// A frame rate as the container's fraction num / den (each 1 … 65535): the
// smallest power-of-ten den that holds it exactly, else the largest that fits.
std::pair<uint32_t, uint32_t> frame_rate_fraction(double fps);
// What every command that encodes takes from its encode3d arguments: the
// codec and its options, the hash units, the threads.
Encode3dOptions encode3d_options(const Encode3dArgs& args);
// Adds --codec, the quality targets and every registered codec's own
// options to `command`.
void add_codec_options(CLI::App& command, Encode3dArgs& args);
int run_encode3d(const Encode3dArgs& args);

}  // namespace m4mesh
