// The single description of each syntax structure of §3. Each function is
// a template over an I/O policy (syntax/io.h): the same lines read, write,
// count and trace, so the directions cannot drift. Names, sizes and value
// constraints (§4) are written here and nowhere else.
#pragma once

#include <string>

#include "bitstream/start_codes.h"
#include "common/error.h"
#include "syntax/structures.h"
#include "syntax/values.h"
#include "syntax/vlc.h"

namespace m4mesh::syntax {

inline constexpr uint32_t kMaxMeshNodes = 65535;
inline constexpr uint32_t kMaxBoundaryNodes = 1023;
inline constexpr int kMaxDeltaLength = 11;
inline constexpr int32_t kMaxCoordinate = 1023;

inline std::string coordinate_message(size_t node, char axis, int32_t value) {
  return "node " + std::to_string(node) + " " + axis + " = " + std::to_string(value) + " outside 0…1023";
}

template <class IO>
void describe(IO& io, UniformGeometry& g) {
  io.field_in("nr_of_mesh_nodes_hori", 10, g.nr_of_mesh_nodes_hori, 2, 1023);
  io.field_in("nr_of_mesh_nodes_verti", 10, g.nr_of_mesh_nodes_verti, 2, 1023);
  io.field_in("mesh_rect_size_hori", 8, g.mesh_rect_size_hori, 1, 255);
  io.field_in("mesh_rect_size_verti", 8, g.mesh_rect_size_verti, 1, 255);
  io.field("triangle_split_code", 2, g.triangle_split_code);
}

template <class IO>
void describe(IO& io, DeltaCode& delta, const char* length_name, const char* bits_name) {
  io.vlc(length_name, delta_length_table(), delta.length);
  if (delta.length > 0) io.field(bits_name, delta.length, delta.bits);
}

template <class IO>
void describe(IO& io, DelaunayGeometry& g) {
  io.field_in("nr_of_mesh_nodes", 16, g.nr_of_mesh_nodes, 3, kMaxMeshNodes);
  io.field_in("nr_of_boundary_nodes", 10, g.nr_of_boundary_nodes, 3, kMaxBoundaryNodes);
  io.require(g.nr_of_boundary_nodes <= g.nr_of_mesh_nodes, ErrorKind::kOutOfRange,
             "nr_of_boundary_nodes", "exceeds nr_of_mesh_nodes");
  io.field("node0_x", 10, g.node0_x);
  io.field("node0_y", 10, g.node0_y);
  io.resize(g.deltas, g.nr_of_mesh_nodes - 1, "delta_x_len_vlc", 4);  // two 2-bit length codes at least
  int32_t x = static_cast<int32_t>(g.node0_x), y = static_cast<int32_t>(g.node0_y);
  for (size_t n = 0; n < g.deltas.size(); ++n) {
    describe(io, g.deltas[n].x, "delta_x_len_vlc", "delta_x");
    x += delta_value(g.deltas[n].x);
    if (x < 0 || x > kMaxCoordinate) io.fail(ErrorKind::kOutOfRange, "delta_x", coordinate_message(n + 1, 'x', x));
    describe(io, g.deltas[n].y, "delta_y_len_vlc", "delta_y");
    y += delta_value(g.deltas[n].y);
    if (y < 0 || y > kMaxCoordinate) io.fail(ErrorKind::kOutOfRange, "delta_y", coordinate_message(n + 1, 'y', y));
  }
}

template <class IO>
void describe(IO& io, MeshGeometry& g) {
  io.field("mesh_type_code", 2, g.mesh_type_code);
  io.require(g.mesh_type_code <= kMeshTypeDelaunay, ErrorKind::kReservedValue, "mesh_type_code",
             "reserved value");
  if (g.mesh_type_code == kMeshTypeUniform)
    describe(io, g.uniform);
  else
    describe(io, g.delaunay);
}

template <class IO>
void describe(IO& io, MeshMotion& m, uint32_t nr_of_mesh_nodes) {
  io.field("motion_range_code", 2, m.motion_range_code);
  io.require(m.motion_range_code != 0, ErrorKind::kReservedValue, "motion_range_code",
             "reserved value 0");
  const int r_size = static_cast<int>(m.motion_range_code) - 1;
  const VlcTable& table = motion_code_table();
  io.resize(m.nodes, nr_of_mesh_nodes, "node_motion_vector_flag");
  for (NodeMotion& n : m.nodes) {
    io.field("node_motion_vector_flag", 1, n.node_motion_vector_flag);
    if (n.node_motion_vector_flag) {
      io.vlc("delta_mv_x_vlc", table, n.delta_mv_x);
      if (r_size > 0 && n.delta_mv_x != 0) io.field("delta_mv_x_res", r_size, n.delta_mv_x_res);
      io.vlc("delta_mv_y_vlc", table, n.delta_mv_y);
      if (r_size > 0 && n.delta_mv_y != 0) io.field("delta_mv_y_res", r_size, n.delta_mv_y_res);
    }
  }
}

// A plane; `mesh_nodes` is nr_of_mesh_nodes of the current mesh (0 before
// the first I-plane) and is updated by an I-plane.
template <class IO>
void describe(IO& io, MeshObjectPlane& p, uint32_t& mesh_nodes) {
  io.start_code("mesh_object_plane_start_code", kMeshObjectPlaneStartCode);
  io.field("new_mesh_flag", 1, p.new_mesh_flag);
  if (p.new_mesh_flag) {
    describe(io, p.geometry);
    mesh_nodes = node_count(p.geometry);
  } else {
    io.require(mesh_nodes != 0, ErrorKind::kStructure, "new_mesh_flag",
               "a P-plane before any I-plane");
    describe(io, p.motion, mesh_nodes);
  }
  io.next_start_code();
}

}  // namespace m4mesh::syntax
