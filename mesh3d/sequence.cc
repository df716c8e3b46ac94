#include "mesh3d/sequence.h"

#include <fcntl.h>
#include <unistd.h>

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/parse_number.h"
#include "mesh/obj.h"
#include "mesh3d/frame_source.h"
#include "mesh3d/little_endian.h"
#include "mesh3d/ply.h"

namespace m4mesh {

namespace {

constexpr char kMagic[] = "M4SEQ1\n";
constexpr size_t kMagicSize = sizeof kMagic - 1;
constexpr uint64_t kMaxVertices = uint64_t{1} << 26;

Error io(const std::string& path, const std::string& message) {
  return Error(ErrorKind::kIo, "", kNoPlane, kNoOffset, (path == "-" ? "standard input" : path) + ": " + message);
}

class ByteReader {
 public:
  ByteReader(const std::vector<uint8_t>& bytes, const std::string& path, const char* format)
      : bytes_(bytes), path_(path), format_(format) {}
  uint32_t u32() {
    need(4);
    uint32_t v = 0;
    for (int i = 0; i < 4; ++i) v |= uint32_t{bytes_[pos_++]} << (8 * i);
    return v;
  }
  float f32() {
    const uint32_t bits = u32();
    float f;
    std::memcpy(&f, &bits, 4);
    return f;
  }
  void need(uint64_t n) const {
    if (pos_ + n > bytes_.size()) throw io(path_, std::string("truncated ") + format_ + " file");
  }
  size_t position() const { return pos_; }
  void skip(size_t n) {
    need(n);
    pos_ += n;
  }

 private:
  const std::vector<uint8_t>& bytes_;
  const std::string& path_;
  const char* format_;
  size_t pos_ = 0;
};

// Every frame's positions as binary32 x, y, z.
void put_positions(std::string& out, const std::vector<std::vector<Vec3>>& frames) {
  for (const std::vector<Vec3>& frame : frames)
    for (const Vec3& v : frame) {
      put_f32(out, static_cast<float>(v.x));
      put_f32(out, static_cast<float>(v.y));
      put_f32(out, static_cast<float>(v.z));
    }
}

// A frame's positions, every one finite.
void read_positions(ByteReader& r, std::vector<Vec3>& frame, const std::string& path) {
  for (Vec3& v : frame) {
    v.x = r.f32();
    v.y = r.f32();
    v.z = r.f32();
    if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z)) throw io(path, "non-finite position");
  }
}

// The vertex count, faces and, on mismatch, the frame named.
void check_same_connectivity(const MeshSequence& s, const MeshFrame& frame, const std::string& name) {
  if (frame.vertices.size() != s.vertex_count)
    throw input_error(name, 0, "has " + std::to_string(frame.vertices.size()) + " vertices where the first frame has " +
                                   std::to_string(s.vertex_count) + ": connectivity must stay fixed");
  if (!frame.faces.empty() && frame.faces != s.faces)
    throw input_error(name, 0, "its faces differ from the first frame's: connectivity must stay fixed");
}

MeshFrame read_obj_frame(const std::string& path) {
  ObjFrame obj = read_obj(path);
  MeshFrame frame;
  frame.vertices.reserve(obj.vertices.size());
  for (const auto& v : obj.vertices) frame.vertices.push_back({v[0], v[1], v[2]});
  frame.faces = std::move(obj.faces);
  frame.dropped = std::move(obj.dropped);
  return frame;
}

// An OBJ, OFF or PLY frame, by its extension, its positions rounded to
// binary32 as every other form holds them (so that the same frames code to
// the same stream from text, .m4seq, .pc2, glTF or Python).
MeshFrame read_frame_file(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  MeshFrame frame = extension == ".off" ? read_off(path) : extension == ".ply" ? read_ply(path) : read_obj_frame(path);
  for (Vec3& p : frame.vertices) p = {static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z)};
  return frame;
}

}  // namespace

