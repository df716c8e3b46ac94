// Encodes a waving sheet with each codec through m4mesh's C interface,
// decodes every stream back as it arrives, and checks what comes out:
// the frames, their error, and a damaged stream's error. Exits 1 on the
// first failure.
#include <m4mesh.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace {

constexpr uint32_t kSide = 16, kFrames = 24;

int failed(const std::string& what) {
  std::fprintf(stderr, "encode_decode: %s\n", what.c_str());
  std::exit(1);
}

struct Decoded {
  std::vector<float> frames;  // frame after frame
  m4mesh_header3d header{};
  m4mesh_error error{};
};

Decoded decode(const std::vector<uint8_t>& stream, size_t chunk) {
  Decoded out;
  m4mesh_decoder3d* decoder = m4mesh_decoder3d_new();
  std::vector<float> positions;
  auto pull = [&] {
    if (m4mesh_decoder3d_header(decoder, &out.header) != M4MESH_OK) return M4MESH_AGAIN;
    positions.resize(3 * size_t{out.header.vertices});
    uint32_t index = 0;
    m4mesh_status status;
    while ((status = m4mesh_decoder3d_next_frame(decoder, &index, positions.data(), positions.size())) == M4MESH_OK)
      out.frames.insert(out.frames.end(), positions.begin(), positions.end());
    return status;
  };
  m4mesh_status status = M4MESH_OK;
  for (size_t at = 0; at < stream.size() && status != M4MESH_ERROR; at += chunk) {
    status = m4mesh_decoder3d_push(decoder, stream.data() + at, std::min(chunk, stream.size() - at));
    if (status != M4MESH_ERROR) status = pull();
  }
  if (status != M4MESH_ERROR && m4mesh_decoder3d_finish(decoder) == M4MESH_OK) pull();
  out.error = *m4mesh_decoder3d_error(decoder);
  m4mesh_decoder3d_free(decoder);
  return out;
}

}  // namespace

int main() {
  std::printf("m4mesh %s, format version %u\n", m4mesh_version(), m4mesh_format_version());
  std::vector<float> sheet;
  for (uint32_t f = 0; f < kFrames; ++f)
    for (uint32_t y = 0; y < kSide; ++y)
      for (uint32_t x = 0; x < kSide; ++x)
        sheet.insert(sheet.end(), {float(x), float(y), std::sin(0.4f * float(x) + 0.3f * float(f)) * float(y) / 8});
  std::vector<uint32_t> faces;
  for (uint32_t y = 0; y + 1 < kSide; ++y)
    for (uint32_t x = 0; x + 1 < kSide; ++x) {
      const uint32_t a = y * kSide + x;
      faces.insert(faces.end(), {a, a + 1, a + kSide + 1, a, a + kSide + 1, a + kSide});
    }
  const uint32_t vertices = kSide * kSide, face_count = uint32_t(faces.size() / 3);

  struct Trial {
    const char* codec;
    double target_kg;
  };
  for (const Trial& trial : {Trial{"bfs3d", 0}, Trial{"affine-octree", 0}, Trial{"lcc", 0}, Trial{"cpca-wpt", 0.5}, Trial{"auto", 0.5}}) {
    m4mesh_encode_options options;
    m4mesh_encode_options_init(&options);
    options.codec = trial.codec;
    options.target_kg = trial.target_kg;
    uint8_t* bytes = nullptr;
    size_t size = 0;
    m4mesh_error error;
    if (m4mesh_encode3d(sheet.data(), kFrames, vertices, faces.data(), face_count, &options, &bytes, &size, &error) != M4MESH_OK)
      failed(std::string(trial.codec) + ": " + error.message);
    const std::vector<uint8_t> stream(bytes, bytes + size);
    m4mesh_free(bytes);
    const Decoded d = decode(stream, 101);
    if (d.error.kind != M4MESH_ERROR_NONE) failed(std::string(trial.codec) + ": decoding: " + d.error.message);
    if (d.frames.size() != sheet.size() || d.header.frames != kFrames || d.header.vertices != vertices || d.header.faces != face_count)
      failed(std::string(trial.codec) + ": " + std::to_string(d.frames.size() / 3 / vertices) + " frames decoded");
    double largest = 0;
    for (size_t i = 0; i < sheet.size(); ++i) largest = std::max(largest, double(std::fabs(d.frames[i] - sheet[i])));
    if (largest > 0.5) failed(std::string(trial.codec) + ": a vertex " + std::to_string(largest) + " away");
    std::printf("%-13s %6zu bytes (%s), largest error %.4f\n", trial.codec, stream.size(), d.header.codec, largest);

    std::vector<uint8_t> damaged = stream;
    damaged[4] ^= 0xFF;  // the object header's version
    const Decoded bad = decode(damaged, 101);
    if (bad.error.kind != M4MESH_ERROR_RESERVED_VALUE || std::string(bad.error.element) != "version")
      failed(std::string(trial.codec) + ": a damaged version gave '" + bad.error.message + "'");
  }
  m4mesh_error error;
  uint8_t* bytes = nullptr;
  size_t size = 0;
  const uint32_t wrong_face[3] = {0, 1, vertices};
  if (m4mesh_encode3d(sheet.data(), kFrames, vertices, wrong_face, 1, nullptr, &bytes, &size, &error) != M4MESH_ERROR ||
      error.kind != M4MESH_ERROR_USAGE)
    failed("a face naming a vertex beyond the last was accepted");
  std::printf("%s\n", error.message);
  return 0;
}
