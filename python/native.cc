// The m4mesh Python module's native part (m4mesh._native): pybind11 over
// the library, numpy arrays in and out; every m4mesh::Error becomes an
// m4mesh.Error carrying its kind, element, frame and bit offset.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cctype>
#include <cstring>
#include <map>
#include <optional>
#include <sstream>

#include "codecs3d/registry.h"
#include "common/error.h"
#include "conformance/runner.h"
#include "decoder/mesh3d/container_decoder.h"
#include "decoder/mesh_object_decoder.h"
#include "encoder/mesh3d/base_mesh.h"
#include "encoder/mesh3d/container_encoder.h"
#include "encoder/mesh3d/quality_target.h"
#include "mesh3d/metrics.h"
#include "syntax/mesh3d/base_mesh.h"

namespace py = pybind11;

namespace m4mesh {
namespace {

using Frames = py::array_t<float, py::array::c_style | py::array::forcecast>;
using Faces = py::array_t<int32_t, py::array::c_style | py::array::forcecast>;

Error usage(const std::string& message) { return usage_error(message); }

MeshSequence sequence_of(const Frames& frames, const Faces& faces) {
  if (frames.ndim() != 3 || frames.shape(2) != 3) throw usage("frames: an array of shape (frames, vertices, 3)");
  if (faces.ndim() != 2 || faces.shape(1) != 3) throw usage("faces: an array of shape (faces, 3)");
  MeshSequence s;
  s.vertex_count = static_cast<uint32_t>(frames.shape(1));
  // Read by bytes: an array over a buffer (np.frombuffer) need not be aligned.
  const auto* f = static_cast<const char*>(static_cast<const py::array&>(frames).data());
  s.frames.resize(static_cast<size_t>(frames.shape(0)), std::vector<Vec3>(s.vertex_count));
  for (size_t k = 0; k < s.frames.size(); ++k)
    for (uint32_t i = 0; i < s.vertex_count; ++i, f += 3 * sizeof(float)) {
      float xyz[3];
      std::memcpy(xyz, f, sizeof xyz);
      s.frames[k][i] = Vec3{xyz[0], xyz[1], xyz[2]};
    }
  const auto* t = static_cast<const char*>(static_cast<const py::array&>(faces).data());
  for (py::ssize_t k = 0; k < faces.shape(0); ++k) {
    Triangle tri{};
    for (int j = 0; j < 3; ++j, t += sizeof(int32_t)) {
      int32_t v = 0;
      std::memcpy(&v, t, sizeof v);
      if (v < 0 || static_cast<uint32_t>(v) >= s.vertex_count) throw usage("faces: a vertex index out of range in face " + std::to_string(k));
      tri.v[j] = static_cast<NodeIndex>(v);
    }
    s.faces.push_back(tri);
  }
  return s;
}

Faces faces_of(std::span<const Triangle> faces) {
  Faces out({static_cast<py::ssize_t>(faces.size()), py::ssize_t{3}});
  auto o = out.mutable_unchecked<2>();
  for (size_t k = 0; k < faces.size(); ++k)
    for (int j = 0; j < 3; ++j) o(k, j) = static_cast<int32_t>(faces[k].v[j]);
  return out;
}

// A stream from any bytes-like object: a bytes object's own bytes (it
// cannot change), any other's copied (the decoder runs without the GIL,
// while another thread could change a bytearray).
class StreamBytes {
 public:
  explicit StreamBytes(const py::handle& stream) {
    if (!PyObject_CheckBuffer(stream.ptr()))
      throw py::type_error("stream: bytes or another bytes-like object (bytearray, memoryview, a numpy uint8 array), not " +
                           std::string(py::str(py::type::handle_of(stream).attr("__name__"))));
    if (PyBytes_Check(stream.ptr())) {
      owner_ = py::reinterpret_borrow<py::object>(stream);
      bytes_ = {reinterpret_cast<const uint8_t*>(PyBytes_AS_STRING(stream.ptr())), static_cast<size_t>(PyBytes_GET_SIZE(stream.ptr()))};
      return;
    }
    const py::buffer_info info = py::reinterpret_borrow<py::buffer>(stream).request();
    if (info.itemsize != 1 || info.ndim != 1 || (info.size > 1 && info.strides[0] != 1))
      throw py::type_error("stream: a one-dimensional, contiguous buffer of bytes (its items are " + std::to_string(info.itemsize) +
                           " bytes, " + std::to_string(info.ndim) + " dimensions)");
    const auto* data = static_cast<const uint8_t*>(info.ptr);
    copy_.assign(data, data + info.size);
    bytes_ = copy_;
  }
  StreamBytes(const StreamBytes&) = delete;
  StreamBytes& operator=(const StreamBytes&) = delete;
  operator std::span<const uint8_t>() const { return bytes_; }
  size_t size() const { return bytes_.size(); }

