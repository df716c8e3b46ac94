// The C interface (api/m4mesh.h) over the library: every C++ exception
// stops here and becomes an m4mesh_error.
#include "api/m4mesh.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <new>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "bitstream/start_codes.h"
#include "codecs3d/registry.h"
#include "common/error.h"
#include "common/parse_number.h"
#include "decoder/mesh3d/container_decoder.h"
#include "decoder/mesh3d/streaming_decoder.h"
#include "decoder/mesh_object_decoder.h"
#include "encoder/mesh3d/container_encoder.h"
#include "encoder/mesh3d/quality_target.h"

namespace m4mesh {
namespace {

// codec_options' "max-error": the whole text a number (its range is checked with the target).
double max_error_option(const char* text) {
  double value = 0;
  const char* end = text + std::strlen(text);
  if (parse_double(text, end, value) != end || end == text) throw usage_error(std::string("codec_options: max-error '") + text + "' is not a number");
  return value;
}

template <size_t N>
void copy_text(char (&out)[N], const std::string& text) {
  const size_t n = std::min(text.size(), N - 1);
  std::memcpy(out, text.data(), n);
  out[n] = '\0';
}

m4mesh_error_kind kind_of(ErrorKind kind) {
  switch (kind) {
    case ErrorKind::kTruncated: return M4MESH_ERROR_TRUNCATED;
    case ErrorKind::kMissingStartCode: return M4MESH_ERROR_MISSING_START_CODE;
    case ErrorKind::kBadStuffing: return M4MESH_ERROR_BAD_STUFFING;
    case ErrorKind::kReservedValue: return M4MESH_ERROR_RESERVED_VALUE;
    case ErrorKind::kOutOfRange: return M4MESH_ERROR_OUT_OF_RANGE;
    case ErrorKind::kInvalidCode: return M4MESH_ERROR_INVALID_CODE;
    case ErrorKind::kTrailingData: return M4MESH_ERROR_TRAILING_DATA;
    case ErrorKind::kGeometry: return M4MESH_ERROR_GEOMETRY;
    case ErrorKind::kStructure: return M4MESH_ERROR_STRUCTURE;
    case ErrorKind::kLimit: return M4MESH_ERROR_LIMIT;
    case ErrorKind::kInput: return M4MESH_ERROR_INPUT;
    case ErrorKind::kIo: return M4MESH_ERROR_IO;
    case ErrorKind::kUsage: return M4MESH_ERROR_USAGE;
  }
  return M4MESH_ERROR_INTERNAL;
}

m4mesh_error no_error() {
  m4mesh_error e{};
  e.kind = M4MESH_ERROR_NONE;
  e.kind_name = "";
  e.frame = e.unit = e.bit_offset = -1;
  return e;
}

m4mesh_error error_of(const Error& error) {
  m4mesh_error e = no_error();
  e.kind = kind_of(error.kind());
  e.kind_name = to_string(error.kind());
  copy_text(e.element, error.element());
  e.frame = error.plane();
  e.unit = error.mesh3d() ? error.unit() : -1;
  e.bit_offset = error.bit_offset();
  copy_text(e.message, error.what());
  return e;
}

m4mesh_error internal_error(const std::string& message) {
  m4mesh_error e = no_error();
  e.kind = M4MESH_ERROR_INTERNAL;
  e.kind_name = "internal";
  copy_text(e.message, message);
  return e;
}

// Runs `body`, its exceptions kept in `error`: M4MESH_ERROR then.
template <class Body>
m4mesh_status guarded(m4mesh_error& error, Body&& body) noexcept {
  try {
    return body();
  } catch (const Error& e) {
    error = error_of(e);
  } catch (const std::bad_alloc&) {
    error = internal_error("out of memory");
  } catch (const std::exception& e) {
    error = internal_error(e.what());
  } catch (...) {
    error = internal_error("an unknown exception");
  }
  return M4MESH_ERROR;
}

// What a call on no decoder (a null handle) reports.
const m4mesh_error* null_handle_error() {
  static const m4mesh_error error = [] {
    m4mesh_error e = no_error();
    e.kind = M4MESH_ERROR_USAGE;
    e.kind_name = "usage";
    copy_text(e.message, "usage: a null decoder handle");
    return e;
  }();
  return &error;
}

void check_capacity(size_t capacity, uint64_t needed, const char* array) {
  if (capacity < needed)
    throw usage_error(std::string(array) + ": " + std::to_string(capacity) + " entries, " + std::to_string(needed) + " needed");
}

}  // namespace
}  // namespace m4mesh

