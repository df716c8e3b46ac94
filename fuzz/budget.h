// What the 3D fuzz targets leave out: streams whose header declares more
// work than a fuzzer's run allows.
#pragma once

#include <cstdint>
#include <span>

#include "bitstream/bit_reader.h"
#include "common/error.h"
#include "syntax/mesh3d/container.h"

namespace m4mesh::fuzz {

// A few bytes may declare up to 2^24 vertices (arithmetic-coded symbols have no minimum size), and decoding
// such a stream to its error is linear in them: under a second in a release build, 10 s at 4 M with the fuzzer's
// instrumentation. Slow, not wrong (tests/fuzz_regressions replays two), so the fuzzer keeps its timeout for hangs.
inline constexpr uint32_t kMaxFuzzedVertices = uint32_t{1} << 18, kMaxFuzzedFaces = uint32_t{1} << 19;
// A progressive codec's first unit decodes every frame the header declares (cpca-wpt's mean shape, however
// many segments have no unit): output linear in vertices × frames, skipped beyond this.
inline constexpr uint64_t kMaxFuzzedVertexFrames = uint64_t{1} << 24;

inline bool declares_more_than_budget(std::span<const uint8_t> stream) {
  try {
    const ContainerParts parts = split_container(stream);
    BitReader reader(parts.object_payload.data(), parts.object_payload.size());
    syntax::ReadIO io(reader);
    ObjectHeader header;
    syntax::describe(io, header);
    return header.vertex_count > kMaxFuzzedVertices || header.face_count > kMaxFuzzedFaces ||
           uint64_t{header.vertex_count} * header.frame_count > kMaxFuzzedVertexFrames;
  } catch (const Error&) {
    return false;
  }
}

}  // namespace m4mesh::fuzz
