// libFuzzer target: encoder input in the §9 text format, then encoding it.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "common/error.h"
#include "encoder/mesh_object_encoder.h"
#include "mesh/decoded_text.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace m4mesh;
  try {
    const std::vector<MeshPlane> planes = parse_decoded_text({reinterpret_cast<const char*>(data), size}, "fuzz");
    encode(planes);
  } catch (const Error&) {
  }
  return 0;
}
