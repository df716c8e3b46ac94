// libFuzzer target: the C interface (api/m4mesh.h) as an application
// drives it. The input's last byte sets the pieces its bytes are pushed in
// (1 … 256 bytes); the rest is a 2D or a 3D stream, decoded as it arrives,
// its frames pulled and a progressive stream's refinements peeked at
// after every piece, then finished.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "api/m4mesh.h"
#include "fuzz/budget.h"
#include "syntax/mesh3d/container.h"

namespace {

void decode3d(const uint8_t* data, size_t size, size_t piece) {
  m4mesh_decoder3d* d = m4mesh_decoder3d_new();
  std::vector<float> positions;
  std::vector<uint32_t> faces;
  auto pull = [&] {
    m4mesh_header3d h;
    if (m4mesh_decoder3d_header(d, &h) != M4MESH_OK) return;
    positions.resize(3 * size_t{h.vertices});
    faces.resize(3 * size_t{h.faces});
    m4mesh_decoder3d_faces(d, faces.data(), faces.size());
    size_t units = 0;
    if (h.frames > 0) m4mesh_decoder3d_peek_frame(d, h.frames - 1, positions.data(), positions.size(), &units);
    uint32_t index = 0;
    while (m4mesh_decoder3d_next_frame(d, &index, positions.data(), positions.size()) == M4MESH_OK) {
    }
  };
  for (size_t at = 0; at < size; at += piece) {
    if (m4mesh_decoder3d_push(d, data + at, std::min(piece, size - at)) != M4MESH_OK) break;
    pull();
  }
  if (m4mesh_decoder3d_finish(d) == M4MESH_OK) pull();
  m4mesh_decoder3d_free(d);
}

void decode2d(const uint8_t* data, size_t size, size_t piece) {
  m4mesh_decoder2d* d = m4mesh_decoder2d_new(2);
  m4mesh_plane2d plane;
  for (size_t at = 0; at < size; at += piece) {
    if (m4mesh_decoder2d_push(d, data + at, std::min(piece, size - at)) != M4MESH_OK) break;
    while (m4mesh_decoder2d_next_plane(d, &plane) == M4MESH_OK) {
    }
  }
  if (m4mesh_decoder2d_finish(d) == M4MESH_OK)
    while (m4mesh_decoder2d_next_plane(d, &plane) == M4MESH_OK) {
    }
  m4mesh_decoder2d_free(d);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return -1;
  const size_t piece = size_t{data[size - 1]} + 1;
  const std::span<const uint8_t> stream(data, size - 1);
  if (m4mesh::is_mesh3d_stream(stream)) {
    if (m4mesh::fuzz::declares_more_than_budget(stream)) return -1;
    decode3d(stream.data(), stream.size(), piece);
  } else {
    decode2d(stream.data(), stream.size(), piece);
  }
  return 0;
}
