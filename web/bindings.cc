// The site's WebAssembly module (docs/web.md): the checker, the trace, the
// conformance judgement and the decoded MD5, called from JavaScript through
// embind (the player decodes with the npm package's module,
// web/package/decoder.cc). Every call returns a JSON text (embind_json.h).
#include <emscripten/bind.h>
#include <emscripten/val.h>

#include <memory>
#include <optional>
#include <nlohmann/json.hpp>
#include <sstream>

#include "codecs3d/registry.h"
#include "common/error.h"
#include "conformance/checker.h"
#include "conformance/judge.h"
#include "decoder/mesh3d/container_decoder.h"
#include "decoder/mesh_object_decoder.h"
#include "decoder/stream_trace.h"
#include "mesh/topology.h"
#include "syntax/mesh3d/container.h"
#include "syntax/mesh_object.h"
#include "syntax/trace.h"
#include "web/embind_json.h"

namespace m4mesh::web {
namespace {

// A conformance suite's manifest: its streams, and m4mesh's judgement of
// each (conformance/judge.h), as `m4mesh conform` gives it.
class Suite {
 public:
  Suite(const std::string& manifest_text, const std::string& name) {
    try {
      manifest_ = parse_manifest(manifest_text, name);
    } catch (const Error& e) {
      error_ = e.what();
    }
  }
  // {"entries": [{id, file, expect}]} or {"error"}.
  std::string entries() const {
    if (!error_.empty()) return json{{"error", {{"text", error_}}}}.dump();
    json list = json::array();
    for (const ManifestEntry& e : manifest_.entries) list.push_back({{"id", e.id}, {"file", e.file}, {"expect", e.valid ? "decode" : "error"}});
    return json{{"entries", list}}.dump();
  }
  // {"pass", "detail"}: entry `index` judged on the stream's bytes.
  std::string judge(int index, const val& bytes) const {
    return guarded([&] {
      if (index < 0 || static_cast<size_t>(index) >= manifest_.entries.size()) throw std::out_of_range("no entry " + std::to_string(index));
      const Verdict verdict = judge_stream(manifest_.kind, manifest_.entries[static_cast<size_t>(index)], bytes_of(bytes));
      return json{{"pass", verdict.pass}, {"detail", verdict.detail}};
    });
  }

 private:
  Manifest manifest_;
  std::string error_;
};

// {"md5"}: the MD5 of the decoded output the conformance manifests hold
// (§9 text for 2D, every frame's binary32 bytes for 3D).
std::string decoded_md5(const val& bytes, int method) {
  return guarded([&] {
    const std::vector<uint8_t> stream = bytes_of(bytes);
    return json{{"md5", decoded_output_md5(is_mesh3d_stream(stream) ? SuiteKind::kMesh3d : SuiteKind::kMesh2d, stream, method)}};
  });
}

// {"conformant", "units" | "planes", "findings": [{error, kind, plane, unit, element, offset, message, text}]}: `m4mesh check`.
std::string check(const val& bytes) {
  return guarded([&] {
    const std::vector<uint8_t> stream = bytes_of(bytes);
    const bool mesh3d = is_mesh3d_stream(stream);
    const CheckReport report = mesh3d ? check_mesh3d(stream) : check_stream(stream);
    json findings = json::array();
    for (const Finding& f : report.findings)
      findings.push_back({{"error", f.error},
                          {"kind", to_string(f.kind)},
                          {"plane", f.plane},
                          {"unit", f.unit ? static_cast<int64_t>(*f.unit) : kNoUnit},
                          {"element", f.element},
                          {"offset", f.bit_offset},
                          {"message", f.message},
                          {"text", format_finding(f)}});
    return json{{"conformant", report.conformant()}, {mesh3d ? "units" : "planes", report.planes}, {"findings", findings}};
  });
}

// {"lines": [[unit, frame, position, name, size, value, context]], "error"?}:
// `m4mesh trace`, parsed; the lines before an error are kept.
std::string traced_lines(const val& bytes, const TraceSelection& selection) {
  const std::vector<uint8_t> stream = bytes_of(bytes);
  std::ostringstream text;
  json out;
  try {
    trace_stream(stream, text, selection);
  } catch (const Error& e) {
    out["error"] = error_json(e);
  } catch (const std::exception& e) {
    out["error"] = internal_error(e.what());
  }
  json lines = json::array();
  std::istringstream in(text.str());
  for (std::string line; std::getline(in, line);)
    if (const std::optional<TraceLine> t = parse_trace_line(line))
      lines.push_back({t->unit, t->frame, t->position, t->name, t->size, t->value, t->context});
  out["lines"] = std::move(lines);
  return out.dump();
}

// The whole stream's fixed fields and byte sections (no bins, no raw bits):
// enough to list its parts and chart their bits.
std::string trace_fields(const val& bytes) { return traced_lines(bytes, {.part = std::nullopt, .symbols = false}); }

// Every element of one part (the 3D object header −1 or unit k, the 2D
// mesh object −1 or plane k), its symbols included.
std::string trace_part(const val& bytes, double part) { return traced_lines(bytes, {.part = static_cast<int64_t>(part), .symbols = true}); }

// {"units": [{offset, bytes, label}]}: where each unit of a 3D stream lies
// (its start code's byte offset, its size with the start code) and what it
// is (unit_labels3d: "frame 3", "refinement, cluster 2 start").
std::string units3d(const val& bytes) {
  return guarded([&] {
    const std::vector<uint8_t> stream = bytes_of(bytes);
    const ContainerParts parts = split_container(stream);
    const std::vector<std::string> labels = unit_labels3d(stream);
    json units = json::array();
    for (size_t k = 0; k < parts.units.size(); ++k) {
      const uint64_t end = k + 1 < parts.units.size() ? parts.units[k + 1].byte_offset : stream.size() - (parts.has_end_code ? 4 : 0);
      units.push_back({{"offset", parts.units[k].byte_offset}, {"bytes", end - parts.units[k].byte_offset}, {"label", labels[k]}});
    }
    return json{{"units", units}, {"endCode", parts.has_end_code}};
  });
}

}  // namespace
}  // namespace m4mesh::web

EMSCRIPTEN_BINDINGS(m4mesh) {
  using namespace m4mesh::web;
  emscripten::function("streamKind", &stream_kind);
  emscripten::function("decodedMd5", &decoded_md5);
  emscripten::function("check", &check);
  emscripten::function("traceFields", &trace_fields);
  emscripten::function("tracePart", &trace_part);
  emscripten::function("units3d", &units3d);
  emscripten::class_<Suite>("Suite")
      .constructor<std::string, std::string>()
      .function("entries", &Suite::entries)
      .function("judge", &Suite::judge);
}
