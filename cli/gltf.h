// Decoded animations for the tools people look at them in: a sequence as
// one glTF 2.0 asset that plays as an animation (docs/gltf.md). The faces
// once; every frame a morph target holding its positions exactly (the
// base positions are zero, so a target of weight 1 gives the frame's
// float32 values bit for bit); a weights animation with STEP
// interpolation, frame k at k / fps seconds.
#pragma once

#include <cstdint>
#include <string>

#include "mesh3d/sequence.h"

namespace m4mesh {

// The most bytes of data one asset holds (a GLB counts its length in 32 bits).
inline constexpr uint64_t kMostGltfBytes = (uint64_t{1} << 32) - (uint64_t{1} << 20);

// .glb (binary) or .gltf (JSON, its buffer embedded), written atomically;
// a sequence past kMostGltfBytes is refused before anything is written.
void write_gltf(const MeshSequence& sequence, double fps, const std::string& path);

}  // namespace m4mesh
