// libFuzzer target: the 3D container, the Draco base mesh and every registered 3D codec's decoder.
#include <cstddef>
#include <cstdint>

#include "common/error.h"
#include "decoder/mesh3d/container_decoder.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace m4mesh;
  try {
    Decode3dOptions options;
    options.verify = true;
    Mesh3dDecoder decoder({data, size}, options);
    while (decoder.next_frame()) {
    }
  } catch (const Error&) {
  }
  return 0;
}