MeshFrame read_off(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw io(path, "cannot open");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  // Tokens with their line numbers, comments removed.
  std::vector<std::pair<std::string_view, int64_t>> tokens;
  int64_t line = 1;
  for (size_t i = 0; i < text.size();) {
    const char c = text[i];
    if (c == '\n') {
      ++line;
      ++i;
    } else if (c == '#') {
      while (i < text.size() && text[i] != '\n') ++i;
    } else if (std::isspace(static_cast<unsigned char>(c))) {
      ++i;
    } else {
      const size_t start = i;
      while (i < text.size() && !std::isspace(static_cast<unsigned char>(text[i])) && text[i] != '#') ++i;
      tokens.push_back({std::string_view(text).substr(start, i - start), line});
    }
  }
  size_t t = 0;
  auto next = [&](const char* what) -> std::pair<std::string_view, int64_t> {
    if (t >= tokens.size()) throw input_error(path, line, std::string("unexpected end of file, expected ") + what);
    return tokens[t++];
  };
  auto integer = [&](const char* what, int64_t lo, int64_t hi) {
    const auto [token, at] = next(what);
    int64_t v = 0;
    auto r = std::from_chars(token.data(), token.data() + token.size(), v);
    if (r.ec != std::errc() || r.ptr != token.data() + token.size() || v < lo || v > hi)
      throw input_error(path, at, std::string("expected ") + what + " in " + std::to_string(lo) + "…" + std::to_string(hi) +
                                      ", found '" + std::string(token) + "'");
    return v;
  };
  auto number = [&](const char* what) {
    const auto [token, at] = next(what);
    double v = 0;
    if (parse_double(token.data(), token.data() + token.size(), v) != token.data() + token.size())
      throw input_error(path, at, std::string("expected ") + what + ", found '" + std::string(token) + "'");
    if (!std::isfinite(v)) throw input_error(path, at, "non-finite number '" + std::string(token) + "'");
    return v;
  };
  const auto [header, header_line] = next("OFF");
  if (header != "OFF") throw input_error(path, header_line, "expected the header 'OFF'");
  const int64_t vertices = integer("a vertex count", 0, static_cast<int64_t>(kMaxVertices));
  const int64_t faces = integer("a face count", 0, static_cast<int64_t>(4 * kMaxVertices));
  integer("an edge count", 0, INT64_MAX);
  MeshFrame frame;
  frame.vertices.reserve(static_cast<size_t>(std::min<int64_t>(vertices, static_cast<int64_t>(tokens.size()))));
  for (int64_t i = 0; i < vertices; ++i) {
    const double x = number("x"), y = number("y"), z = number("z");
    frame.vertices.push_back({x, y, z});
  }
  for (int64_t f = 0; f < faces; ++f) {
    const int64_t n = integer("a polygon size", 3, 1 << 16);
    std::vector<NodeIndex> polygon;
    for (int64_t k = 0; k < n; ++k) polygon.push_back(static_cast<NodeIndex>(integer("a vertex index", 0, vertices - 1)));
    for (size_t k = 1; k + 1 < polygon.size(); ++k) frame.faces.push_back(Triangle{{polygon[0], polygon[k], polygon[k + 1]}});
  }
  return frame;
}

namespace {

// A mesh stream given where frames are read: named as what it is, not
// parsed as a frame file.
void refuse_mesh_stream(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  unsigned char code[4] = {};
  if (!in.read(reinterpret_cast<char*>(code), 4) || code[0] != 0 || code[1] != 0 || code[2] != 1) return;
  if (code[3] == 0xBC)
    throw input_error(path, 0, "a 2D mesh stream, not 3D frames (2D streams are for decode, render, check and trace)");
  if (code[3] == 0xC4) throw input_error(path, 0, "a 3D stream, not frames: decode3d it first (-o frames.m4seq)");
}

}  // namespace

MeshSequence load_sequence(const std::string& path, bool progress) {
  namespace fs = std::filesystem;
  if (fs::is_regular_file(path)) refuse_mesh_stream(path);
  // Standard input holds a .m4seq file.
  if (path == "-" || (fs::is_regular_file(path) && fs::path(path).extension() == ".m4seq")) return read_binary_sequence(path);
  if (fs::is_regular_file(path) && fs::path(path).extension() == ".pc2") return read_pc2_sequence(path);
  std::vector<std::string> unused;
  const std::vector<std::string> files = frame_files(path, {".obj", ".off", ".ply"}, &unused);
  std::string extension = fs::path(files.front()).extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (progress && !unused.empty())
    std::fprintf(stderr, "warning: %s: %zu files not used (not %s frames), %s%s\n", path.c_str(), unused.size(), extension.c_str(),
                 unused.front().c_str(), unused.size() > 1 ? ", …" : "");
  if (const std::string gaps = numbering_gaps_warning(path, files); progress && !gaps.empty())
    std::fprintf(stderr, "warning: %s\n", gaps.c_str());
  const bool report_progress = progress && files.size() > 10 && isatty(fileno(stderr));
  MeshSequence sequence;
  for (size_t k = 0; k < files.size(); ++k) {
    MeshFrame frame = read_frame_file(files[k]);
    if (k == 0) {
      if (frame.vertices.size() < 3 || frame.faces.empty()) throw input_error(files[k], 0, "a mesh needs vertices and faces");
      if (const std::string note = dropped_records_note(files[k], frame.dropped, "positions and faces"); progress && !note.empty())
        std::fprintf(stderr, "note: %s\n", note.c_str());
      sequence.vertex_count = static_cast<uint32_t>(frame.vertices.size());
      sequence.faces = frame.faces;
    } else {
      check_same_connectivity(sequence, frame, files[k]);
    }
    sequence.frames.push_back(std::move(frame.vertices));
    if (report_progress) std::fprintf(stderr, "\rreading frame %zu/%zu", k + 1, files.size());
  }
  if (report_progress) std::fprintf(stderr, "\r%*s\r", 40, "");
  return sequence;
}