 private:
  py::object owner_;
  std::vector<uint8_t> copy_;
  std::span<const uint8_t> bytes_;
};

// Option names in a message as keywords: "--intra-period" → "intra_period".
std::string keyword_spelling(const std::string& message) {
  std::string out;
  for (size_t i = 0; i < message.size(); ++i) {
    const bool option = message.compare(i, 2, "--") == 0 && i + 2 < message.size() && std::islower(static_cast<unsigned char>(message[i + 2]));
    if (!option) {
      out += message[i];
      continue;
    }
    for (i += 2; i < message.size() && (std::isalnum(static_cast<unsigned char>(message[i])) || message[i] == '-'); ++i)
      out += message[i] == '-' ? '_' : message[i];
    --i;
  }
  return out;
}

py::bytes encode(const Frames& frames, const Faces& faces, const std::string& codec, bool hashes, uint32_t hash_group, bool reorder,
                 std::optional<uint32_t> position_blend, const py::kwargs& options) {
  Encode3dOptions o;
  o.codec = codec;
  o.hashes = hashes;
  o.hash_group = hash_group;
  o.reorder = reorder;
  if (position_blend > kPositionBlendUnit) throw py::value_error("position_blend is None (auto) or 0 … 16");
  o.position_blend = position_blend;
  QualityTarget target;
  for (const auto& [key, value] : options) {
    std::string name = py::str(key);
    std::replace(name.begin(), name.end(), '_', '-');
    if (name == "target-kg") target.kg = value.cast<double>();
    else if (name == "target-psnr") target.psnr = value.cast<double>();
    else if (name == "max-error") target.max_error = value.cast<double>();
    else o.codec_options[name] = py::isinstance<py::bool_>(value) ? (value.cast<bool>() ? "1" : "0") : std::string(py::str(value));
  }
  const MeshSequence s = sequence_of(frames, faces);
  Encode3dResult result;
  {
    py::gil_scoped_release release;
    std::string chosen;
    if (codec == "auto")
      result = encode_smallest(s, o, target, [](const TargetTrial&) {}, chosen);  // a usage error without a target
    else if (target.set())
      result = encode_to_target(s, o, target, [](const TargetTrial&) {});
    else
      result = encode_mesh3d(s, o);
  }
  return py::bytes(reinterpret_cast<const char*>(result.stream.data()), result.stream.size());
}

// Whether a stream numbers its vertices in coding order (encode3d --reorder).
bool in_coding_order(const Mesh3dDecoder& decoder) { return decoder.vertex_order() == kVertexOrderCoding; }
bool in_coding_order(std::span<const uint8_t> stream) { return in_coding_order(Mesh3dDecoder(stream)); }

// A stream of reorder=True numbers its vertices in coding order: a UserWarning says so.
void warn_if_coding_order(bool coding_order) {
  if (coding_order &&
      PyErr_WarnEx(PyExc_UserWarning,
                   "the stream numbers its vertices in coding order (reorder=True, or an input already in that order): compare "
                   "it with its original through m4mesh.metrics(original, stream, faces), which maps them",
                   1) < 0)
    throw py::error_already_set();  // warnings turned into errors
}

py::tuple decode(const py::handle& stream) {
  const StreamBytes bytes(stream);
  std::vector<std::vector<Float3>> decoded;  // binary32, copied once into the array returned
  std::vector<Triangle> faces;
  uint32_t vertex_count = 0;
  bool coding_order = false;
  {
    py::gil_scoped_release release;
    Mesh3dDecoder decoder(bytes);
    vertex_count = decoder.header().vertex_count;
    coding_order = in_coding_order(decoder);
    while (decoder.next_frame()) decoded.push_back(decoder.positions());
    faces = decoder.faces();
  }
  warn_if_coding_order(coding_order);
  Frames frames({static_cast<py::ssize_t>(decoded.size()), static_cast<py::ssize_t>(vertex_count), py::ssize_t{3}});
  for (size_t k = 0; k < decoded.size(); ++k) std::memcpy(frames.mutable_data(k), decoded[k].data(), decoded[k].size() * sizeof(Float3));
  return py::make_tuple(frames, faces_of(faces));
}

// A 3D stream's frames one at a time, in display order: memory for the
// decoder and one frame, however long the sequence.
class FrameIterator {
 public:
  explicit FrameIterator(const py::handle& stream) : stream_(stream), decoder_(stream_) {
    warn_if_coding_order(in_coding_order(decoder_));
  }
  // float32[V, 3]: the next frame; a hash unit that disagrees raises as soon as it is read.
  Frames next() {
    // The frame decodes without the GIL: another thread must not step the same iterator meanwhile.
    if (busy_) throw py::value_error("frames: already being read in another thread");
    bool more = false;
    {
      const Busy busy(busy_);  // cleared once the GIL is held again
      py::gil_scoped_release release;
      more = decoder_.next_frame();
    }
    if (!more) throw py::stop_iteration();
    const std::vector<Float3>& positions = decoder_.positions();
    Frames frame({static_cast<py::ssize_t>(positions.size()), py::ssize_t{3}});
    std::memcpy(frame.mutable_data(), positions.data(), positions.size() * sizeof(Float3));
    return frame;
  }
  Faces faces() const {
    if (busy_) throw py::value_error("frames: already being read in another thread");
    return faces_of(decoder_.faces());
  }

