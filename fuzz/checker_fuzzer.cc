// libFuzzer target: `m4mesh check`, which reads past errors and resynchronises.
#include <cstddef>
#include <cstdint>

#include "conformance/checker.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  m4mesh::check_stream({data, size});
  return 0;
}
