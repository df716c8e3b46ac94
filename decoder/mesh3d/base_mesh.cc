// The base mesh unit's data (docs/base_mesh.md), for every codec that sends one.
#include <bit>
#include <numeric>

#include "codecs3d/codec_decoder.h"
#include "syntax/mesh3d/entropy_io.h"

namespace m4mesh {

namespace {

// Kept out of read_base_mesh, whose two inlined copies (traced or not)
// made one function that WebAssembly engines compile whole when it gets
// hot: 4 MB more of Node's peak memory.
template <class IO>
[[gnu::noinline]] BaseMesh read_symbols(IO& symbols, const BaseMeshData& data, const ObjectHeader& header) {
  syntax::BaseMeshContexts contexts;
  const uint32_t traversal_faces = header.face_count - data.loose_face_count;
  GateTraversal traversal(traversal_faces);
  struct NoOracle {};
  describe_traversal(symbols, contexts, traversal, header.vertex_count, traversal_faces,
                     static_cast<NoOracle*>(nullptr));
  BaseMesh base;
  base.faces = traversal.faces();
  // Loose faces are raw bits: the raw section bounds their count before any allocation.
  if (uint64_t{data.loose_face_count} * 3 * std::bit_width(header.vertex_count - 1) > 8 * uint64_t{data.raw.size()})
    symbols.fail(ErrorKind::kTruncated, "loose_vertex", "the raw bit section cannot hold loose_face_count faces");
  std::vector<Triangle> loose(data.loose_face_count);
  describe_loose_faces(symbols, header.vertex_count, std::span<Triangle>(loose));
  base.faces.insert(base.faces.end(), loose.begin(), loose.end());
  std::vector<uint32_t> input_of(header.vertex_count);
  describe_vertex_order(symbols, contexts, data.vertex_order, traversal.parents(), input_of);
  base.positions.resize(header.vertex_count);
  describe_positions(symbols, contexts, PositionCoding(base.faces, header.vertex_count), data.position_blend, base.positions);
  symbols.finish("base_mesh");
  if (data.vertex_order == kVertexOrderCoding) {
    base.coding_order.resize(header.vertex_count);
    std::iota(base.coding_order.begin(), base.coding_order.end(), 0u);
  } else {
    base.coding_order = input_of;
    for (Triangle& t : base.faces)
      for (NodeIndex& v : t.v) v = input_of[v];
    std::vector<IntPoint3> coded = std::move(base.positions);
    base.positions.resize(coded.size());
    for (uint32_t i = 0; i < coded.size(); ++i) base.positions[input_of[i]] = coded[i];
  }
  return base;
}

}  // namespace

BaseMesh read_base_mesh(syntax::ReadIO& io, const ObjectHeader& header, Trace* trace) {
  BaseMeshData data;
  io.note_start("base_mesh", io.reader().position());  // rules about the whole base mesh are placed at its start
  syntax::describe(io, data);
  if (data.loose_face_count > header.face_count)
    io.fail(ErrorKind::kOutOfRange, "loose_face_count", "more loose faces than the object's face_count");
  const uint8_t* payload = io.reader().data();
  const syntax::SectionPlace place{"bins", "raw", 8 * static_cast<uint64_t>(data.bins.data() - payload),
                                   8 * static_cast<uint64_t>(data.raw.data() - payload), io.plane()};
  if (trace) {
    syntax::EntropyReadIO<true> symbols(data.bins, data.raw, place, trace);
    return read_symbols(symbols, data, header);
  }
  syntax::EntropyReadIO<false> symbols(data.bins, data.raw, place);
  return read_symbols(symbols, data, header);
}

}  // namespace m4mesh