 private:
  // Sets a flag for its lifetime.
  struct Busy {
    explicit Busy(bool& set) : flag(set) { flag = true; }
    ~Busy() { flag = false; }
    bool& flag;
  };

  const StreamBytes stream_;
  Mesh3dDecoder decoder_;
  bool busy_ = false;  // read and written with the GIL held
};

// A progressive stream's prefixes, unit by unit.
class Progressive {
 public:
  explicit Progressive(const py::handle& stream)
      : stream_(stream), decoder_(stream_), parts_(split_container(stream_)) {
    if (!decoder_.progressive())
      throw usage(decoder_.codec().name + " decodes frame by frame; progressive decoding needs a progressive codec (cpca-wpt)");
  }
  // (units, bytes received, frames float32[F, V, 3]) after the next unit.
  py::tuple next() {
    if (!decoder_.next_unit()) throw py::stop_iteration();
    ++units_;
    const ObjectHeader& h = decoder_.header();
    // Frames of a segment that has ended are final: kept here once the decoder releases them.
    for (uint32_t f : decoder_.unit().released) decoder_.frame(f, released_[f] = std::vector<Float3>(h.vertex_count));
    Frames frames({static_cast<py::ssize_t>(h.frame_count), static_cast<py::ssize_t>(h.vertex_count), py::ssize_t{3}});
    for (uint32_t f = 0; f < h.frame_count; ++f) {
      const std::span<Float3> out(reinterpret_cast<Float3*>(frames.mutable_data(f)), h.vertex_count);
      if (auto it = released_.find(f); it != released_.end())
        std::copy(it->second.begin(), it->second.end(), out.begin());
      else
        decoder_.frame(f, out);
    }
    const size_t taken = decoder_.units_taken();
    const uint64_t received = taken < parts_.units.size() ? parts_.units[taken].byte_offset : stream_.size();
    return py::make_tuple(units_, received, frames);
  }

