// The base mesh unit's data (docs/container3d.md), for every codec that sends one.
#include "codecs3d/codec_decoder.h"
#include "mesh3d/quantization.h"

namespace m4mesh {

BaseMesh read_base_mesh(syntax::ReadIO& io, const ObjectHeader& header) {
  BaseMeshData data;
  syntax::describe(io, data);
  BaseMesh base;
  try {
    base = decode_base_mesh(data.draco_mesh, header.vertex_count, header.face_count);
  } catch (const Error& e) {
    io.fail(ErrorKind::kInput, "base_mesh", e.message());
  }
  for (const IntPoint3& q : base.positions)
    for (int32_t c : q)
      if (c > kMaxQuantized || c < -kMaxQuantized) io.fail(ErrorKind::kOutOfRange, "base_mesh", "a position leaves ±2^26 grid steps");
  return base;
}

}  // namespace m4mesh