void write_binary_sequence(const MeshSequence& s, const std::string& path) {
  std::string out(kMagic, kMagicSize);
  put_u32(out, s.vertex_count);
  put_u32(out, static_cast<uint32_t>(s.faces.size()));
  put_u32(out, static_cast<uint32_t>(s.frames.size()));
  for (const Triangle& t : s.faces)
    for (NodeIndex v : t.v) put_u32(out, v);
  put_positions(out, s.frames);
  write_file_atomically(path, out);
}

MeshSequence read_binary_sequence(const std::string& path) {
  const std::vector<uint8_t> bytes = read_file(path);
  ByteReader r(bytes, path, ".m4seq");
  r.need(kMagicSize);
  if (std::memcmp(bytes.data(), kMagic, kMagicSize) != 0) throw io(path, "not a .m4seq file");
  r.skip(kMagicSize);
  MeshSequence s;
  s.vertex_count = r.u32();
  const uint32_t face_count = r.u32(), frame_count = r.u32();
  if (s.vertex_count < 3 || s.vertex_count > kMaxVertices) throw io(path, "vertex count out of range");
  // Everything the counts announce must be in the file before anything is allocated.
  r.need(uint64_t{face_count} * 12 + uint64_t{frame_count} * s.vertex_count * 12);
  s.faces.resize(face_count);
  for (Triangle& t : s.faces)
    for (NodeIndex& v : t.v) {
      v = r.u32();
      if (v >= s.vertex_count) throw io(path, "face index out of range");
    }
  s.frames.resize(frame_count);
  for (std::vector<Vec3>& frame : s.frames) {
    frame.resize(s.vertex_count);
    read_positions(r, frame, path);
  }
  if (r.position() != bytes.size()) throw io(path, "bytes after the last frame");
  return s;
}

MeshSequence read_pc2_sequence(const std::string& path) {
  namespace fs = std::filesystem;
  const std::string obj = pc2_faces_path(path);
  if (!fs::is_regular_file(obj)) throw io(path, "a PC2 file takes its faces from " + obj + ", which is missing");
  const MeshFrame first = read_obj_frame(obj);
  const std::vector<uint8_t> bytes = read_file(path);
  ByteReader r(bytes, path, "PC2");
  static const char kSignature[12] = {'P', 'O', 'I', 'N', 'T', 'C', 'A', 'C', 'H', 'E', '2', '\0'};
  r.need(sizeof kSignature);
  if (std::memcmp(bytes.data(), kSignature, sizeof kSignature) != 0) throw io(path, "not a PC2 file (no POINTCACHE2 signature)");
  r.skip(sizeof kSignature);
  if (r.u32() != 1) throw io(path, "PC2 version other than 1");
  const uint32_t points = r.u32();
  r.f32();  // start frame
  r.f32();  // sample rate
  const uint32_t samples = r.u32();
  if (points != first.vertices.size())
    throw io(path, std::to_string(points) + " points where " + obj + " has " + std::to_string(first.vertices.size()) + " vertices");
  if (points < 3 || first.faces.empty()) throw input_error(obj, 0, "a mesh needs vertices and faces");
  if (samples == 0) throw io(path, "no samples");
  r.need(uint64_t{samples} * points * 12);
  MeshSequence s;
  s.vertex_count = points;
  s.faces = first.faces;
  s.frames.resize(samples);
  for (std::vector<Vec3>& frame : s.frames) {
    frame.resize(points);
    read_positions(r, frame, path);
  }
  if (r.position() != bytes.size()) throw io(path, "bytes after the last sample");
  return s;
}

void write_pc2_sequence(const MeshSequence& s, const std::string& path) {
  namespace fs = std::filesystem;
  std::string out("POINTCACHE2", 12);
  put_u32(out, 1);
  put_u32(out, s.vertex_count);
  put_f32(out, 0.0f);  // start frame
  put_f32(out, 1.0f);  // sample rate
  put_u32(out, static_cast<uint32_t>(s.frames.size()));
  put_positions(out, s.frames);
  write_obj_frame(s.frames.at(0), s.faces, pc2_faces_path(path));
  write_file_atomically(path, out);
}