 private:
  const StreamBytes stream_;
  Mesh3dDecoder decoder_;
  ContainerParts parts_;
  std::map<uint32_t, std::vector<Float3>> released_;
  size_t units_ = 0;
};

// Whether an argument is a stream: a bytes-like object other than a numpy
// array of frames.
bool is_stream(const py::handle& o) {
  if (!PyObject_CheckBuffer(o.ptr())) return false;
  if (!py::isinstance<py::array>(o)) return true;
  const py::array array = py::reinterpret_borrow<py::array>(o);
  return array.ndim() == 1 && array.itemsize() == 1;
}

// The decoded side of metrics(): frames with faces (`faces` when none are
// given), or a stream, decoded; `coding_order` when its vertices are not
// numbered as `original_faces` number them.
MeshSequence decoded_of(const py::handle& decoded, const Faces& faces, const py::object& decoded_faces, std::span<const Triangle> original_faces,
                        bool& coding_order) {
  if (is_stream(decoded)) {
    if (!decoded_faces.is_none()) throw usage("decoded_faces: the stream has its own faces");
    const StreamBytes bytes(decoded);
    coding_order = in_coding_order(bytes);
    py::gil_scoped_release release;
    return decode_mesh3d(bytes);
  }
  MeshSequence s = sequence_of(decoded.cast<Frames>(), decoded_faces.is_none() ? faces : decoded_faces.cast<Faces>());
  coding_order = !same_faces(original_faces, s.faces);  // in coding order, if anything
  return s;
}

py::dict metrics(const Frames& original, const py::handle& decoded, const Faces& faces, const py::object& decoded_faces) {
  const MeshSequence given = sequence_of(original, faces);
  bool coding_order = false;
  const MeshSequence b = decoded_of(decoded, faces, decoded_faces, given.faces, coding_order);
  const MeshSequence a = original_as_decoded(given, b, coding_order, "the decoded sequence");
  SequenceMetrics m;
  {
    py::gil_scoped_release release;
    m = compare_sequences(a, b);
  }
  py::dict out;
  out["kg_error"] = m.kg_error;
  out["rmse"] = m.rmse;
  out["max_error"] = m.max_error;
  out["psnr"] = m.psnr;
  out["sted_spatial"] = m.sted_spatial;
  out["sted_temporal"] = m.sted_temporal;
  out["sted"] = m.sted;
  return out;
}

py::list read_2d(const py::handle& stream) {
  py::list planes;
  const StreamBytes bytes(stream);
  Decoder decoder(bytes);
  while (decoder.next()) {
    py::array_t<int32_t> nodes({static_cast<py::ssize_t>(decoder.nodes().size()), py::ssize_t{2}});
    auto n = nodes.mutable_unchecked<2>();
    for (size_t i = 0; i < decoder.nodes().size(); ++i) {
      n(i, 0) = decoder.nodes()[i].x;
      n(i, 1) = decoder.nodes()[i].y;
    }
    py::dict plane;
    plane["intra"] = decoder.info().intra;
    plane["nodes"] = nodes;
    plane["triangles"] = faces_of(decoder.triangles());
    planes.append(plane);
  }
  return planes;
}

py::dict conform(const std::string& suite, const std::string& decoder_command) {
  std::ostringstream report;
  ConformResult r;
  {
    py::gil_scoped_release release;
    r = run_conformance({suite, decoder_command}, report);
  }
  py::dict out;
  out["passed"] = r.passed;
  out["failed"] = r.failed;
  out["skipped"] = r.skipped;
  out["report"] = report.str();
  return out;
}

}  // namespace
}  // namespace m4mesh

