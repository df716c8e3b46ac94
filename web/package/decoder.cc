// The npm package's WebAssembly module (web/package/): the decoders alone,
// for its worker and its three.js loader. A 3D stream is decoded as its
// bytes arrive (Stream3d), a 2D stream whole (decode2d); every call returns
// a JSON text (web/embind_json.h), typed arrays are copies the caller owns.
#include <emscripten/bind.h>
#include <emscripten/val.h>

#include <map>
#include <memory>
#include <nlohmann/json.hpp>

#include "codecs3d/registry.h"
#include "decoder/mesh3d/container_decoder.h"
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
  // Frame `index` as x, y, z per vertex: a final frame kept here, else a
  // progressive codec's latest refinement of it; empty when neither.
  val frame(uint32_t index) const {
    std::vector<float> flat;
    std::vector<Float3> positions;
    if (auto it = frames_.find(index); it != frames_.end()) {
      positions = it->second;
    } else if (decoder_ && decoder_->progressive() && units_applied_ > 0 && decoder_->holds(index)) {
      positions.resize(decoder_->header().vertex_count);
      decoder_->frame(index, positions);
    }
    for (const Float3& p : positions) flat.insert(flat.end(), p.begin(), p.end());
    return copy_out<float>("Float32Array", flat);
  }
  // Forgets a final frame the caller has taken.
  void drop(uint32_t index) { frames_.erase(index); }

 private:
  template <class T>
  static val copy_out(const char* type, const std::vector<T>& values) {
    val out = val::global(type).new_(values.size());
    out.call<void>("set", val(emscripten::typed_memory_view(values.size(), values.data())));
    return out;
  }

  // Decodes the units whole in the first `size` bytes held, keeps the
  // frames that became final, and drops the bytes of the units taken.
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
        decoder_->extend(whole, received_start_);
      }
      if (decoder_) {
        units_applied_ += decoder_->take_received_units();
        while (!done_ && (decoder_->next_frame_ready() || ended_)) {
          if (!decoder_->next_frame()) {
            done_ = true;
            break;
          }
          frames_[decoder_->frame_index()] = decoder_->positions();
          ++final_frames_;
        }
        if (const std::optional<uint32_t> f = decoder_->first_mismatch())
          throw Error(ErrorKind::kStructure, "frame_md5", *f, kNoOffset, "the decoded frame does not match its hash").in_mesh3d(kNoUnit);
        bytes_decoded_ = received_start_ + size;
        const size_t taken = decoder_->units_taken();
        const uint64_t keep = taken < decoder_->units_received() ? decoder_->unit_offset(taken) : received_start_ + size;
        received_.erase(received_.begin(), received_.begin() + static_cast<std::ptrdiff_t>(keep - received_start_));
        received_start_ = keep;
      }
    } catch (const Error& e) {
      error_ = error_json(e);
    } catch (const std::exception& e) {
      if (error_.is_null()) error_ = internal_error(e.what());
    }
    status["bytesReceived"] = received_start_ + received_.size();
    status["bytesDecoded"] = bytes_decoded_;
    status["unitsApplied"] = units_applied_;
    status["done"] = done_;
    if (!error_.is_null()) status["error"] = error_;
    if (decoder_) {
      const ObjectHeader& h = decoder_->header();
      status["header"] = {{"codec", decoder_->codec().name},
                          {"vertices", h.vertex_count},
                          {"faces", h.face_count},
                          {"frames", h.frame_count != 0 ? size_t{h.frame_count} : final_frames_},
                          {"frameRate", static_cast<double>(h.frame_rate_num) / h.frame_rate_den},
                          {"progressive", decoder_->progressive()}};
      status["framesDecoded"] = decoder_->progressive() ? (units_applied_ > 0 ? size_t{h.frame_count} : 0) : final_frames_;
    }
    return status.dump();
  }

  std::vector<uint8_t> received_;  // the stream's bytes from received_start_ on
  uint64_t received_start_ = 0;
  std::unique_ptr<Mesh3dDecoder> decoder_;
  std::map<uint32_t, std::vector<Float3>> frames_;
  size_t final_frames_ = 0;  // frames that became final so far, in display order
  size_t units_applied_ = 0;
  uint64_t bytes_decoded_ = 0;
  bool ended_ = false;
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