using namespace m4mesh;

struct m4mesh_decoder3d {
  StreamingMesh3dDecoder stream;
  mutable m4mesh_error error = no_error();  // const calls report misuse here too

  bool failed() const { return error.kind != M4MESH_ERROR_NONE; }
  const Mesh3dDecoder* decoder() const { return stream.decoder(); }
};

struct m4mesh_decoder2d {
  std::vector<uint8_t> received;
  std::vector<uint8_t> complete;  // the planes whole so far and the start code after them
  DecoderOptions options;
  std::unique_ptr<Decoder> decoder;
  int64_t planes_out = 0;
  bool ended = false;
  std::vector<int32_t> nodes;
  std::vector<uint32_t> triangles;
  m4mesh_error error = no_error();

  bool failed() const { return error.kind != M4MESH_ERROR_NONE; }

  static bool code_at(std::span<const uint8_t> bytes, size_t end, uint32_t code) {
    return end >= 4 && (uint32_t{bytes[end - 4]} << 24 | uint32_t{bytes[end - 3]} << 16 | uint32_t{bytes[end - 2]} << 8 | bytes[end - 1]) == code;
  }
  // The bytes up to the last plane or end start code received, with it:
  // every plane before that code is whole.
  size_t whole_size() const {
    if (ended) return received.size();
    for (size_t end = received.size(); end >= 4; --end)
      if (code_at(received, end, kMeshObjectPlaneStartCode) || code_at(received, end, kMeshObjectEndCode)) return end;
    return 0;
  }
  // The planes whole in `complete`: one per plane start code, but the last
  // when nothing follows it yet.
  int64_t whole_planes() const {
    int64_t codes = 0;
    for (size_t end = 4; end <= complete.size(); ++end) codes += code_at(complete, end, kMeshObjectPlaneStartCode);
    return codes - (code_at(complete, complete.size(), kMeshObjectPlaneStartCode) ? 1 : 0);
  }
};

