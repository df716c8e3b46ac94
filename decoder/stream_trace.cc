#include "decoder/stream_trace.h"

#include "decoder/mesh3d/container_decoder.h"
#include "syntax/mesh3d/container.h"
#include "syntax/mesh_object.h"

namespace m4mesh {

void trace_stream(std::span<const uint8_t> stream, std::ostream& out, const TraceSelection& selection) {
  Trace trace(out);
  if (selection.part) trace.only_part(*selection.part);
  if (!selection.symbols) trace.without_symbols();
  const auto before_part = [&](int64_t taken) { return !selection.part || taken <= *selection.part; };
  if (is_mesh3d_stream(stream)) {
    Decode3dOptions options;
    options.trace = &trace;
    Mesh3dDecoder decoder(stream, options);
    while (before_part(static_cast<int64_t>(decoder.units_taken())) && decoder.next_unit()) {
    }
    return;
  }
  syntax::MeshObjectReader reader(stream, &trace);
  MeshObjectPlane plane;
  while (before_part(reader.planes_read()) && reader.next(plane)) {
  }
}

}  // namespace m4mesh
