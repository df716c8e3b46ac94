// The npm package's WebAssembly module (web/package/): the decoders alone,
// for its worker and its three.js loader. A 3D stream is decoded as its
// bytes arrive (Stream3d), a 2D stream whole (decode2d); every call returns
// a JSON text (web/embind_json.h), typed arrays are copies the caller owns.
#include <emscripten/bind.h>
#include <emscripten/val.h>

#include <map>
#include <nlohmann/json.hpp>
#include <span>

#include "codecs3d/registry.h"
#include "decoder/mesh3d/container_decoder.h"
#include "decoder/mesh3d/streaming_decoder.h"
#include "decoder/mesh_object_decoder.h"
#include "web/embind_json.h"

namespace m4mesh::web {
namespace {

MotionMethod method_of(int method) { return method == 1 ? MotionMethod::kMethod1 : MotionMethod::kMethod2; }

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
// a progressive codec's frames refine at every unit. Frames no later unit
// can change are kept here, in display order, until drop()ped; the bytes
// of the units decoded are not kept.
class Stream3d {
 public:
  std::string push(const val& chunk) {
    const std::vector<uint8_t> bytes = bytes_of(chunk);
    return step([&] { return stream_.push(bytes); });
  }
  std::string end() {
    return step([&] { return stream_.finish(); });
  }

  val faces() const {
    const Mesh3dDecoder* decoder = stream_.decoder();
    return copy_out(decoder ? std::span<const Triangle>(decoder->faces()) : std::span<const Triangle>());
  }
  // Frame `index` as x, y, z per vertex: a final frame kept here, else a
  // progressive codec's latest refinement of it; empty when neither.
  val frame(uint32_t index) const {
    if (auto it = frames_.find(index); it != frames_.end()) return copy_out(it->second);
    std::vector<Float3> positions;
    if (const Mesh3dDecoder* decoder = stream_.decoder(); decoder && decoder->progressive() && units_applied_ > 0 && decoder->holds(index)) {
      positions.resize(decoder->header().vertex_count);
      decoder->frame(index, positions);
    }
    return copy_out(positions);
  }
  // Forgets a final frame the caller has taken.
  void drop(uint32_t index) { frames_.erase(index); }

 private:
  // A copy the caller owns: slice() of a view of the module's memory, whose
  // numbers are little-endian as JavaScript's typed arrays are.
  template <class T>
  static val copy_out(std::span<const T> values) {
    return val(emscripten::typed_memory_view(values.size(), values.data())).call<val>("slice");
  }
  // Positions as one Float32Array.
  static val copy_out(std::span<const Float3> positions) {
    return copy_out(std::span<const float>(positions.empty() ? nullptr : positions.data()->data(), 3 * positions.size()));
  }
  // Faces as one Uint32Array of their vertices.
  static val copy_out(std::span<const Triangle> faces) {
    static_assert(sizeof(Triangle) == 3 * sizeof(uint32_t));
    return copy_out(std::span<const uint32_t>(faces.empty() ? nullptr : faces.data()->v.data(), 3 * faces.size()));
  }

  // Runs `take` (push or finish), which decodes units and returns how
  // many, then keeps the frames that became final; the stream's status.
  template <class Take>
  std::string step(Take&& take) {
    json status;
    try {
      if (!error_.is_null()) throw std::logic_error("the stream has failed already");
      units_applied_ += take();
      Mesh3dDecoder* decoder = stream_.decoder();
      while (decoder && !done_ && (decoder->next_frame_ready() || stream_.finished())) {
        if (!decoder->next_frame()) {
          done_ = true;
          break;
        }
        frames_[decoder->frame_index()] = decoder->positions();
        ++final_frames_;
      }
    } catch (const Error& e) {
      error_ = error_json(e);
    } catch (const std::exception& e) {
      if (error_.is_null()) error_ = internal_error(e.what());
    }
    status["bytesReceived"] = stream_.bytes_received();
    status["bytesDecoded"] = stream_.bytes_decoded();
    status["unitsApplied"] = units_applied_;
    status["done"] = done_;
    if (!error_.is_null()) status["error"] = error_;
    if (const Mesh3dDecoder* decoder = stream_.decoder()) {
      const ObjectHeader& h = decoder->header();
      status["header"] = {{"codec", decoder->codec().name},
                          {"vertices", h.vertex_count},
                          {"faces", h.face_count},
                          {"frames", h.frame_count != 0 ? size_t{h.frame_count} : final_frames_},
                          {"frameRate", static_cast<double>(h.frame_rate_num) / h.frame_rate_den},
                          {"progressive", decoder->progressive()}};
      status["framesDecoded"] = decoder->progressive() ? (units_applied_ > 0 ? size_t{h.frame_count} : 0) : final_frames_;
    }
    return status.dump();
  }

  StreamingMesh3dDecoder stream_;
  std::map<uint32_t, std::vector<Float3>> frames_;
  size_t final_frames_ = 0;  // frames that became final so far, in display order
  size_t units_applied_ = 0;
  bool done_ = false;
  json error_;
};

}  // namespace
}  // namespace m4mesh::web

EMSCRIPTEN_BINDINGS(m4mesh_decoder) {
  using namespace m4mesh::web;
  emscripten::function("streamKind", &stream_kind);
  emscripten::function("decode2d", &decode2d);
  emscripten::class_<Stream3d>("Stream3d")
      .constructor<>()
      .function("push", &Stream3d::push)
      .function("end", &Stream3d::end)
      .function("faces", &Stream3d::faces)
      .function("frame", &Stream3d::frame)
      .function("drop", &Stream3d::drop);
}