PYBIND11_MODULE(_native, m) {
  using namespace m4mesh;
  m.doc() = "m4mesh's library from Python (the m4mesh package re-exports it)";
  // Kept for the interpreter's lifetime (a static py::object would outlive it).
  static const py::handle error_class = py::object(py::module_::import("m4mesh._errors").attr("Error")).release();
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const Error& e) {
      // Usage errors name options as the command line spells them; Python's are keywords.
      auto spelled = [&e](const std::string& text) { return e.kind() == ErrorKind::kUsage ? keyword_spelling(text) : text; };
      const py::object error =
          error_class(spelled(e.what()), to_string(e.kind()), e.element(), e.plane(), e.bit_offset(), spelled(e.message()));
      PyErr_SetObject(error_class.ptr(), error.ptr());
    }
  });
  m.def("codecs", [] {
    std::vector<std::string> names;
    for (const Codec3d& c : codecs3d()) names.push_back(c.name);
    return names;
  }, "The registered 3D codecs' names.");
  m.def("encode", &encode, py::arg("frames"), py::arg("faces"), py::arg("codec") = "bfs3d", py::arg("hashes") = true,
        py::arg("hash_group") = 16, py::arg("reorder") = false, py::arg("position_blend") = py::none(), R"(A 3D stream (bytes) of frames float32[F, V, 3] with faces int32[T, 3].

codec: a name of m4mesh.codecs(), or "auto" (every codec at the target,
the smallest stream kept). Its options as keywords, dashes as underscores
(bits=12, me=5, theta_bits=6, noise="auto", …; True is "1"); target_kg=X,
target_psnr=Y or max_error=E (no decoded vertex farther than E from its
original, in the model's units; each a finite number above 0) searches the
codec's quality for the smallest stream that reaches it. hashes, hash_group, reorder,
position_blend (None: auto): as encode3d's.)");
  m.def("decode", &decode, py::arg("stream"),
        "(frames float32[F, V, 3], faces int32[T, 3]) of a 3D stream (bytes or any bytes-like object), every frame checked "
        "against its hash units. A stream of reorder=True numbers its vertices in coding order (a UserWarning says so): "
        "compare it with metrics(original, stream, faces).");
  py::class_<FrameIterator>(m, "frames",
                          "Iterates over a 3D stream's frames, float32[V, 3] each, in display order, holding one at a time "
                          "(decode() returns them all); every frame checked against its hash units, a mismatch raised as soon "
                          "as its hash unit is read. A group hash unit (encode's hash_group, 16 by default) follows its "
                          "group's last frame: the group's earlier frames are handed out before they are checked, so a "
                          "caller that must not show an unchecked frame waits for the group's end or encodes with "
                          "hash_group=1. faces: int32[T, 3], once the first frame is read.")
      .def(py::init<const py::handle&>(), py::arg("stream"))
      .def("__iter__", [](FrameIterator& self) -> FrameIterator& { return self; })
      .def("__next__", &FrameIterator::next)
      .def_property_readonly("faces", &FrameIterator::faces);
  py::class_<Progressive>(m, "progressive", "Iterates over a progressive stream's prefixes: (units, bytes received, frames) after each unit.")
      .def(py::init<const py::handle&>(), py::arg("stream"))
      .def("__iter__", [](Progressive& self) -> Progressive& { return self; })
      .def("__next__", &Progressive::next);
  m.def("metrics", &metrics, py::arg("original"), py::arg("decoded"), py::arg("faces"), py::arg("decoded_faces") = py::none(),
        R"(KG error (%), RMSE, max error, PSNR (dB), STED spatial, temporal and combined, as `m4mesh metrics`.

original: frames float32[F, V, 3] with `faces`. decoded: frames with the
same faces, or with `decoded_faces` when decode() gave others, or a stream
(bytes-like), decoded here. Vertices a stream of reorder=True numbered in
coding order are mapped back through the original's faces, as the command
line does; faces that are not the original's in any order are an error.
Coordinates that are not finite are an error.)");
  m.def("read_2d", &read_2d, py::arg("stream"),
        "A 2D stream's planes: a list of {'intra': bool, 'nodes': int32[N, 2] (half pixels), 'triangles': int32[T, 3]}.");
  m.def("conform", &conform, py::arg("suite"), py::arg("decoder") = "",
        "Runs a conformance suite (a folder with manifest.json) through m4mesh's decoder or the command `decoder` "
        "('mydec {in} {out}'): {'passed', 'failed', 'skipped', 'report'}.");
}
