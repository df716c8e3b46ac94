#include "decoder/mesh_object_decoder.h"

#include "mesh/cdt.h"
#include "mesh/decoded_text.h"
#include "mesh/uniform.h"
#include "syntax/mesh_object.h"
#include "syntax/values.h"

namespace m4mesh {

namespace {

// Positions after motion are not range-limited (§7.2); this decoder keeps
// them in 32 bits and stops, naming the plane, before they could overflow.
constexpr int32_t kPositionLimit = 1 << 30;

Error plane_error(ErrorKind kind, const char* element, int64_t plane, uint64_t offset,
                  const std::string& message) {
  return Error(kind, element, plane, static_cast<int64_t>(offset), message);
}

}  // namespace

Decoder::Decoder(std::span<const uint8_t> stream, const DecoderOptions& options)
    : options_(options), reader_(stream, options.trace) {}

bool Decoder::next() {
  const uint64_t plane_start = reader_.position();
  if (!reader_.next(plane_)) return false;
  if (plane_.new_mesh_flag)
    decode_geometry(plane_.geometry, plane_start);
  else
    decode_motion(plane_.motion, plane_start);
  return true;
}

void Decoder::decode_geometry(const MeshGeometry& g, uint64_t plane_start) {
  info_ = PlaneInfo{};
  info_.intra = true;
  if (g.mesh_type_code == kMeshTypeUniform) {
    const UniformGeometry& u = g.uniform;
    info_.kind = MeshKind::kUniform;
    info_.uniform = UniformParams{u.nr_of_mesh_nodes_hori, u.nr_of_mesh_nodes_verti, u.mesh_rect_size_hori,
                                  u.mesh_rect_size_verti, u.triangle_split_code};
  } else {
    info_.kind = MeshKind::kDelaunay;
    info_.boundary = g.delaunay.nr_of_boundary_nodes;
  }
  intra_info_ = info_;
  mesh_ = MeshTopology{};
  order_ready_ = false;
  triangles_ready_ = false;
  if (info_.kind == MeshKind::kUniform) {
    // The topology, traversal and triangle list follow from five numbers:
    // they are built when a P-plane or the output first needs them.
    nodes_ = uniform_nodes(info_.uniform);
  } else {
    // The triangulation validates the geometry, so it is built at once.
    nodes_ = delaunay_node_positions(g.delaunay);
    try {
      mesh_ = constrained_delaunay(nodes_, info_.boundary);
      build_order();
    } catch (const GeometryError& e) {
      const uint64_t at = e.node() == kNoNode ? plane_start : plane_start + syntax::delaunay_node_offset(plane_, e.node());
      throw plane_error(e.kind(), "MeshGeometry", plane_index(), at, e.message());
    } catch (const Error& e) {
      throw plane_error(e.kind(), "MeshGeometry", plane_index(), plane_start, e.message());
    }
    triangles_ = canonical_triangles(mesh_.triangles, nodes_);
    triangles_ready_ = true;
  }
  vectors_.assign(nodes_.size() + 1, Point{});
}

void Decoder::build_order() {
  const bool uniform = intra_info_.kind == MeshKind::kUniform;
  if (uniform && options_.method == MotionMethod::kMethod2 && mesh_.triangles.empty()) mesh_ = uniform_topology(intra_info_.uniform);
  order_ = plane_motion_order(options_.method, mesh_, nodes_.size(), uniform ? &intra_info_.uniform : nullptr, intra_info_.boundary);
  order_ready_ = true;
}

std::span<const Triangle> Decoder::triangles() {
  if (!triangles_ready_) {  // a uniform mesh: listed from its parameters on first use
    const UniformParams& u = intra_info_.uniform;
    triangles_ = canonical_triangles(uniform_triangles(u), uniform_nodes(u));
    triangles_ready_ = true;
  }
  return triangles_;
}

void Decoder::decode_motion(const MeshMotion& motion, uint64_t plane_start) {
  if (!order_ready_) build_order();
  info_ = PlaneInfo{};
  info_.intra = false;
  info_.range = motion.motion_range_code;
  const MotionRange range(motion.motion_range_code);
  const size_t count = order_.node.size();
  const NodeIndex* node = order_.node.data();
  const NodeMotion* coded = motion.nodes.data();
  Point* v = vectors_.data();
  // The vectors in coded order (each prediction reads vectors decoded before it), then the
  // positions in node order: the chain of predictions touches no position.
  for (size_t k = 0; k < count; ++k) {
    const NodeMotion& c = coded[k];
    const Point w = predicted_vector(order_, k, v);
    const Point vector{range.wrap(w.x + range.difference(c.delta_mv_x, c.delta_mv_x_res)),
                       range.wrap(w.y + range.difference(c.delta_mv_y, c.delta_mv_y_res))};
    v[node[k]] = c.node_motion_vector_flag ? vector : Point{0, 0};
  }
  Point* p = nodes_.data();
  bool overflow = false;
  for (size_t n = 0; n < nodes_.size(); ++n) {
    p[n].x += v[n].x;
    p[n].y += v[n].y;
    overflow |= p[n].x > kPositionLimit || p[n].x < -kPositionLimit || p[n].y > kPositionLimit ||
                p[n].y < -kPositionLimit;
  }
  if (overflow)
    throw plane_error(ErrorKind::kLimit, "MeshMotion", plane_index(), plane_start,
                      "node positions leave ±2^30 half pixels (decoder limit, docs/decisions.md)");
}

std::vector<Point> delaunay_node_positions(const DelaunayGeometry& g) {
  std::vector<Point> nodes;
  nodes.reserve(g.nr_of_mesh_nodes);
  Point p{static_cast<int32_t>(g.node0_x), static_cast<int32_t>(g.node0_y)};
  nodes.push_back(p);
  for (const NodeDelta& d : g.deltas) {
    p.x += delta_value(d.x);
    p.y += delta_value(d.y);
    nodes.push_back(p);
  }
  return nodes;
}

std::string decode_to_text(std::span<const uint8_t> stream, const DecoderOptions& options,
                           const std::function<void(std::string_view)>& sink) {
  Decoder decoder(stream, options);
  DecodedTextWriter writer(sink);
  while (decoder.next())
    writer.plane(decoder.info(), decoder.nodes(), decoder.info().intra ? decoder.triangles() : std::span<const Triangle>{});
  return writer.finish();
}

}  // namespace m4mesh
