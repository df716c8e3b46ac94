// libFuzzer target: the 2D mesh decoder, both motion methods, with §9 output.
#include <cstddef>
#include <cstdint>

#include "common/error.h"
#include "decoder/decoder.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace m4mesh;
  for (MotionMethod method : {MotionMethod::kMethod2, MotionMethod::kMethod1}) {
    DecoderOptions options;
    options.method = method;
    try {
      decode_to_text({data, size}, options, {});
    } catch (const Error&) {
    }
  }
  return 0;
}
