// Animations in glTF 2.0 (docs/gltf.md), both ways.
// Out: a sequence as one asset that plays as an animation. The faces once;
// every frame a morph target holding its positions exactly (the base
// positions are zero, so a target of weight 1 gives the frame's float32
// values bit for bit); a weights animation with STEP interpolation, frame
// k at k / fps seconds.
// In: one mesh of an asset, its morph targets and its skin baked to frames
// at the animation's keyframes or at a given rate.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>

#include "mesh3d/sequence.h"

namespace m4mesh {

// The most bytes of data one asset holds (a GLB counts its length in 32 bits).
inline constexpr uint64_t kMostGltfBytes = (uint64_t{1} << 32) - (uint64_t{1} << 20);

// .glb (binary) or .gltf (JSON, its buffer embedded), written atomically;
// a sequence past kMostGltfBytes is refused before anything is written.
void write_gltf(const MeshSequence& sequence, double fps, const std::string& path);

// Whether a path names a glTF asset (.glb or .gltf).
bool is_gltf_path(const std::string& path);

struct GltfSelection {
  std::string mesh;       // a node's or a mesh's name; empty: the asset's one animated mesh
  std::string animation;  // empty: the asset's one animation
  std::optional<double> fps;  // sample at this rate; none: at the animation's keyframes
};

// What baking may take: vertex positions kept (frames × vertices), and
// vertex operations (per frame and vertex: 1, its weighted morph targets
// and its joints).
struct GltfLimits {
  uint64_t most_positions = uint64_t{1} << 26;
  uint64_t most_work = uint64_t{1} << 33;
};

struct GltfAnimation {
  MeshSequence sequence;
  double fps = 0;  // the rate of the frames: `fps`, or the keyframes' (evenly spaced)
};

// The chosen mesh's triangles (every primitive's, in order) and, per
// sample time, its vertices after morph targets, skin (linear blend) and
// its node's transform, as float32 values. Errors name the file and what
// it holds that cannot be taken.
GltfAnimation read_gltf(const std::string& path, const GltfSelection& selection, const GltfLimits& limits = {});
// The same of a GLB in memory (no file beside it); `name` for the errors.
GltfAnimation read_glb(std::span<const uint8_t> bytes, const std::string& name, const GltfSelection& selection, const GltfLimits& limits = {});

}  // namespace m4mesh