namespace {

// A file read at offsets (pread: safe from several threads at once).
class PositionedFile {
 public:
  explicit PositionedFile(const std::string& path) : path_(path), fd_(::open(path.c_str(), O_RDONLY | O_CLOEXEC)) {
    if (fd_ < 0) throw io(path, "cannot open");
  }
  ~PositionedFile() { ::close(fd_); }
  PositionedFile(const PositionedFile&) = delete;
  PositionedFile& operator=(const PositionedFile&) = delete;

  uint64_t size() const {
    const off_t end = ::lseek(fd_, 0, SEEK_END);
    if (end < 0) throw io(path_, "cannot tell its size");
    return static_cast<uint64_t>(end);
  }
  void read(uint64_t offset, std::span<uint8_t> out) const {
    size_t done = 0;
    while (done < out.size()) {
      const ssize_t n = ::pread(fd_, out.data() + done, out.size() - done, static_cast<off_t>(offset + done));
      if (n <= 0) throw io(path_, n == 0 ? "truncated" : "read error");
      done += static_cast<size_t>(n);
    }
  }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  int fd_;
};

// Frames stored as binary32 x, y, z per vertex, one after the other from
// `first_frame` (a .m4seq or .pc2 file).
class PackedFramesSource final : public FrameSource {
 public:
  PackedFramesSource(std::unique_ptr<PositionedFile> file, uint64_t first_frame, uint32_t vertex_count, uint32_t frame_count,
                     std::vector<Triangle> faces)
      : file_(std::move(file)), first_frame_(first_frame), vertex_count_(vertex_count), frame_count_(frame_count), faces_(std::move(faces)) {}

  uint32_t vertex_count() const override { return vertex_count_; }
  std::span<const Triangle> faces() const override { return faces_; }
  uint32_t frame_count() const override { return frame_count_; }
  void read(uint32_t index, std::span<Vec3> out) const override {
    std::vector<uint8_t> bytes(size_t{vertex_count_} * 12);
    file_->read(first_frame_ + uint64_t{index} * bytes.size(), bytes);
    ByteReader r(bytes, file_->path(), "frame");
    for (Vec3& v : out.first(vertex_count_)) {
      v.x = r.f32();
      v.y = r.f32();
      v.z = r.f32();
    }
  }

 private:
  std::unique_ptr<PositionedFile> file_;
  uint64_t first_frame_;
  uint32_t vertex_count_, frame_count_;
  std::vector<Triangle> faces_;
};

// One frame file per frame, parsed when read; each must have the first's
// vertex count and faces.
class FrameFilesSource final : public FrameSource {
 public:
  FrameFilesSource(std::vector<std::string> files, MeshFrame first) : files_(std::move(files)) {
    shape_.vertex_count = static_cast<uint32_t>(first.vertices.size());
    shape_.faces = std::move(first.faces);
  }

  uint32_t vertex_count() const override { return shape_.vertex_count; }
  std::span<const Triangle> faces() const override { return shape_.faces; }
  uint32_t frame_count() const override { return static_cast<uint32_t>(files_.size()); }
  void read(uint32_t index, std::span<Vec3> out) const override {
    const MeshFrame frame = read_frame_file(files_.at(index));
    check_same_connectivity(shape_, frame, files_[index]);
    std::copy(frame.vertices.begin(), frame.vertices.end(), out.begin());
  }

