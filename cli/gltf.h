// Decoded animations for the tools people look at them in: a sequence as
// one glTF 2.0 asset that plays as an animation (docs/gltf.md). The faces
// once; every frame a morph target holding its positions exactly (the
// base positions are zero, so a target of weight 1 gives the frame's
// float32 values bit for bit); a weights animation with STEP
// interpolation, frame k at k / fps seconds.
#pragma once

#include <string>

#include "mesh3d/sequence.h"

namespace m4mesh {

// .glb (binary) or .gltf (JSON, its buffer embedded), written atomically.
void write_gltf(const MeshSequence& sequence, double fps, const std::string& path);

}  // namespace m4mesh
