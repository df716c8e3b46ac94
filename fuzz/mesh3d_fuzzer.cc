// libFuzzer target: the 3D container, the Draco base mesh and the bfs3d decoder.
#include <cstddef>
#include <cstdint>

#include "common/error.h"
#include "decoder/mesh3d_decoder.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace m4mesh;
  try {
    Mesh3dDecoder decoder({data, size}, true);
    while (decoder.next_frame()) {
    }
  } catch (const Error&) {
  }
  return 0;
}
