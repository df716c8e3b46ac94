// libFuzzer target: the 2D mesh decoder. The input's length picks the
// motion-vector method, so both are reached without decoding twice.
#include <cstddef>
#include <cstdint>

#include "common/error.h"
#include "decoder/mesh_object_decoder.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace m4mesh;
  DecoderOptions options;
  options.method = size % 2 ? MotionMethod::kMethod1 : MotionMethod::kMethod2;
  try {
    Decoder decoder({data, size}, options);
    while (decoder.next())
      if (decoder.info().intra) decoder.triangles();
  } catch (const Error&) {
  }
  return 0;
}
