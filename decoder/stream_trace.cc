#include "decoder/stream_trace.h"

#include <algorithm>

#include "codecs3d/registry.h"
#include "decoder/mesh3d/container_decoder.h"
#include "syntax/mesh3d/container.h"
#include "syntax/mesh3d/cpca_wpt.h"
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
    // The object's part runs through the first unit: a header's section may be read there (cpca-wpt's map by neighbours).
    const int64_t last = selection.part ? std::max<int64_t>(*selection.part, 0) : 0;
    while ((!selection.part || static_cast<int64_t>(decoder.units_taken()) <= last) && decoder.next_unit()) {
    }
    return;
  }
  syntax::MeshObjectReader reader(stream, &trace);
  MeshObjectPlane plane;
  while (before_part(reader.planes_read()) && reader.next(plane)) {
  }
}

std::vector<std::string> unit_labels3d(std::span<const uint8_t> stream) {
  const ContainerParts parts = split_container(stream);
  ObjectHeader object;
  {
    BitReader reader(parts.object_payload.data(), parts.object_payload.size());
    syntax::ReadIO io(reader);
    syntax::describe(io, object);
  }
  std::vector<std::string> labels;
  for (const ContainerUnit& unit : parts.units) {
    BitReader reader(unit.payload.data(), unit.payload.size());
    syntax::ReadIO io(reader);
    try {
      UnitHeader header;
      syntax::describe(io, header);
      std::string label = unit_type_name(header.type());
      if (header.type() == UnitType::kRefinement && object.codec_id == kCpcaWptId) {
        CpcaRefinement refinement;
        syntax::describe(io, refinement);
        label += refinement.kind == kCpcaGroup
                     ? ", group of " + std::to_string(refinement.group.size())
                     : ", cluster " + std::to_string(refinement.cluster) + " " + cpca_unit_kind_name(refinement.kind);
      } else if (header.type() != UnitType::kRefinement) {
        label += ", frame " + std::to_string(header.frame_index);
      }
      labels.push_back(std::move(label));
    } catch (const Error&) {
      labels.push_back("unreadable");
    }
  }
  return labels;
}

}  // namespace m4mesh