extern "C" {

const char* m4mesh_version(void) { return M4MESH_VERSION; }
unsigned m4mesh_format_version(void) { return kFormatVersion; }

m4mesh_decoder3d* m4mesh_decoder3d_new(void) { return new (std::nothrow) m4mesh_decoder3d; }
void m4mesh_decoder3d_free(m4mesh_decoder3d* decoder) { delete decoder; }

m4mesh_status m4mesh_decoder3d_push(m4mesh_decoder3d* d, const uint8_t* data, size_t size) {
  if (!d || d->failed()) return M4MESH_ERROR;
  return guarded(d->error, [&] {
    if (d->stream.finished()) throw usage_error("m4mesh_decoder3d_push: the stream has finished");
    if (!data && size > 0) throw usage_error("m4mesh_decoder3d_push: no data");
    d->stream.push(std::span(data, size));
    return M4MESH_OK;
  });
}

m4mesh_status m4mesh_decoder3d_finish(m4mesh_decoder3d* d) {
  if (!d || d->failed()) return M4MESH_ERROR;
  return guarded(d->error, [&] {
    d->stream.finish();
    d->stream.decoder()->next_unit();  // none left: checks that every frame is decoded
    return M4MESH_OK;
  });
}

m4mesh_status m4mesh_decoder3d_header(const m4mesh_decoder3d* d, m4mesh_header3d* header) {
  if (!d) return M4MESH_ERROR;
  if (!header) return guarded(d->error, []() -> m4mesh_status { throw usage_error("m4mesh_decoder3d_header: no header"); });
  if (!d->decoder()) return d->failed() ? M4MESH_ERROR : M4MESH_AGAIN;
  const ObjectHeader& h = d->decoder()->header();
  *header = m4mesh_header3d{};
  copy_text(header->codec, d->decoder()->codec().name);
  header->frames = h.frame_count;
  header->vertices = h.vertex_count;
  header->faces = h.face_count;
  header->frame_rate = static_cast<double>(h.frame_rate_num) / h.frame_rate_den;
  header->progressive = d->decoder()->progressive() ? 1 : 0;
  return M4MESH_OK;
}

m4mesh_status m4mesh_decoder3d_faces(const m4mesh_decoder3d* d, uint32_t* faces, size_t capacity) {
  if (!d) return M4MESH_ERROR;
  if (!d->decoder()) return d->failed() ? M4MESH_ERROR : M4MESH_AGAIN;
  const std::vector<Triangle>& decoded = d->decoder()->faces();
  const uint32_t count = d->decoder()->header().face_count;
  if (decoded.size() < count) return d->failed() ? M4MESH_ERROR : M4MESH_AGAIN;
  return guarded(d->error, [&] {
    check_capacity(faces ? capacity : 0, 3 * uint64_t{count}, "m4mesh_decoder3d_faces: faces");
    for (size_t k = 0; k < count; ++k)
      for (int j = 0; j < 3; ++j) faces[3 * k + j] = decoded[k].v[j];
    return M4MESH_OK;
  });
}

m4mesh_status m4mesh_decoder3d_next_frame(m4mesh_decoder3d* d, uint32_t* index, float* positions, size_t capacity) {
  if (!d || d->failed()) return M4MESH_ERROR;
  Mesh3dDecoder* decoder = d->stream.decoder();
  if (!decoder || (!d->stream.finished() && !decoder->next_frame_ready())) return M4MESH_AGAIN;
  return guarded(d->error, [&] {
    check_capacity(positions && index ? capacity : 0, 3 * uint64_t{decoder->header().vertex_count}, "m4mesh_decoder3d_next_frame: positions");
    if (!decoder->next_frame()) return M4MESH_END;
    *index = decoder->frame_index();
    const std::vector<Float3>& p = decoder->positions();
    std::memcpy(positions, p.data(), p.size() * sizeof(Float3));
    return M4MESH_OK;
  });
}

m4mesh_status m4mesh_decoder3d_peek_frame(const m4mesh_decoder3d* d, uint32_t index, float* positions, size_t capacity, size_t* units) {
  if (!d) return M4MESH_ERROR;
  if (!d->decoder()) return d->failed() ? M4MESH_ERROR : M4MESH_AGAIN;
  const Mesh3dDecoder& decoder = *d->decoder();
  if (!decoder.progressive() || !decoder.holds(index)) return M4MESH_AGAIN;
  return guarded(d->error, [&] {
    const uint32_t vertices = decoder.header().vertex_count;
    check_capacity(positions && units ? capacity : 0, 3 * uint64_t{vertices}, "m4mesh_decoder3d_peek_frame: positions");
    decoder.frame(index, std::span(reinterpret_cast<Float3*>(positions), vertices));
    *units = decoder.units_taken();
    return M4MESH_OK;
  });
}

size_t m4mesh_decoder3d_units(const m4mesh_decoder3d* d) { return d && d->decoder() ? d->decoder()->units_taken() : 0; }
const m4mesh_error* m4mesh_decoder3d_error(const m4mesh_decoder3d* d) { return d ? &d->error : null_handle_error(); }

m4mesh_decoder2d* m4mesh_decoder2d_new(int method) {
  if (method != 1 && method != 2) return nullptr;
  m4mesh_decoder2d* d = new (std::nothrow) m4mesh_decoder2d;
  if (d) d->options.method = method == 1 ? MotionMethod::kMethod1 : MotionMethod::kMethod2;
  return d;
}
void m4mesh_decoder2d_free(m4mesh_decoder2d* decoder) { delete decoder; }

m4mesh_status m4mesh_decoder2d_push(m4mesh_decoder2d* d, const uint8_t* data, size_t size) {
  if (!d || d->failed()) return M4MESH_ERROR;
  return guarded(d->error, [&] {
    if (d->ended) throw usage_error("m4mesh_decoder2d_push: the stream has finished");
    if (!data && size > 0) throw usage_error("m4mesh_decoder2d_push: no data");
    if (size > 0) d->received.insert(d->received.end(), data, data + size);
    return M4MESH_OK;
  });
}

m4mesh_status m4mesh_decoder2d_finish(m4mesh_decoder2d* d) {
  if (!d || d->failed()) return M4MESH_ERROR;
  d->ended = true;
  return M4MESH_OK;
}

m4mesh_status m4mesh_decoder2d_next_plane(m4mesh_decoder2d* d, m4mesh_plane2d* plane) {
  if (!d || d->failed()) return M4MESH_ERROR;
  return guarded(d->error, [&] {
    if (!plane) throw usage_error("m4mesh_decoder2d_next_plane: no plane");
    // The planes are read again from the start when more of them are whole
    // (2D streams are small); those handed out already are skipped.
    const size_t whole = d->whole_size();
    if (whole > d->complete.size() || (d->ended && !d->decoder)) {
      d->complete.assign(d->received.begin(), d->received.begin() + static_cast<std::ptrdiff_t>(whole));
      d->decoder = std::make_unique<Decoder>(d->complete, d->options);
      for (int64_t k = 0; k < d->planes_out; ++k) d->decoder->next();
    }
    if (!d->decoder) return M4MESH_AGAIN;
    if (!d->ended && d->planes_out >= d->whole_planes()) return M4MESH_AGAIN;
    try {
      if (!d->decoder->next()) return M4MESH_END;
    } catch (const Error& e) {
      if (d->ended || e.kind() != ErrorKind::kTruncated) throw;
      d->decoder.reset();  // a start code's bytes inside a plane: read again with more bytes
      d->complete.clear();
      return M4MESH_AGAIN;
    }
    ++d->planes_out;
    d->nodes.clear();
    for (const Point& p : d->decoder->nodes()) d->nodes.insert(d->nodes.end(), {p.x, p.y});
    d->triangles.clear();
    for (const Triangle& t : d->decoder->triangles()) d->triangles.insert(d->triangles.end(), t.v.begin(), t.v.end());
    *plane = m4mesh_plane2d{};
    plane->index = d->decoder->plane_index();
    const PlaneInfo& info = d->decoder->info();
    plane->intra = info.intra ? 1 : 0;
    plane->delaunay = info.intra && info.kind == MeshKind::kDelaunay ? 1 : 0;
    plane->cols = info.uniform.cols, plane->rows = info.uniform.rows, plane->dx = info.uniform.dx, plane->dy = info.uniform.dy;
    plane->split = info.uniform.split;
    plane->boundary = info.boundary;
    plane->range = info.range;
    plane->node_count = static_cast<uint32_t>(d->decoder->nodes().size());
    plane->nodes = d->nodes.data();
    plane->triangle_count = static_cast<uint32_t>(d->triangles.size() / 3);
    plane->triangles = d->triangles.data();
    return M4MESH_OK;
  });
}

const m4mesh_error* m4mesh_decoder2d_error(const m4mesh_decoder2d* d) { return d ? &d->error : null_handle_error(); }

void m4mesh_encode_options_init(m4mesh_encode_options* options) {
  if (!options) return;
  *options = m4mesh_encode_options{};
  options->codec = "bfs3d";
  options->hashes = 1;
  options->frame_rate = 25;
}

m4mesh_status m4mesh_encode3d(const float* positions, uint32_t frames, uint32_t vertices, const uint32_t* faces, uint32_t face_count,
                              const m4mesh_encode_options* options, uint8_t** stream, size_t* size, m4mesh_error* error) {
  m4mesh_error local = no_error();
  const m4mesh_status status = guarded(local, [&] {
    m4mesh_encode_options o;
    m4mesh_encode_options_init(&o);
    if (options) o = *options;
    Encode3dOptions encode;
    encode.codec = o.codec ? o.codec : "bfs3d";
    encode.hashes = o.hashes != 0;
    const double rate = o.frame_rate > 0 ? o.frame_rate : 25;
    if (!(rate <= 1e6)) throw usage_error("frame_rate: at most 10^6 frames per second");
    encode.frame_rate_num = static_cast<uint32_t>(std::llround(rate * 1000));
    encode.frame_rate_den = 1000;
    if (rate == std::floor(rate)) encode.frame_rate_num = static_cast<uint32_t>(rate), encode.frame_rate_den = 1;
    QualityTarget target;
    // max-error is a quality target among the codec's options, so that 1.0's struct keeps its size.
    if (o.codec_options)
      for (const char* const* p = o.codec_options; *p; p += 2) {
        if (!p[1]) throw usage_error(std::string("codec_options: option ") + p[0] + " has no value");
        if (std::string_view(p[0]) == "max-error")
          target.max_error = max_error_option(p[1]);
        else
          encode.codec_options[p[0]] = p[1];
      }
    if (o.max_bytes > 0) encode.codec_options["max-bytes"] = std::to_string(o.max_bytes);
    if (o.target_kg != 0) target.kg = o.target_kg;
    if (o.target_psnr != 0) target.psnr = o.target_psnr;

    if (!stream || !size) throw usage_error("m4mesh_encode3d: no place for the stream");
    if ((frames > 0 && vertices > 0 && !positions) || (face_count > 0 && !faces)) throw usage_error("m4mesh_encode3d: no positions or no faces");
    MeshSequence s;
    s.vertex_count = vertices;
    s.frames.resize(frames, std::vector<Vec3>(vertices));
    for (uint32_t f = 0; f < frames; ++f)
      for (uint32_t v = 0; v < vertices; ++v) {
        const float* p = positions + 3 * (size_t{f} * vertices + v);
        s.frames[f][v] = Vec3{p[0], p[1], p[2]};
      }
    s.faces.resize(face_count);
    for (uint32_t k = 0; k < face_count; ++k)
      for (int j = 0; j < 3; ++j) {
        const uint32_t v = faces[3 * size_t{k} + j];
        if (v >= vertices) throw usage_error("faces: face " + std::to_string(k) + " names vertex " + std::to_string(v) + " of " + std::to_string(vertices));
        s.faces[k].v[j] = static_cast<NodeIndex>(v);
      }
    Encode3dResult result;
    std::string chosen;
    if (encode.codec == "auto")
      result = encode_smallest(s, encode, target, [](const TargetTrial&) {}, chosen);
    else if (target.set())
      result = encode_to_target(s, encode, target, [](const TargetTrial&) {});
    else
      result = encode_mesh3d(s, encode);
    auto* out = static_cast<uint8_t*>(std::malloc(std::max<size_t>(result.stream.size(), 1)));
    if (!out) throw std::bad_alloc();
    std::memcpy(out, result.stream.data(), result.stream.size());
    *stream = out;
    *size = result.stream.size();
    return M4MESH_OK;
  });
  if (error) *error = local;
  return status;
}

void m4mesh_free(void* memory) { std::free(memory); }

}  // extern "C"
