// Inputs the fuzzers once broke m4mesh with (a crash, or a timeout: a vertex in 20,000
// faces once made the parallelograms quadratic): each must now fail cleanly (or decode).
#include <gtest/gtest.h>

#include <filesystem>

#include "common/atomic_file.h"
#include "conformance/checker.h"
#include "decoder/mesh3d/container_decoder.h"
#include "decoder/mesh_object_decoder.h"
#include "encoder/mesh_object_encoder.h"
#include "mesh/decoded_text.h"

namespace m4mesh {
namespace {

TEST(FuzzRegressions, EveryReproducerFailsCleanly) {
  const std::filesystem::path folder = std::filesystem::path(M4MESH_SOURCE_DIR) / "tests" / "fuzz_regressions";
  int replayed = 0;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    const std::vector<uint8_t> bytes = read_file(entry.path().string());
    if (entry.path().extension() == ".txt") {
      try {
        encode(parse_decoded_text({reinterpret_cast<const char*>(bytes.data()), bytes.size()}, entry.path().string()));
      } catch (const Error&) {
      }
    } else if (is_mesh3d_stream(bytes)) {
      try {
        decode_mesh3d(bytes);
      } catch (const Error&) {
      }
      check_mesh3d(bytes);
    } else {
      try {
        decode_to_text(bytes, {}, {});
      } catch (const Error&) {
      }
      check_stream(bytes);
    }
    ++replayed;
  }
  EXPECT_GE(replayed, 1);
}

}  // namespace
}  // namespace m4mesh
