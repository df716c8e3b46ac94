// libFuzzer target: the 3D container, the base mesh and every registered
// 3D codec's decoder, plain, from an intra refresh (seek), traced, and in
// the checker's carry-on mode.
#include <cstddef>
#include <cstdint>
#include <sstream>

#include "bitstream/bit_reader.h"
#include "common/error.h"
#include "conformance/checker.h"
#include "decoder/mesh3d/container_decoder.h"
#include "syntax/mesh3d/container.h"

namespace {

// A few bytes may declare up to 2^24 vertices (arithmetic-coded symbols have no minimum size), and decoding
// such a stream to its error is linear in them: under a second in a release build, 10 s at 4 M with the fuzzer's
// instrumentation. Slow, not wrong (tests/fuzz_regressions replays two), so the fuzzer keeps its timeout for hangs.
constexpr uint32_t kMaxFuzzedVertices = uint32_t{1} << 18, kMaxFuzzedFaces = uint32_t{1} << 19;
// A progressive codec's first unit decodes every frame the header declares (cpca-wpt's mean shape, however
// many segments have no unit): output linear in vertices × frames, skipped beyond this.
constexpr uint64_t kMaxFuzzedVertexFrames = uint64_t{1} << 24;

bool declares_more_than_budget(std::span<const uint8_t> stream) {
  using namespace m4mesh;
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

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace m4mesh;
  const std::span<const uint8_t> stream(data, size);
  if (declares_more_than_budget(stream)) return -1;  // -1: not added to the corpus
  try {
    Decode3dOptions options;
    options.verify = true;
    Mesh3dDecoder decoder(stream, options);
    while (decoder.next_frame()) {
    }
  } catch (const Error&) {
  }
  try {
    Decode3dOptions options;
    options.verify = true;
    Mesh3dDecoder decoder(stream, options);
    decoder.seek(size > 0 ? data[size - 1] : 0);
    while (decoder.next_frame()) {
    }
  } catch (const Error&) {
  }
  try {
    std::ostringstream text;
    trace_mesh3d(stream, text);
  } catch (const Error&) {
  }
  check_mesh3d(stream);
  return 0;
}
