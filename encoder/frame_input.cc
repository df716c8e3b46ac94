#include "encoder/frame_input.h"

#include <cmath>
#include <map>

#include "common/error.h"

namespace m4mesh {

namespace {

constexpr double kCoordinateLimit = 1 << 30;

std::vector<Point> quantize(const ObjFrame& frame, double scale, const std::string& name) {
  std::vector<Point> points;
  points.reserve(frame.vertices.size());
  for (size_t i = 0; i < frame.vertices.size(); ++i) {
    const double x = std::nearbyint(frame.vertices[i][0] * scale), y = std::nearbyint(frame.vertices[i][1] * scale);
    if (!(std::abs(x) <= kCoordinateLimit && std::abs(y) <= kCoordinateLimit))
      throw input_error(name, 0, "vertex " + std::to_string(i + 1) + " does not fit half-pixel integers after scaling");
    points.push_back(Point{static_cast<int32_t>(x), static_cast<int32_t>(y)});
  }
  return points;
}

// The boundary of a triangle mesh as one closed loop of vertices.
std::vector<NodeIndex> boundary_loop(const std::vector<Triangle>& faces, const std::string& name) {
  std::map<std::pair<NodeIndex, NodeIndex>, int> directed;
  for (const Triangle& t : faces)
    for (int j = 0; j < 3; ++j) ++directed[{t.v[j], t.v[(j + 1) % 3]}];
  std::map<NodeIndex, NodeIndex> next;
  for (const auto& [edge, count] : directed) {
    if (count > 1) throw input_error(name, 0, "the mesh is not manifold or not consistently oriented");
    if (directed.count({edge.second, edge.first})) continue;
    if (!next.emplace(edge.first, edge.second).second)
      throw input_error(name, 0, "the boundary passes twice through vertex " + std::to_string(edge.first + 1));
  }
  if (next.empty()) throw input_error(name, 0, "the mesh has no boundary (a Delaunay mesh needs one)");
  std::vector<NodeIndex> loop{next.begin()->first};
  while (true) {
    const NodeIndex following = next.at(loop.back());
    if (following == loop.front()) break;
    loop.push_back(following);
    if (loop.size() > next.size()) break;
  }
  if (loop.size() != next.size())
    throw input_error(name, 0, "the mesh has " + std::to_string(next.size()) + " boundary vertices in more than one loop");
  return loop;
}

}  // namespace

bool detect_uniform(const std::vector<Point>& nodes, const std::vector<Triangle>& triangles, UniformParams& params) {
  if (nodes.size() < 4 || nodes[0] != Point{0, 0} || nodes[1].y != 0 || nodes[1].x <= 0) return false;
  UniformParams p;
  p.dx = static_cast<uint32_t>(nodes[1].x);
  while (p.cols < nodes.size() && nodes[p.cols].y == 0) ++p.cols;
  if (p.cols < 2 || p.cols > 1023 || nodes.size() % p.cols != 0 || p.dx > 255) return false;
  p.rows = static_cast<uint32_t>(nodes.size() / p.cols);
  if (p.rows < 2 || p.rows > 1023 || nodes[p.cols].y <= 0 || nodes[p.cols].y > 255) return false;
  p.dy = static_cast<uint32_t>(nodes[p.cols].y);
  if (uniform_nodes(p) != nodes) return false;
  const std::vector<Triangle> given = canonical_triangles(triangles, nodes);
  for (p.split = 0; p.split < 4; ++p.split) {
    if (canonical_triangles(uniform_triangles(p), nodes) == given) {
      params = p;
      return true;
    }
  }
  return false;
}

FrameInput planes_from_frames(const std::vector<ObjFrame>& frames, const std::vector<std::string>& names, double scale) {
  if (frames.empty()) throw Error(ErrorKind::kInput, "", kNoPlane, kNoOffset, "no frames");
  if (!(scale > 0) || !std::isfinite(scale)) throw usage_error("the scale must be positive");
  const ObjFrame& first = frames[0];
  const size_t count = first.vertices.size();
  if (count < 3 || count > 1023 * 1023) throw input_error(names[0], 0, "a mesh needs 3 … 1046529 vertices");
  // z is not coded: a mesh that is not flat is a 3D mesh, not one to drop z from.
  for (size_t k = 0; k < frames.size(); ++k)
    for (size_t i = 0; i < frames[k].vertices.size(); ++i)
      if (frames[k].vertices[i][2] != first.vertices[0][2])
        throw input_error(names[k], i < frames[k].vertex_lines.size() ? frames[k].vertex_lines[i] : 0,
                          "vertex " + std::to_string(i + 1) + " has z " + std::to_string(frames[k].vertices[i][2]) + " where " + names[0] +
                              "'s vertex 1 has " + std::to_string(first.vertices[0][2]) +
                              ": a 3D mesh (the 2D mesh object codes flat meshes, x and y; m4mesh encode3d codes 3D sequences)");
  for (size_t k = 1; k < frames.size(); ++k) {
    if (frames[k].vertices.size() != count)
      throw input_error(names[k], 0, "has " + std::to_string(frames[k].vertices.size()) + " vertices where the first frame has " +
                                         std::to_string(count) + " (connectivity must stay fixed)");
    if (!frames[k].faces.empty() && frames[k].faces != first.faces)
      throw input_error(names[k], 0, "its faces differ from the first frame's (connectivity must stay fixed)");
  }

  FrameInput input;
  MeshPlane intra;
  const std::vector<Point> first_points = quantize(first, scale, names[0]);
  if (detect_uniform(first_points, first.faces, intra.info.uniform)) {
    intra.info.kind = MeshKind::kUniform;
    for (NodeIndex i = 0; i < count; ++i) input.input_vertex.push_back(i);
  } else {
    intra.info.kind = MeshKind::kDelaunay;
    // A Delaunay I-plane's nodes lie in 0 … 1023: name the OBJ vertex that does not.
    for (size_t i = 0; i < count; ++i)
      if (first_points[i].x < 0 || first_points[i].x > 1023 || first_points[i].y < 0 || first_points[i].y > 1023)
        throw input_error(names[0], i < first.vertex_lines.size() ? first.vertex_lines[i] : 0,
                          "vertex " + std::to_string(i + 1) + " lies at (" + std::to_string(first_points[i].x) + ", " +
                              std::to_string(first_points[i].y) + ") half pixels, outside 0 … 1023 (a Delaunay I-plane's nodes; see --scale)");
    input.input_vertex = boundary_loop(first.faces, names[0]);
    if (input.input_vertex.size() > 1023) throw input_error(names[0], 0, "more than 1023 boundary vertices");
    intra.info.boundary = static_cast<uint32_t>(input.input_vertex.size());
    std::vector<uint8_t> on_boundary(count, 0);
    for (NodeIndex v : input.input_vertex) on_boundary[v] = 1;
    for (NodeIndex i = 0; i < count; ++i)
      if (!on_boundary[i]) input.input_vertex.push_back(i);
  }
  std::vector<NodeIndex> node_of_vertex(count);
  for (NodeIndex i = 0; i < count; ++i) node_of_vertex[input.input_vertex[i]] = i;
  auto plane_nodes = [&](const std::vector<Point>& points) {
    std::vector<Point> nodes(count);
    for (NodeIndex i = 0; i < count; ++i) nodes[i] = points[input.input_vertex[i]];
    return nodes;
  };
  intra.nodes = plane_nodes(first_points);
  intra.triangles = first.faces;
  for (Triangle& t : intra.triangles)
    for (NodeIndex& v : t.v) v = node_of_vertex[v];
  input.planes.push_back(std::move(intra));
  for (size_t k = 1; k < frames.size(); ++k) {
    MeshPlane inter;
    inter.info.intra = false;
    inter.nodes = plane_nodes(quantize(frames[k], scale, names[k]));
    input.planes.push_back(std::move(inter));
  }
  return input;
}

}  // namespace m4mesh