 private:
  std::vector<std::string> files_;
  MeshSequence shape_;  // the vertex count and faces, no frames
};

// A .m4seq file's frames where it holds more than `in_memory` vertex-frames.
std::unique_ptr<FrameSource> open_m4seq(const std::string& path, uint64_t in_memory) {
  auto file = std::make_unique<PositionedFile>(path);
  std::vector<uint8_t> head(kMagicSize + 12);
  if (file->size() < head.size()) throw io(path, "truncated .m4seq file");
  file->read(0, head);
  if (std::memcmp(head.data(), kMagic, kMagicSize) != 0) throw io(path, "not a .m4seq file");
  ByteReader r(head, path, ".m4seq");
  r.skip(kMagicSize);
  const uint32_t vertices = r.u32(), face_count = r.u32(), frames = r.u32();
  if (vertices < 3 || vertices > kMaxVertices) throw io(path, "vertex count out of range");
  const uint64_t first_frame = head.size() + uint64_t{face_count} * 12;
  const uint64_t expected = first_frame + uint64_t{frames} * vertices * 12;
  if (file->size() < expected) throw io(path, "truncated .m4seq file");
  if (file->size() > expected) throw io(path, "bytes after the last frame");
  if (uint64_t{frames} * vertices <= in_memory) return nullptr;
  std::vector<uint8_t> face_bytes(size_t{face_count} * 12);
  file->read(head.size(), face_bytes);
  ByteReader f(face_bytes, path, ".m4seq");
  std::vector<Triangle> faces(face_count);
  for (Triangle& t : faces)
    for (NodeIndex& v : t.v) {
      v = f.u32();
      if (v >= vertices) throw io(path, "face index out of range");
    }
  return std::make_unique<PackedFramesSource>(std::move(file), first_frame, vertices, frames, std::move(faces));
}

// A .pc2 file's frames where it holds more than `in_memory` vertex-frames.
std::unique_ptr<FrameSource> open_pc2(const std::string& path, uint64_t in_memory) {
  auto file = std::make_unique<PositionedFile>(path);
  constexpr size_t kHeader = 32;
  std::vector<uint8_t> head(kHeader);
  if (file->size() < kHeader || (file->read(0, head), std::memcmp(head.data(), "POINTCACHE2", 12) != 0)) return nullptr;
  ByteReader r(head, path, "PC2");
  r.skip(16);  // the signature and the version
  const uint32_t points = r.u32();
  r.skip(8);  // the start frame and the sample rate
  const uint32_t samples = r.u32();
  if (uint64_t{samples} * points <= in_memory || file->size() != kHeader + uint64_t{samples} * points * 12) return nullptr;
  const std::string obj = pc2_faces_path(path);
  if (!std::filesystem::is_regular_file(obj)) return nullptr;
  MeshFrame first = read_obj_frame(obj);
  if (first.vertices.size() != points || first.faces.empty()) return nullptr;  // read_pc2_sequence names the error
  return std::make_unique<PackedFramesSource>(std::move(file), kHeader, points, samples, std::move(first.faces));
}

}  // namespace

std::unique_ptr<FrameSource> open_sequence(const std::string& path, bool progress, uint64_t in_memory) {
  namespace fs = std::filesystem;
  if (path != "-" && fs::is_regular_file(path)) {
    refuse_mesh_stream(path);
    const std::string extension = fs::path(path).extension().string();
    std::unique_ptr<FrameSource> large = extension == ".m4seq" ? open_m4seq(path, in_memory) : extension == ".pc2" ? open_pc2(path, in_memory) : nullptr;
    if (large) return large;
  } else if (path != "-") {
    std::vector<std::string> files = frame_files(path, {".obj", ".off", ".ply"});
    MeshFrame first = read_frame_file(files.front());
    if (uint64_t{files.size()} * first.vertices.size() > in_memory && first.vertices.size() >= 3 && !first.faces.empty()) {
      if (const std::string note = dropped_records_note(files.front(), first.dropped, "positions and faces"); progress && !note.empty())
        std::fprintf(stderr, "note: %s\n", note.c_str());
      if (const std::string gaps = numbering_gaps_warning(path, files); progress && !gaps.empty())
        std::fprintf(stderr, "warning: %s\n", gaps.c_str());
      return std::make_unique<FrameFilesSource>(std::move(files), std::move(first));
    }
  }
  return std::make_unique<SequenceSource>(load_sequence(path, progress));
}

std::string pc2_faces_path(const std::string& path) { return std::filesystem::path(path).replace_extension(".obj").string(); }

std::string obj_frame_name(size_t frame_index) {
  char name[32];
  std::snprintf(name, sizeof name, "%04zu.obj", frame_index + 1);
  return name;
}

void write_obj_frame(std::span<const Vec3> positions, std::span<const Triangle> faces, const std::string& path) {
  std::string text;
  char line[96];
  for (const Vec3& v : positions) {
    std::snprintf(line, sizeof line, "v %.9g %.9g %.9g\n", v.x, v.y, v.z);
    text += line;
  }
  for (const Triangle& t : faces) {
    std::snprintf(line, sizeof line, "f %u %u %u\n", t.v[0] + 1, t.v[1] + 1, t.v[2] + 1);
    text += line;
  }
  write_file_atomically(path, text);
}

void write_obj_frames(const MeshSequence& s, const std::string& folder) {
  std::filesystem::create_directories(folder);
  for (size_t k = 0; k < s.frames.size(); ++k)
    write_obj_frame(s.frames[k], s.faces, (std::filesystem::path(folder) / obj_frame_name(k)).string());
}

}  // namespace m4mesh
