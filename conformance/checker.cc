#include "conformance/checker.h"

#include "decoder/mesh_object_decoder.h"
#include "mesh/cdt.h"
#include "syntax/describe.h"
#include "syntax/mesh_object.h"

namespace m4mesh {

namespace {

constexpr size_t kMaxGeometryReports = 100;

// The byte offset of the next plane start code or end code at or after `from`.
size_t find_plane_or_end_code(std::span<const uint8_t> s, size_t from) {
  for (size_t i = from; i + 3 < s.size(); ++i)
    if (s[i] == 0 && s[i + 1] == 0 && s[i + 2] == 1 && (s[i + 3] == 0xBD || s[i + 3] == 0xB1)) return i;
  return s.size();
}

class Checker {
 public:
  explicit Checker(std::span<const uint8_t> stream) : stream_(stream), reader_(stream.data(), stream.size()), io_(reader_) {}

  CheckReport run();

 private:
  void error(const Error& e) { report_.findings.push_back({true, e.kind(), e.plane(), e.element(), e.bit_offset(), e.message(), false, std::nullopt}); }
  void error(ErrorKind kind, int64_t plane, const std::string& element, uint64_t bit, const std::string& message) {
    report_.findings.push_back({true, kind, plane, element, static_cast<int64_t>(bit), message, false, std::nullopt});
  }
  void warning(int64_t plane, const std::string& element, uint64_t bit, const std::string& message) {
    report_.findings.push_back({false, ErrorKind::kStructure, plane, element, static_cast<int64_t>(bit), message, false, std::nullopt});
  }
  // Continues at the next plane or end code after `bit`; false when there is none.
  bool resync(uint64_t bit) {
    const size_t next = find_plane_or_end_code(stream_, static_cast<size_t>((bit + 7) / 8));
    if (next >= stream_.size()) return false;
    reader_.seek(uint64_t{next} * 8);
    return true;
  }
  bool check_geometry(const MeshObjectPlane& plane, int64_t index, uint64_t start);

  std::span<const uint8_t> stream_;
  BitReader reader_;
  syntax::ReadIO io_;
  CheckReport report_;
};

bool Checker::check_geometry(const MeshObjectPlane& plane, int64_t index, uint64_t start) {
  const MeshGeometry& geometry = plane.geometry;
  if (geometry.mesh_type_code == kMeshTypeUniform) return true;
  const std::vector<Point> nodes = delaunay_node_positions(geometry.delaunay);
  const uint32_t boundary = geometry.delaunay.nr_of_boundary_nodes;
  auto at = [&](NodeIndex node) { return node == kNoNode ? start : start + syntax::delaunay_node_offset(plane, node); };
  const std::vector<GeometryViolation> violations = delaunay_node_violations(nodes, boundary, kMaxGeometryReports);
  for (const GeometryViolation& v : violations) error(ErrorKind::kGeometry, index, "MeshGeometry", at(v.node), v.message);
  if (!violations.empty()) return false;
  try {
    const MeshTopology mesh = constrained_delaunay(nodes, boundary);
    method2_order(mesh.triangles, mesh.neighbours, nodes.size(), 0, boundary - 1);
  } catch (const GeometryError& e) {
    error(e.kind(), index, "MeshGeometry", at(e.node()), e.message());
    return false;
  } catch (const Error& e) {
    error(e.kind(), index, "MeshGeometry", start, e.message());
    return false;
  }
  return true;
}

CheckReport Checker::run() {
  try {
    io_.start_code("mesh_object_start_code", kMeshObjectStartCode);
  } catch (const Error& e) {
    error(e);
    if (!resync(0)) return report_;
  }
  uint32_t mesh_nodes = 0;
  bool mesh_valid = false;
  MeshObjectPlane plane;
  for (int64_t k = 0;; ++k) {
    const std::optional<uint32_t> next = nextbits_bytealigned(reader_);
    const uint64_t start = reader_.position();
    if (!next && reader_.bits_left() == 0) {
      warning(kNoPlane, "mesh_object_end_code", start, "mesh_object_end_code missing at the end of the data");
      break;
    }
    if (next != kMeshObjectPlaneStartCode) {
      io_.set_plane(kNoPlane);
      try {
        io_.start_code("mesh_object_end_code", kMeshObjectEndCode);
        if (reader_.bits_left() != 0)
          error(ErrorKind::kTrailingData, kNoPlane, "mesh_object_end_code", reader_.position(),
                std::to_string(reader_.bits_left() / 8) + " bytes after the end code");
        break;
      } catch (const Error& e) {
        error(e);
        if (!resync(start + 8)) break;
        --k;
        continue;
      }
    }
    io_.set_plane(k);
    report_.planes = k + 1;
    try {
      syntax::describe(io_, plane, mesh_nodes);
    } catch (const Error& e) {
      error(e);
      if (plane.new_mesh_flag || e.kind() == ErrorKind::kStructure) mesh_valid = false;
      if (!resync(start + 32)) break;
      continue;
    }
    for (uint64_t bit : start_code_emulations(stream_, start + 32, reader_.position()))
      warning(k, "", bit, "start-code emulation: 23 zero bits then a 1");
    if (plane.new_mesh_flag)
      mesh_valid = check_geometry(plane, k, start);
    else if (!mesh_valid)
      error(ErrorKind::kStructure, k, "new_mesh_flag", start + 32, "a P-plane after an I-plane that is not valid");
  }
  return report_;
}

}  // namespace

bool CheckReport::conformant() const { return errors() == 0; }

size_t CheckReport::errors() const {
  size_t n = 0;
  for (const Finding& f : findings) n += f.error;
  return n;
}

CheckReport check_stream(std::span<const uint8_t> stream) { return Checker(stream).run(); }

std::string format_finding(const Finding& f) {
  const std::string kind = f.error ? "error: " : "warning: ";
  if (f.mesh3d) {
    std::string where = f.unit ? "unit " + std::to_string(*f.unit) : "";
    if (f.plane != kNoPlane) where += (where.empty() ? "" : ", ") + std::string("frame ") + std::to_string(f.plane);
    const Error located(f.kind, f.element, kNoPlane, f.bit_offset, f.message);
    return kind + where + (where.empty() ? "" : ", ") + located.what();
  }
  const Error located(f.kind, f.element, f.plane, f.bit_offset, f.message);
  return kind + located.what();
}

std::vector<uint64_t> start_code_emulations(std::span<const uint8_t> stream, uint64_t from, uint64_t to) {
  std::vector<uint64_t> found;
  uint64_t zeros = 0;
  to = std::min<uint64_t>(to, uint64_t{stream.size()} * 8);
  for (uint64_t bit = from; bit < to; ++bit) {
    if ((stream[static_cast<size_t>(bit / 8)] >> (7 - bit % 8)) & 1) {
      if (zeros >= 23) found.push_back(bit - 23);
      zeros = 0;
    } else {
      ++zeros;
    }
  }
  return found;
}

}  // namespace m4mesh
