#include "conformance/coverage.h"

#include "conformance/checker.h"
#include "decoder/mesh_object_decoder.h"
#include "syntax/mesh_object.h"
#include "syntax/values.h"

namespace m4mesh {

namespace {

void geometry_classes(const MeshGeometry& g, std::set<std::string>& classes) {
  if (g.mesh_type_code == kMeshTypeUniform) {
    const UniformGeometry& u = g.uniform;
    classes.insert("mesh:uniform");
    classes.insert("split:" + std::to_string(u.triangle_split_code));
    for (uint32_t n : {u.nr_of_mesh_nodes_hori, u.nr_of_mesh_nodes_verti})
      if (n == 2 || n == 1023) classes.insert("uniform_nodes:" + std::to_string(n));
    if (u.nr_of_mesh_nodes_hori == 1023) classes.insert("uniform:1023x" + std::to_string(u.nr_of_mesh_nodes_verti));
    if (u.nr_of_mesh_nodes_verti == 1023) classes.insert("uniform:" + std::to_string(u.nr_of_mesh_nodes_hori) + "x1023");
    for (uint32_t size : {u.mesh_rect_size_hori, u.mesh_rect_size_verti})
      if (size == 1 || size == 255) classes.insert("rect_size:" + std::to_string(size));
    return;
  }
  const DelaunayGeometry& d = g.delaunay;
  classes.insert("mesh:delaunay");
  if (d.nr_of_mesh_nodes == 3) classes.insert("nodes:3");
  if (d.nr_of_mesh_nodes == 65535) classes.insert("nodes:65535");
  if (d.nr_of_boundary_nodes == 1023) classes.insert("boundary:1023");
  if (d.nr_of_mesh_nodes > d.nr_of_boundary_nodes) classes.insert("interior_nodes");
  for (const NodeDelta& delta : d.deltas) {
    classes.insert("delta_len:" + std::to_string(delta.x.length));
    classes.insert("delta_len:" + std::to_string(delta.y.length));
  }
  const std::vector<Point> nodes = delaunay_node_positions(d);
  for (const Point& p : nodes) {
    if (p.x == 0 || p.y == 0) classes.insert("coordinate:0");
    if (p.x == 1023 || p.y == 1023) classes.insert("coordinate:1023");
  }
  const uint32_t b = d.nr_of_boundary_nodes;
  for (uint32_t i = 0; i < b; ++i) {
    const int64_t turn = orient(nodes[(i + b - 1) % b], nodes[i], nodes[(i + 1) % b]);
    if (turn == 0) classes.insert("boundary:collinear");
    if (turn > 0) classes.insert("boundary:nonconvex");  // a clockwise turn on a counterclockwise polygon
  }
}

}  // namespace

std::set<std::string> value_classes(std::span<const uint8_t> stream, MotionMethod method) {
  std::set<std::string> classes;
  const MeshObject object = syntax::read_mesh_object(stream);
  if (!object.has_end_code) classes.insert("end_code:missing");
  DecoderOptions options;
  options.method = method;
  Decoder decoder(stream, options);
  std::vector<Point> previous;
  std::vector<Point> v;
  int intra = 0;
  for (const MeshObjectPlane& plane : object.planes) {
    decoder.next();
    const std::vector<Point> now(decoder.nodes().begin(), decoder.nodes().end());
    if (plane.new_mesh_flag) {
      ++intra;
      geometry_classes(plane.geometry, classes);
      if (plane.geometry.mesh_type_code == kMeshTypeDelaunay) {
        // Cocircular quads in the decoded triangulation.
        const std::span<const Triangle> t = decoder.triangles();
        const TriangleNeighbours neighbours = triangle_neighbours(t, now.size());
        for (size_t k = 0; k < t.size(); ++k)
          for (int j = 0; j < 3; ++j) {
            const uint32_t n = neighbours[k][j];
            if (n == kNoTriangle) continue;
            NodeIndex far = 0;
            for (NodeIndex x : t[n].v)
              if (x != t[k].v[(j + 1) % 3] && x != t[k].v[(j + 2) % 3]) far = x;
            if (incircle(now[t[k].v[0]], now[t[k].v[1]], now[t[k].v[2]], now[far]) == 0) classes.insert("cocircular");
          }
      }
    } else {
      const MotionRange range(plane.motion.motion_range_code);
      classes.insert("range:" + std::to_string(plane.motion.motion_range_code));
      const MotionOrder& order = decoder.motion_order();
      v.assign(now.size() + 1, Point{});
      int zero_run = 0;
      for (size_t k = 0; k < order.node.size(); ++k) {
        const NodeIndex n = order.node[k];
        const NodeMotion& coded = plane.motion.nodes[k];
        v[n] = Point{now[n].x - previous[n].x, now[n].y - previous[n].y};
        zero_run = coded.node_motion_vector_flag ? 0 : zero_run + 1;
        if (zero_run == 23) classes.insert("zero_run:23");
        if (!coded.node_motion_vector_flag) continue;
        const Point& a = v[order.pred_a[k]];
        const Point& b = v[order.pred_b[k]];
        const int sums[2] = {((a.x + b.x + 1) >> 1) + range.difference(coded.delta_mv_x, coded.delta_mv_x_res),
                             ((a.y + b.y + 1) >> 1) + range.difference(coded.delta_mv_y, coded.delta_mv_y_res)};
        for (int sum : sums) {
          if (sum < range.low) classes.insert("wrap:up");
          if (sum > range.high) classes.insert("wrap:down");
        }
        for (int component : {v[n].x, v[n].y}) {
          if (component == range.low) classes.insert("mv:low:" + std::to_string(plane.motion.motion_range_code));
          if (component == range.high) classes.insert("mv:high:" + std::to_string(plane.motion.motion_range_code));
        }
      }
      for (const Point& p : now)
        if (p.x < 0 || p.y < 0 || p.x > 1023 || p.y > 1023) classes.insert("position:outside");
    }
    previous = now;
  }
  if (intra > 1) classes.insert("intra:repeated");
  for (const Finding& f : check_stream(stream).findings)
    if (!f.error && f.message.starts_with("start-code emulation")) classes.insert("emulation");
  return classes;
}

std::set<std::string> required_value_classes() {
  std::set<std::string> required{"mesh:uniform", "mesh:delaunay", "nodes:3", "nodes:65535", "boundary:1023",
                                 "interior_nodes", "coordinate:0", "coordinate:1023", "boundary:collinear",
                                 "boundary:nonconvex", "cocircular", "uniform_nodes:2", "uniform:1023x2",
                                 "uniform:2x1023", "rect_size:1", "rect_size:255", "wrap:up", "wrap:down",
                                 "zero_run:23", "emulation", "intra:repeated", "end_code:missing", "position:outside"};
  for (int s = 0; s < 4; ++s) required.insert("split:" + std::to_string(s));
  for (int r = 1; r <= 3; ++r) {
    required.insert("range:" + std::to_string(r));
    required.insert("mv:low:" + std::to_string(r));
    required.insert("mv:high:" + std::to_string(r));
  }
  // Length 11 cannot occur in a valid stream (docs/decisions.md).
  for (int l = 0; l <= 10; ++l) required.insert("delta_len:" + std::to_string(l));
  return required;
}

}  // namespace m4mesh
