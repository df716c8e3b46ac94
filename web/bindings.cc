// The WebAssembly module of the browser side (docs/web.md): the project's
// own decoders, checker and trace, called from JavaScript through embind.
// Every call returns a JSON text; an error in the stream comes back as
// {"error": {kind, element, plane, unit, offset, message, text}}, never as
// a JavaScript exception. Typed arrays are copies the page owns.
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

namespace m4mesh {
namespace {

using emscripten::val;
using json = nlohmann::json;

std::vector<uint8_t> bytes_of(const val& array) { return emscripten::convertJSArrayToNumberVector<uint8_t>(array); }

json error_json(const Error& e) {
  return {{"kind", to_string(e.kind())}, {"element", e.element()}, {"plane", e.plane()},     {"unit", e.unit()},
          {"offset", e.bit_offset()},    {"mesh3d", e.mesh3d()},   {"message", e.message()}, {"text", e.what()}};
}

json internal_error(const char* what) { return {{"kind", "internal"}, {"text", what}}; }

// Runs `make` and returns its JSON; an error becomes {"error": …}.
template <class Make>
std::string guarded(Make&& make) {
  try {
    return make().dump();
  } catch (const Error& e) {
    return json{{"error", error_json(e)}}.dump();
  } catch (const std::exception& e) {
    return json{{"error", internal_error(e.what())}}.dump();
  }
}

MotionMethod method_of(int method) { return method == 1 ? MotionMethod::kMethod1 : MotionMethod::kMethod2; }

// {"kind": "2d" | "3d"}: which decoder the stream needs.
std::string stream_kind(const val& bytes) {
  const std::vector<uint8_t> stream = bytes_of(bytes);
  return json{{"kind", is_mesh3d_stream(stream) ? "3d" : "2d"}}.dump();
}

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

// {"planes": [{intra, bits, nodes: [x, y, …] (half pixels), triangles?: [a, b, c, …]}]}:
// every plane of a 2D stream; an I-plane also carries its mesh's triangles.
std::string decode2d(const val& bytes, int method) {
  return guarded([&] {
    const std::vector<uint8_t> stream = bytes_of(bytes);
    DecoderOptions options;
    options.method = method_of(method);
    Decoder decoder(stream, options);
    json planes = json::array();
    uint64_t start = decoder.bit_position();
    while (decoder.next()) {
      json plane{{"intra", decoder.info().intra}, {"bits", decoder.bit_position() - start}};
      start = decoder.bit_position();
      json nodes = json::array();
      for (const Point& p : decoder.nodes()) nodes.push_back(p.x), nodes.push_back(p.y);
      plane["nodes"] = std::move(nodes);
      if (decoder.info().intra) {
        json triangles = json::array();
        for (const Triangle& t : decoder.triangles()) triangles.push_back(t.v[0]), triangles.push_back(t.v[1]), triangles.push_back(t.v[2]);
        plane["triangles"] = std::move(triangles);
      }
      planes.push_back(std::move(plane));
    }
    return json{{"planes", planes}};
  });
}

// A 3D stream decoded as it arrives: push() the bytes as they come, end()
// when the download is over. Units are decoded as soon as they are whole;
// a progressive codec's frames refine at every unit, a frame-by-frame
// codec's frames are kept as they are decoded.
class Stream3d {
 public:
  std::string push(const val& chunk) {
    const std::vector<uint8_t> bytes = bytes_of(chunk);
    received_.insert(received_.end(), bytes.begin(), bytes.end());
    return step(whole_payloads_size(received_));
  }
  std::string end() {
    ended_ = true;
    return step(received_.size());
  }

  val faces() const {
    std::vector<uint32_t> flat;
    if (decoder_)
      for (const Triangle& t : decoder_->faces()) flat.insert(flat.end(), t.v.begin(), t.v.end());
    return copy_out<uint32_t>("Uint32Array", flat);
  }
  // Frame `index` as x, y, z per vertex: the latest refinement, or (frame by
  // frame) the frame once decoded; empty before that.
  val frame(uint32_t index) const {
    std::vector<float> flat;
    std::vector<Float3> positions;
    if (auto it = frames_.find(index); it != frames_.end()) {
      positions = it->second;
    } else if (decoder_ && decoder_->progressive() && units_applied_ > 0 && index < decoder_->header().frame_count) {
      positions.resize(decoder_->header().vertex_count);
      decoder_->frame(index, positions);
    }
    for (const Float3& p : positions) flat.insert(flat.end(), p.begin(), p.end());
    return copy_out<float>("Float32Array", flat);
  }

