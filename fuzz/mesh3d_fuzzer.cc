// libFuzzer target: the 3D container, the base mesh and every registered
// 3D codec's decoder, plain, from an intra refresh (seek), traced, and in
// the checker's carry-on mode.
#include <cstddef>
#include <cstdint>
#include <sstream>

#include "common/error.h"
#include "conformance/checker.h"
#include "decoder/mesh3d/container_decoder.h"
#include "fuzz/budget.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace m4mesh;
  const std::span<const uint8_t> stream(data, size);
  if (fuzz::declares_more_than_budget(stream)) return -1;  // -1: not added to the corpus
  try {
    Mesh3dDecoder decoder(stream);
    while (decoder.next_frame()) {
    }
  } catch (const Error&) {
  }
  try {
    Mesh3dDecoder decoder(stream);
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
