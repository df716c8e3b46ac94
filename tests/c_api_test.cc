// The C interface (api/m4mesh.h) through the shared library: both suites
// decoded with their bytes pushed a few at a time, every rejected stream's
// error (kind, element, frame, bit) as `m4mesh conform` expects it, a
// progressive stream's refinements, encoding, and misuse.
#include "api/m4mesh.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "common/atomic_file.h"
#include "common/md5.h"
#include "conformance/manifest.h"

namespace m4mesh {
namespace {

const std::string kSuite2d = M4MESH_CONFORMANCE_DIR;
const std::string kSuite3d = std::string(M4MESH_CONFORMANCE_DIR) + "/mesh3d";

struct Outcome {
  std::string md5;  // of the frames, or of the planes' nodes and triangles
  int64_t pieces = 0;
  m4mesh_error error{};
};

Outcome decode3d(const std::vector<uint8_t>& stream, size_t chunk) {
  Outcome out;
  Md5 md5;
  m4mesh_decoder3d* d = m4mesh_decoder3d_new();
  std::vector<float> positions;
  auto pull = [&] {
    m4mesh_header3d h;
    if (const m4mesh_status status = m4mesh_decoder3d_header(d, &h); status != M4MESH_OK) return status;
    positions.resize(3 * size_t{h.vertices});
    uint32_t index = 0;
    m4mesh_status status;
    while ((status = m4mesh_decoder3d_next_frame(d, &index, positions.data(), positions.size())) == M4MESH_OK) {
      EXPECT_EQ(index, out.pieces++);
      md5.update(positions.data(), positions.size() * sizeof(float));
    }
    return status;
  };
  m4mesh_status status = M4MESH_OK;
  for (size_t at = 0; at < stream.size() && status != M4MESH_ERROR; at += chunk) {
    status = m4mesh_decoder3d_push(d, stream.data() + at, std::min(chunk, stream.size() - at));
    if (status != M4MESH_ERROR) status = pull();
  }
  if (status != M4MESH_ERROR) status = m4mesh_decoder3d_finish(d);
  if (status != M4MESH_ERROR) status = pull();
  EXPECT_TRUE(status == M4MESH_ERROR || status == M4MESH_END);
  out.error = *m4mesh_decoder3d_error(d);
  out.md5 = md5.hex_digest();
  m4mesh_decoder3d_free(d);
  return out;
}

Outcome decode2d(const std::vector<uint8_t>& stream, size_t chunk, int method) {
  Outcome out;
  Md5 md5;
  m4mesh_decoder2d* d = m4mesh_decoder2d_new(method);
  auto pull = [&] {
    m4mesh_plane2d p;
    m4mesh_status status;
    while ((status = m4mesh_decoder2d_next_plane(d, &p)) == M4MESH_OK) {
      EXPECT_EQ(p.index, out.pieces++);
      md5.update(p.nodes, 2 * sizeof(int32_t) * p.node_count);
      md5.update(p.triangles, 3 * sizeof(uint32_t) * p.triangle_count);
    }
    return status;
  };
  m4mesh_status status = M4MESH_OK;
  for (size_t at = 0; at < stream.size() && status != M4MESH_ERROR; at += chunk) {
    status = m4mesh_decoder2d_push(d, stream.data() + at, std::min(chunk, stream.size() - at));
    if (status != M4MESH_ERROR) status = pull();
  }
  if (status != M4MESH_ERROR) status = m4mesh_decoder2d_finish(d);
  if (status != M4MESH_ERROR) status = pull();
  EXPECT_TRUE(status == M4MESH_ERROR || status == M4MESH_END);
  out.error = *m4mesh_decoder2d_error(d);
  out.md5 = md5.hex_digest();
  m4mesh_decoder2d_free(d);
  return out;
}

void expect_error(const ManifestEntry& e, const m4mesh_error& error) {
  EXPECT_STREQ(error.kind_name, e.error_kind.c_str()) << e.id << ": " << error.message;
  EXPECT_STREQ(error.element, e.error_element.c_str()) << e.id << ": " << error.message;
  EXPECT_EQ(error.frame, e.error_plane) << e.id << ": " << error.message;
  EXPECT_EQ(error.bit_offset, e.error_offset) << e.id << ": " << error.message;
}

TEST(CApi, Versions) {
  EXPECT_STREQ(m4mesh_version(), "1.0.0");
  EXPECT_EQ(m4mesh_format_version(), 16u);
}

TEST(CApi, The3dSuiteDecodesAsItArrives) {
  for (const ManifestEntry& e : read_manifest(kSuite3d + "/manifest.json").entries) {
    const std::vector<uint8_t> stream = read_file(kSuite3d + "/" + e.file);
    for (const size_t chunk : {size_t{61}, stream.size() + 1}) {
      const Outcome out = decode3d(stream, chunk);
      if (!e.valid) {
        expect_error(e, out.error);
        continue;
      }
      EXPECT_EQ(out.error.kind, M4MESH_ERROR_NONE) << e.id << ": " << out.error.message;
      EXPECT_EQ(out.md5, e.decoded_md5) << e.id;
      EXPECT_EQ(out.pieces, e.planes) << e.id;
    }
  }
}

TEST(CApi, The2dSuiteDecodesAsItArrives) {
  for (const ManifestEntry& e : read_manifest(kSuite2d + "/manifest.json").entries) {
    const std::vector<uint8_t> stream = read_file(kSuite2d + "/" + e.file);
    const Outcome whole = decode2d(stream, stream.size() + 1, e.method), bytewise = decode2d(stream, 1, e.method);
    if (!e.valid) {
      expect_error(e, whole.error);
      expect_error(e, bytewise.error);
      continue;
    }
    EXPECT_EQ(whole.error.kind, M4MESH_ERROR_NONE) << e.id << ": " << whole.error.message;
    EXPECT_EQ(whole.pieces, e.planes) << e.id;
    EXPECT_EQ(bytewise.md5, whole.md5) << e.id;
    EXPECT_EQ(bytewise.pieces, whole.pieces) << e.id;
  }
}

// A progressive stream's frames refine unit by unit, then come out final.
TEST(CApi, AProgressiveStreamRefinesItsFrames) {
  const std::vector<uint8_t> stream = read_file(kSuite3d + "/streams/cpca-01-wpt.m4m");
  m4mesh_decoder3d* d = m4mesh_decoder3d_new();
  std::vector<float> frame;
  size_t refined = 0, last_units = 0;
  for (size_t at = 0; at < stream.size(); at += 200) {
    ASSERT_EQ(m4mesh_decoder3d_push(d, stream.data() + at, std::min<size_t>(200, stream.size() - at)), M4MESH_OK);
    m4mesh_header3d h;
    if (m4mesh_decoder3d_header(d, &h) != M4MESH_OK) continue;
    ASSERT_EQ(h.progressive, 1);
    frame.resize(3 * size_t{h.vertices});
    size_t units = 0;
    if (m4mesh_decoder3d_peek_frame(d, h.frames - 1, frame.data(), frame.size(), &units) != M4MESH_OK) continue;
    EXPECT_EQ(units, m4mesh_decoder3d_units(d));
    if (units > last_units) ++refined, last_units = units;
  }
  EXPECT_GT(refined, 3u);
  ASSERT_EQ(m4mesh_decoder3d_finish(d), M4MESH_OK);
  uint32_t index = 0, frames = 0;
  while (m4mesh_decoder3d_next_frame(d, &index, frame.data(), frame.size()) == M4MESH_OK) ++frames;
  EXPECT_GT(frames, 0u);
  m4mesh_decoder3d_free(d);
}

TEST(CApi, EncodesAndDecodesBack) {
  std::vector<float> positions;
  for (int f = 0; f < 5; ++f)
    for (int v = 0; v < 4; ++v) positions.insert(positions.end(), {float(v % 2), float(v / 2), 0.1f * float(f * v)});
  const uint32_t faces[] = {0, 1, 3, 0, 3, 2};
  m4mesh_encode_options o;
  m4mesh_encode_options_init(&o);
  const char* const options[] = {"bits", "14", nullptr};
  o.codec_options = options;
  uint8_t* bytes = nullptr;
  size_t size = 0;
  m4mesh_error error;
  ASSERT_EQ(m4mesh_encode3d(positions.data(), 5, 4, faces, 2, &o, &bytes, &size, &error), M4MESH_OK) << error.message;
  const Outcome out = decode3d(std::vector<uint8_t>(bytes, bytes + size), 7);
  m4mesh_free(bytes);
  EXPECT_EQ(out.error.kind, M4MESH_ERROR_NONE) << out.error.message;
  EXPECT_EQ(out.pieces, 5);

  o.codec = "lcc";
  const char* const unknown[] = {"no-such-option", "1", nullptr};
  o.codec_options = unknown;
  EXPECT_EQ(m4mesh_encode3d(positions.data(), 5, 4, faces, 2, &o, &bytes, &size, &error), M4MESH_ERROR);
  EXPECT_EQ(error.kind, M4MESH_ERROR_USAGE) << error.message;
  o.codec = "auto";
  o.codec_options = nullptr;
  EXPECT_EQ(m4mesh_encode3d(positions.data(), 5, 4, faces, 2, &o, &bytes, &size, &error), M4MESH_ERROR);
  EXPECT_EQ(error.kind, M4MESH_ERROR_USAGE) << error.message;  // auto needs a target
}

// The frames of a 3D stream, through the interface.
std::vector<float> decoded_positions(const uint8_t* bytes, size_t size) {
  m4mesh_decoder3d* d = m4mesh_decoder3d_new();
  EXPECT_EQ(m4mesh_decoder3d_push(d, bytes, size), M4MESH_OK);
  EXPECT_EQ(m4mesh_decoder3d_finish(d), M4MESH_OK);
  m4mesh_header3d header;
  EXPECT_EQ(m4mesh_decoder3d_header(d, &header), M4MESH_OK);
  std::vector<float> all, frame(3 * size_t{header.vertices});
  uint32_t index = 0;
  while (m4mesh_decoder3d_next_frame(d, &index, frame.data(), frame.size()) == M4MESH_OK) all.insert(all.end(), frame.begin(), frame.end());
  m4mesh_decoder3d_free(d);
  return all;
}

// "max-error" among the codec options is the quality target: no decoded vertex farther than it from its original;
// a looser one gives a smaller stream; a value that is no number, or one out of range, is a usage error.
TEST(CApi, MaxErrorIsAQualityTarget) {
  std::vector<float> positions;
  for (int f = 0; f < 6; ++f)
    for (int v = 0; v < 16; ++v) positions.insert(positions.end(), {float(v % 4), float(v / 4), 0.37f * std::sin(0.5f * float(f + v))});
  std::vector<uint32_t> faces;
  for (uint32_t y = 0; y < 3; ++y)
    for (uint32_t x = 0; x < 3; ++x) faces.insert(faces.end(), {4 * y + x, 4 * y + x + 1, 4 * y + x + 5, 4 * y + x, 4 * y + x + 5, 4 * y + x + 4});
  m4mesh_encode_options o;
  m4mesh_encode_options_init(&o);
  m4mesh_error error;
  size_t sizes[2] = {0, 0};
  const char* const targets[2] = {"0.002", "0.05"};
  for (int t = 0; t < 2; ++t) {
    const char* const options[] = {"max-error", targets[t], nullptr};
    o.codec_options = options;
    uint8_t* bytes = nullptr;
    ASSERT_EQ(m4mesh_encode3d(positions.data(), 6, 16, faces.data(), 18, &o, &bytes, &sizes[t], &error), M4MESH_OK) << error.message;
    const std::vector<float> decoded = decoded_positions(bytes, sizes[t]);
    m4mesh_free(bytes);
    ASSERT_EQ(decoded.size(), positions.size());
    double farthest = 0;
    for (size_t i = 0; i < positions.size(); i += 3)
      farthest = std::max(farthest, std::hypot(double{decoded[i]} - positions[i], double{decoded[i + 1]} - positions[i + 1], double{decoded[i + 2]} - positions[i + 2]));
    EXPECT_LE(farthest, std::stod(targets[t])) << targets[t];
  }
  EXPECT_LT(sizes[1], sizes[0]);
  for (const char* wrong : {"far", "-1", "0", ""}) {
    const char* const options[] = {"max-error", wrong, nullptr};
    o.codec_options = options;
    uint8_t* bytes = nullptr;
    size_t size = 0;
    EXPECT_EQ(m4mesh_encode3d(positions.data(), 6, 16, faces.data(), 18, &o, &bytes, &size, &error), M4MESH_ERROR) << wrong;
    EXPECT_EQ(error.kind, M4MESH_ERROR_USAGE) << wrong << ": " << error.message;
  }
}

// Bytes that cannot begin a stream fail at the push that completes four of
// them, not at finish after everything has been buffered.
TEST(CApi, BytesThatAreNoStreamFailAtOnce) {
  const std::vector<uint8_t> ones(size_t{1} << 20, 0xFF);
  m4mesh_decoder3d* d = m4mesh_decoder3d_new();
  EXPECT_EQ(m4mesh_decoder3d_push(d, ones.data(), 3), M4MESH_OK);  // not four bytes yet
  EXPECT_EQ(m4mesh_decoder3d_push(d, ones.data(), ones.size()), M4MESH_ERROR);
  EXPECT_STREQ(m4mesh_decoder3d_error(d)->kind_name, "missing-start-code") << m4mesh_decoder3d_error(d)->message;
  EXPECT_STREQ(m4mesh_decoder3d_error(d)->element, "mesh3d_object_start_code");
  EXPECT_EQ(m4mesh_decoder3d_error(d)->bit_offset, 0);
  m4mesh_decoder3d_free(d);
  // A 2D stream's start is no 3D stream either.
  const std::vector<uint8_t> two_d = read_file(kSuite2d + "/streams/p01-hand-3x3.m4m");
  d = m4mesh_decoder3d_new();
  EXPECT_EQ(m4mesh_decoder3d_push(d, two_d.data(), 4), M4MESH_ERROR);
  m4mesh_decoder3d_free(d);
}

// A stream pushed a byte at a time decodes as it does whole (start codes straddling pushes).
TEST(CApi, AStreamPushedByteByByte) {
  for (const char* id : {"bfs3d-01-average", "cpca-01-wpt", "hash-01-groups"}) {
    const std::vector<uint8_t> stream = read_file(kSuite3d + "/streams/" + id + ".m4m");
    const Outcome bytewise = decode3d(stream, 1), whole = decode3d(stream, stream.size());
    EXPECT_EQ(bytewise.error.kind, M4MESH_ERROR_NONE) << id << ": " << bytewise.error.message;
    EXPECT_EQ(bytewise.md5, whole.md5) << id;
    EXPECT_EQ(bytewise.pieces, whole.pieces) << id;
  }
}

TEST(CApi, MisuseIsAnErrorNotACrash) {
  m4mesh_decoder3d* d = m4mesh_decoder3d_new();
  EXPECT_EQ(m4mesh_decoder3d_finish(d), M4MESH_ERROR);  // no bytes at all
  EXPECT_EQ(m4mesh_decoder3d_error(d)->kind, M4MESH_ERROR_TRUNCATED);
  EXPECT_EQ(m4mesh_decoder3d_push(d, nullptr, 0), M4MESH_ERROR);  // failed for good
  m4mesh_decoder3d_free(d);

  const std::vector<uint8_t> stream = read_file(kSuite3d + "/streams/bfs3d-01-average.m4m");
  d = m4mesh_decoder3d_new();
  ASSERT_EQ(m4mesh_decoder3d_push(d, stream.data(), stream.size()), M4MESH_OK);
  ASSERT_EQ(m4mesh_decoder3d_finish(d), M4MESH_OK);
  float one[3];
  uint32_t index = 0;
  EXPECT_EQ(m4mesh_decoder3d_next_frame(d, &index, one, 3), M4MESH_ERROR);  // too small for the frame
  EXPECT_EQ(m4mesh_decoder3d_error(d)->kind, M4MESH_ERROR_USAGE);
  m4mesh_decoder3d_free(d);

  EXPECT_EQ(m4mesh_decoder3d_push(nullptr, stream.data(), 1), M4MESH_ERROR);
  EXPECT_EQ(m4mesh_decoder3d_error(nullptr)->kind, M4MESH_ERROR_USAGE);
  m4mesh_decoder3d_free(nullptr);
  EXPECT_EQ(m4mesh_decoder2d_new(3), nullptr);
  EXPECT_EQ(m4mesh_encode3d(nullptr, 2, 2, nullptr, 0, nullptr, nullptr, nullptr, nullptr), M4MESH_ERROR);
}

}  // namespace
}  // namespace m4mesh