 private:
  template <class T>
  static val copy_out(const char* type, const std::vector<T>& values) {
    val out = val::global(type).new_(values.size());
    out.call<void>("set", val(emscripten::typed_memory_view(values.size(), values.data())));
    return out;
  }

  // Decodes the units whole in the first `size` bytes received.
  std::string step(size_t size) {
    json status;
    try {
      if (!error_.is_null()) throw std::logic_error("the stream has failed already");
      const std::span<const uint8_t> whole(received_.data(), size);
      if (!decoder_ && (size > 0 || ended_)) {
        Decode3dOptions options;
        options.verify = true;
        decoder_ = std::make_unique<Mesh3dDecoder>(whole, options);
      } else if (decoder_) {
        decoder_->extend(whole);
      }
      if (decoder_) {
        while (decoder_->units_taken() < decoder_->units_received()) {
          decoder_->next_unit();
          ++units_applied_;
          // A progressive codec's frames stay with it until its segment ends (released): kept here then.
          const DecodedUnit& unit = decoder_->unit();
          for (uint32_t f : decoder_->progressive() ? unit.released : unit.frames) {
            std::vector<Float3>& slot = frames_[f];
            slot.resize(decoder_->header().vertex_count);
            decoder_->frame(f, slot);
          }
        }
        if (ended_ && !decoder_->next_unit()) done_ = true;
        if (const std::optional<uint32_t> f = decoder_->first_mismatch())
          throw Error(ErrorKind::kStructure, "frame_md5", *f, kNoOffset, "the decoded frame does not match its hash").in_mesh3d(kNoUnit);
        bytes_decoded_ = size;
      }
    } catch (const Error& e) {
      error_ = error_json(e);
    } catch (const std::exception& e) {
      if (error_.is_null()) error_ = internal_error(e.what());
    }
    status["bytesReceived"] = received_.size();
    status["bytesDecoded"] = bytes_decoded_;
    status["unitsApplied"] = units_applied_;
    status["done"] = done_;
    if (!error_.is_null()) status["error"] = error_;
    if (decoder_) {
      const ObjectHeader& h = decoder_->header();
      status["header"] = {{"codec", decoder_->codec().name},
                          {"vertices", h.vertex_count},
                          {"faces", h.face_count},
                          {"frames", h.frame_count != 0 ? size_t{h.frame_count} : frames_.size()},
                          {"frameRate", static_cast<double>(h.frame_rate_num) / h.frame_rate_den},
                          {"progressive", decoder_->progressive()}};
      status["framesDecoded"] = decoder_->progressive() ? (units_applied_ > 0 ? size_t{h.frame_count} : 0) : frames_.size();
    }
    return status.dump();
  }

  std::vector<uint8_t> received_;
  std::unique_ptr<Mesh3dDecoder> decoder_;
  std::map<uint32_t, std::vector<Float3>> frames_;
  size_t units_applied_ = 0;
  size_t bytes_decoded_ = 0;
  bool ended_ = false;
  bool done_ = false;
  json error_;
};

}  // namespace
}  // namespace m4mesh

EMSCRIPTEN_BINDINGS(m4mesh) {
  using namespace m4mesh;
  emscripten::function("streamKind", &stream_kind);
  emscripten::function("decodedMd5", &decoded_md5);
  emscripten::function("check", &check);
  emscripten::function("traceFields", &trace_fields);
  emscripten::function("tracePart", &trace_part);
  emscripten::function("units3d", &units3d);
  emscripten::function("decode2d", &decode2d);
  emscripten::class_<Suite>("Suite")
      .constructor<std::string, std::string>()
      .function("entries", &Suite::entries)
      .function("judge", &Suite::judge);
  emscripten::class_<Stream3d>("Stream3d")
      .constructor<>()
      .function("push", &Stream3d::push)
      .function("end", &Stream3d::end)
      .function("faces", &Stream3d::faces)
      .function("frame", &Stream3d::frame);
}
