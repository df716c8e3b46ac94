#include "mesh3d/ply.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>

#include "common/atomic_file.h"
#include "common/bit_cast.h"
#include "common/error.h"
#include "common/parse_number.h"
#include "mesh3d/little_endian.h"

namespace m4mesh {

namespace {

Error ply_error(const std::string& path, const std::string& message) {
  return Error(ErrorKind::kInput, "", kNoPlane, kNoOffset, path + ": " + message);
}

enum class Scalar { kInt8, kUint8, kInt16, kUint16, kInt32, kUint32, kFloat32, kFloat64 };

bool scalar_of(const std::string& name, Scalar& type) {
  static const std::pair<const char*, Scalar> kNames[] = {
      {"char", Scalar::kInt8},     {"int8", Scalar::kInt8},     {"uchar", Scalar::kUint8},  {"uint8", Scalar::kUint8},
      {"short", Scalar::kInt16},   {"int16", Scalar::kInt16},   {"ushort", Scalar::kUint16}, {"uint16", Scalar::kUint16},
      {"int", Scalar::kInt32},     {"int32", Scalar::kInt32},   {"uint", Scalar::kUint32},  {"uint32", Scalar::kUint32},
      {"float", Scalar::kFloat32}, {"float32", Scalar::kFloat32}, {"double", Scalar::kFloat64}, {"float64", Scalar::kFloat64}};
  for (const auto& [n, t] : kNames)
    if (name == n) {
      type = t;
      return true;
    }
  return false;
}

size_t size_of(Scalar type) {
  switch (type) {
    case Scalar::kInt8: case Scalar::kUint8: return 1;
    case Scalar::kInt16: case Scalar::kUint16: return 2;
    case Scalar::kInt32: case Scalar::kUint32: case Scalar::kFloat32: return 4;
    case Scalar::kFloat64: return 8;
  }
  return 0;
}

struct Property {
  std::string name;
  Scalar type = Scalar::kFloat32;
  bool list = false;
  Scalar count_type = Scalar::kUint8;
};

struct Element {
  std::string name;
  uint64_t count = 0;
  std::vector<Property> properties;
};

// Values of the body, in ASCII tokens or binary little-endian, each bounds-checked.
class Body {
 public:
  Body(const std::vector<uint8_t>& bytes, size_t start, bool ascii, const std::string& path)
      : bytes_(bytes), position_(start), ascii_(ascii), path_(path) {}

  double value(Scalar type) {
    if (ascii_) return token();
    const size_t n = size_of(type);
    if (position_ + n > bytes_.size()) throw ply_error(path_, "the data ends early");
    uint64_t raw = 0;
    for (size_t i = 0; i < n; ++i) raw |= uint64_t{bytes_[position_ + i]} << (8 * i);
    position_ += n;
    switch (type) {
      case Scalar::kInt8: return static_cast<int8_t>(raw);
      case Scalar::kUint8: return static_cast<uint8_t>(raw);
      case Scalar::kInt16: return static_cast<int16_t>(raw);
      case Scalar::kUint16: return static_cast<uint16_t>(raw);
      case Scalar::kInt32: return static_cast<int32_t>(raw);
      case Scalar::kUint32: return static_cast<uint32_t>(raw);
      case Scalar::kFloat32: return bit_cast<float>(static_cast<uint32_t>(raw));
      case Scalar::kFloat64: return bit_cast<double>(raw);
    }
    return 0;
  }
  // Whether `count` items can still follow, each of at least `bytes` bytes
  // in binary or `values` numbers (two characters each at least) in ASCII.
  bool holds(uint64_t count, uint64_t bytes, uint64_t values) const {
    const uint64_t least = std::max<uint64_t>(ascii_ ? 2 * values : bytes, 1);
    return count <= (bytes_.size() - position_) / least;
  }
  bool at_end() {
    if (ascii_)
      while (position_ < bytes_.size() && std::isspace(bytes_[position_])) ++position_;
    return position_ == bytes_.size();
  }

 private:
  double token() {
    while (position_ < bytes_.size() && std::isspace(bytes_[position_])) ++position_;
    const char* begin = reinterpret_cast<const char*>(bytes_.data()) + position_;
    const char* end = reinterpret_cast<const char*>(bytes_.data()) + bytes_.size();
    double v = 0;
    const char* next = parse_double(begin, end, v);
    if (next == begin) throw ply_error(path_, "a value that is not a number, or the data ends early");
    position_ += static_cast<size_t>(next - begin);
    return v;
  }

