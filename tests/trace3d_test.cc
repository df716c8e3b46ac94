// The decoder's trace of a 3D stream equals the trace its encoder printed
// while writing it: both directions run the same descriptions.
#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>

#include "conformance/suite3d/suite3d.h"
#include "decoder/mesh3d/container_decoder.h"
#include "encoder/mesh3d/container_encoder.h"
#include "tests/test_util.h"

namespace m4mesh {
namespace {

namespace fs = std::filesystem;

std::string decoder_trace(const std::vector<uint8_t>& stream) {
  std::ostringstream text;
  trace_mesh3d(stream, text);
  return text.str();
}

// The first line where two traces part, for the failure message.
std::string first_difference(const std::string& a, const std::string& b) {
  std::istringstream x(a), y(b);
  std::string p, q;
  for (int line = 1;; ++line) {
    const bool more_x = static_cast<bool>(std::getline(x, p)), more_y = static_cast<bool>(std::getline(y, q));
    if (!more_x && !more_y) return "none";
    if (p != q || more_x != more_y) return "line " + std::to_string(line) + ":\n  encoder: " + p + "\n  decoder: " + q;
  }
}

TEST(Trace3d, EveryConformanceStreamTracesAlikeInBothDirections) {
  size_t traced = 0;
  for (const SuiteCase& c : build_suite3d(true)) {
    if (!c.valid || c.written) continue;
    ASSERT_FALSE(c.encoder_trace.empty()) << c.id;
    const std::string decoded = decoder_trace(c.stream);
    EXPECT_EQ(c.encoder_trace, decoded) << c.id << ": first difference at " << first_difference(c.encoder_trace, decoded);
    ++traced;
  }
  EXPECT_GE(traced, 9u);
}

TEST(Trace3d, EveryElementKindIsTraced) {
  const std::vector<SuiteCase> suite = build_suite3d(true);
  std::string all;
  for (const SuiteCase& c : suite) all += c.encoder_trace;
  for (const char* element : {"mesh3d_object_start_code", "codec_id", "unit_type", "frame_index", "vertex_order", "gate_new_vertex", "gate_candidate", "position_prefix", "frame_md5", "arithmetic_bytes_x",
                              "raw_bytes_z", "bins_x:0", "raw_z:0", "motion_nonzero", "motion_prefix", "motion_sign", "motion_top", "split_flag",
                              "direct_flag", "matrix_nonzero", "direct_nonzero", "mesh_object_end_code"})
    EXPECT_NE(all.find(element), std::string::npos) << element;
}

// The paper's sequences, a few frames of each (the whole of them: tests/cli_test.sh).
TEST(Trace3d, RealSequencesTraceAlike) {
  const fs::path data = fs::path(M4MESH_SOURCE_DIR) / ".." / "shared" / "data";
  for (const char* name : {"horse-gallop", "pcow"}) {
    if (!fs::exists(data / name)) GTEST_SKIP() << "../shared/data/" << name << " is absent";
    MeshSequence s = load_sequence((data / name).string());
    s.frames.resize(3);
    for (const char* codec : {"bfs3d", "affine-octree"}) {
      std::ostringstream text;
      Trace trace(text);
      Encode3dOptions options;
      options.codec = codec;
      options.trace = &trace;
      const std::vector<uint8_t> stream = encode_mesh3d(s, options).stream;
      const std::string decoded = decoder_trace(stream);
      EXPECT_EQ(text.str(), decoded) << name << " " << codec << ": " << first_difference(text.str(), decoded);
    }
  }
}

}  // namespace
}  // namespace m4mesh
