#include "cli/inspect.h"

#include <cstdio>
#include <iostream>
#include <map>

#include "cli/console.h"
#include "cli/sequence_files.h"
#include "codecs3d/registry.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "conformance/checker.h"
#include "decoder/mesh3d/container_decoder.h"
#include "decoder/stream_trace.h"
#include "syntax/mesh3d/base_mesh.h"
#include "syntax/mesh3d/container.h"
#include "syntax/mesh3d/cpca_wpt.h"
#include "syntax/mesh_object.h"
#include "syntax/trace.h"

namespace m4mesh {

namespace {

const char* vertex_order_name(uint32_t order) {
  switch (order) {
    case kVertexOrderCoding: return "coding order (the input's only if it was in coding order: encode3d --reorder)";
    case kVertexOrderFromGate: return "the input's (sent, predicted by the gate's vertex)";
    default: return "the input's (sent, predicted by parallelograms of input numbers)";
  }
}

int run_info3d(const std::string& input) {
  const std::vector<uint8_t> stream = read_file(input);
  const ContainerParts parts = split_container(stream);
  Mesh3dDecoder decoder(stream);
  const ObjectHeader& h = decoder.header();
  std::printf("%s: %zu bytes, mesh3d format %u.%u, codec_id %u (%s), %u vertices, %u faces, %u frames at %u/%u fps\n", input.c_str(),
              stream.size(), h.version >> 4, h.version & 15, h.codec_id, decoder.codec().name.c_str(), h.vertex_count, h.face_count,
              h.frame_count, h.frame_rate_num, h.frame_rate_den);
  if (h.codec_id == kCpcaWptId) std::printf("  segments: of %u frames\n", read_headers<CpcaHeader>(parts).second.segment_frames);
  if (const std::optional<uint32_t> order = decoder.vertex_order()) std::printf("  vertex order: %s\n", vertex_order_name(*order));
  if (const std::optional<uint32_t> blend = decoder.position_blend())
    std::printf("  positions: parallelograms blended with the neighbours' mean by %u/16\n", *blend);
  const UnitSizes unit = unit_sizes(parts, stream.size());
  const uint64_t* sizes = unit.bytes;
  const uint64_t* counts = unit.count;
  for (uint32_t t = 0; t < kUnitTypes; ++t)
    if (counts[t])
      std::printf("  %-10s units: %llu, %llu bytes\n", unit_type_name(static_cast<UnitType>(t)), static_cast<unsigned long long>(counts[t]),
                  static_cast<unsigned long long>(sizes[t]));
  const uint32_t frame_units = static_cast<uint32_t>(UnitType::kFrame);
  if (h.frame_count > 1 && counts[frame_units])
    std::printf("  frames: %.3f bits/vertex/frame\n",
                8.0 * static_cast<double>(sizes[frame_units]) / (static_cast<double>(h.vertex_count) * (h.frame_count - 1)));
  std::printf("  end code %s\n", parts.has_end_code ? "present" : "MISSING");
  // A stream cut short or broken is not summarised as if it were whole: every unit is decoded.
  while (decoder.next_unit()) {
  }
  return 0;
}

}  // namespace

int run_trace(const std::string& input, const TraceSelection& selection) {
  trace_stream(read_file(input), std::cout, selection);
  return 0;
}

int run_info(const std::string& input) {
  const std::vector<uint8_t> stream = read_file(input);
  if (is_mesh3d_stream(stream)) return run_info3d(input);
  syntax::MeshObjectReader reader(stream);
  MeshObjectPlane plane;
  std::printf("%s: %zu bytes, 2D mesh object\n", input.c_str(), stream.size());
  uint64_t start = reader.position();
  std::map<std::string, int64_t> counts;
  while (reader.next(plane)) {
    const uint64_t bits = reader.position() - start;
    std::string kind;
    if (!plane.new_mesh_flag) {
      kind = "P range=" + std::to_string(plane.motion.motion_range_code);
    } else if (plane.geometry.mesh_type_code == kMeshTypeUniform) {
      const UniformGeometry& u = plane.geometry.uniform;
      kind = "I uniform " + std::to_string(u.nr_of_mesh_nodes_hori) + "x" + std::to_string(u.nr_of_mesh_nodes_verti) +
             " split=" + std::to_string(u.triangle_split_code);
    } else {
      kind = "I delaunay boundary=" + std::to_string(plane.geometry.delaunay.nr_of_boundary_nodes);
    }
    ++counts[plane.new_mesh_flag ? "I" : "P"];
    std::printf("plane %lld at bit %llu: %s, %u nodes, %llu bits (%.3f bits/node)\n",
                static_cast<long long>(reader.planes_read() - 1), static_cast<unsigned long long>(start), kind.c_str(),
                reader.mesh_nodes(), static_cast<unsigned long long>(bits),
                static_cast<double>(bits) / reader.mesh_nodes());
    start = reader.position();
  }
  std::printf("%s (%lld I, %lld P), end code %s\n", console::counted(static_cast<uint64_t>(reader.planes_read()), "plane", "planes").c_str(),
              static_cast<long long>(counts["I"]), static_cast<long long>(counts["P"]),
              reader.has_end_code() ? "present" : "MISSING");
  return 0;
}

int run_check(const std::string& input) {
  const std::vector<uint8_t> stream = read_file(input);
  const bool mesh3d = is_mesh3d_stream(stream);
  const CheckReport report = mesh3d ? check_mesh3d(stream) : check_stream(stream);
  for (const Finding& f : report.findings) std::printf("%s\n", format_finding(f).c_str());
  const size_t errors = report.errors(), warnings = report.findings.size() - errors;
  auto counted = [](long long n, const char* one, const char* many) { return std::to_string(n) + " " + (n == 1 ? one : many); };
  std::printf("%s: %s, %s, %s: %s\n", input.c_str(), counted(report.planes, mesh3d ? "unit" : "plane", mesh3d ? "units" : "planes").c_str(),
              counted(static_cast<long long>(errors), "error", "errors").c_str(), counted(static_cast<long long>(warnings), "warning", "warnings").c_str(),
              report.conformant() ? "conformant" : "NOT conformant");
  return report.conformant() ? 0 : 1;
}

}  // namespace m4mesh