  const std::vector<uint8_t>& bytes_;
  size_t position_;
  bool ascii_;
  const std::string& path_;
};

}  // namespace

MeshFrame read_ply(const std::string& path) {
  const std::vector<uint8_t> bytes = read_file(path);
  const std::string text(bytes.begin(), bytes.end());
  const size_t header_end = text.find("end_header");
  if (text.rfind("ply", 0) != 0 || header_end == std::string::npos) throw ply_error(path, "not a PLY file (no 'ply' … 'end_header')");
  const size_t body_start = text.find('\n', header_end);
  if (body_start == std::string::npos) throw ply_error(path, "no data after the header");
  std::istringstream header(text.substr(0, header_end));
  std::string line;
  bool ascii = false, format = false;
  std::vector<Element> elements;
  while (std::getline(header, line)) {
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    if (keyword == "format") {
      std::string kind;
      words >> kind;
      if (kind != "ascii" && kind != "binary_little_endian") throw ply_error(path, "format " + kind + ": m4mesh reads ascii and binary_little_endian");
      ascii = kind == "ascii";
      format = true;
    } else if (keyword == "element") {
      Element e;
      words >> e.name >> e.count;
      if (!words) throw ply_error(path, "a malformed element line: " + line);
      elements.push_back(e);
    } else if (keyword == "property") {
      if (elements.empty()) throw ply_error(path, "a property before any element");
      Property p;
      std::string type;
      words >> type;
      if (type == "list") {
        std::string count_type, item_type;
        words >> count_type >> item_type >> p.name;
        p.list = true;
        if (!scalar_of(count_type, p.count_type) || !scalar_of(item_type, p.type)) throw ply_error(path, "an unknown type: " + line);
      } else {
        words >> p.name;
        if (!scalar_of(type, p.type)) throw ply_error(path, "an unknown type: " + line);
      }
      elements.back().properties.push_back(p);
    }
  }
  if (!format) throw ply_error(path, "no format line");
  Body body(bytes, body_start + 1, ascii, path);
  MeshFrame frame;
  for (const Element& e : elements) {
    uint64_t least = 0;  // bytes per item at least
    for (const Property& p : e.properties) least += size_of(p.list ? p.count_type : p.type);
    if (!body.holds(e.count, least, e.properties.size())) throw ply_error(path, "element " + e.name + ": more items than the data holds");
    const bool vertices = e.name == "vertex", faces = e.name == "face";
    if (vertices) {
      if (e.count > (uint64_t{1} << 26)) throw ply_error(path, "too many vertices");
      frame.vertices.resize(static_cast<size_t>(e.count));
    }
    for (uint64_t i = 0; i < e.count; ++i)
      for (const Property& p : e.properties) {
        if (!p.list) {
          const double v = body.value(p.type);
          if (vertices && (p.name == "x" || p.name == "y" || p.name == "z")) {
            if (!std::isfinite(v)) throw ply_error(path, "vertex " + std::to_string(i) + ": a coordinate that is not finite");
            Vec3& vertex = frame.vertices[static_cast<size_t>(i)];  // i < count ≤ 2^26
            (p.name == "x" ? vertex.x : p.name == "y" ? vertex.y : vertex.z) = v;
          }
          continue;
        }
        const double n = body.value(p.count_type);
        if (n < 0 || n > 1 << 16 || n != std::floor(n)) throw ply_error(path, "element " + e.name + " " + std::to_string(i) + ": a bad list length");
        std::vector<NodeIndex> polygon;
        for (int k = 0; k < static_cast<int>(n); ++k) {
          const double index = body.value(p.type);
          if (faces && (p.name == "vertex_indices" || p.name == "vertex_index")) {
            if (index < 0 || index >= static_cast<double>(frame.vertices.size()) || index != std::floor(index))
              throw ply_error(path, "face " + std::to_string(i) + ": a vertex index out of range");
            polygon.push_back(static_cast<NodeIndex>(index));
          }
        }
        if (polygon.size() >= 3)
          for (size_t k = 1; k + 1 < polygon.size(); ++k) frame.faces.push_back(Triangle{{polygon[0], polygon[k], polygon[k + 1]}});
        else if (faces && !polygon.empty())
          throw ply_error(path, "face " + std::to_string(i) + ": fewer than 3 vertices");
      }
  }
  if (!body.at_end()) throw ply_error(path, "data after the last element");
  return frame;
}

void write_ply_frame(std::span<const Vec3> positions, std::span<const Triangle> faces, const std::string& path) {
  std::string out = "ply\nformat binary_little_endian 1.0\ncomment m4mesh\nelement vertex " + std::to_string(positions.size()) +
                    "\nproperty float x\nproperty float y\nproperty float z\nelement face " + std::to_string(faces.size()) +
                    "\nproperty list uchar int vertex_indices\nend_header\n";
  for (const Vec3& v : positions) {
    put_f32(out, static_cast<float>(v.x));
    put_f32(out, static_cast<float>(v.y));
    put_f32(out, static_cast<float>(v.z));
  }
  for (const Triangle& t : faces) {
    out += static_cast<char>(3);
    for (NodeIndex v : t.v) put_u32(out, v);
  }
  write_file_atomically(path, out);
}

}  // namespace m4mesh
