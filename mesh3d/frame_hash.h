// What the hash units of a 3D stream carry (docs/container3d.md, "Hash
// units"): a decoded frame's canonical bytes, their MD5, and the MD5 of a
// group of frames. The encoder writes them and the decoder checks them
// with these same functions.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "common/point3.h"

namespace m4mesh {

using Digest = std::array<uint8_t, 16>;

// A decoded frame's canonical bytes: binary32 x, y, z per vertex, little-endian.
std::vector<uint8_t> frame_bytes(std::span<const Float3> positions);
// The same appended to `out`.
void append_frame_bytes(std::span<const Float3> positions, std::vector<uint8_t>& out);
// Their MD5: a frame hash unit's frame_md5.
Digest frame_digest(std::span<const Float3> positions);
// The digests of frames of one vertex count, several at once (SIMD lanes).
void frame_digests(std::span<const std::span<const Float3>> frames, std::span<Digest> out);
// The MD5 of the frames' digests concatenated in display order: a group
// hash unit's group_md5.
Digest group_digest(std::span<const Digest> frame_digests);

}  // namespace m4mesh
