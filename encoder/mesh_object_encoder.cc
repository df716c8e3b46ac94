#include "encoder/mesh_object_encoder.h"

#include <algorithm>

#include "mesh/cdt.h"
#include "mesh/uniform.h"
#include "syntax/mesh_object.h"
#include "syntax/values.h"

namespace m4mesh {

namespace {

Error plane_error(int64_t plane, const std::string& message) {
  return Error(ErrorKind::kInput, "", plane, kNoOffset, message);
}

class PlaneEncoder {
 public:
  explicit PlaneEncoder(const EncoderOptions& options) : options_(options), writer_(options.trace) {}

  void intra(const MeshPlane& plane, int64_t index);
  // False when the motion does not fit the largest range.
  bool inter(const MeshPlane& plane, int64_t index);
  std::vector<uint8_t> finish() { return writer_.finish(options_.end_code); }

  bool is_delaunay() const { return kind_ == MeshKind::kDelaunay; }

 private:
  void report(const std::string& message) const {
    if (options_.report) options_.report(message);
  }
  void set_order(const MeshTopology& mesh, const UniformParams* uniform, uint32_t boundary);

  const EncoderOptions& options_;
  syntax::MeshObjectWriter writer_;
  MeshObjectPlane syntax_;
  MeshKind kind_ = MeshKind::kUniform;
  std::vector<NodeIndex> input_of_coded_;  // coded node → input node
  std::vector<Point> current_;             // by coded node
  MotionOrder order_;
  std::vector<Point> vectors_;
};

void PlaneEncoder::set_order(const MeshTopology& mesh, const UniformParams* uniform, uint32_t boundary) {
  order_ = plane_motion_order(options_.method, mesh, current_.size(), uniform, boundary);
  vectors_.assign(current_.size() + 1, Point{});
}

void PlaneEncoder::intra(const MeshPlane& plane, int64_t index) {
  syntax_.new_mesh_flag = 1;
  MeshGeometry& g = syntax_.geometry;
  kind_ = plane.info.kind;
  const size_t count = plane.nodes.size();
  if (kind_ == MeshKind::kUniform) {
    const UniformParams& u = plane.info.uniform;
    if (plane.nodes != uniform_nodes(u))
      throw plane_error(index, "the nodes of a uniform I-plane must be the grid of its parameters");
    g.mesh_type_code = kMeshTypeUniform;
    g.uniform = UniformGeometry{u.cols, u.rows, u.dx, u.dy, u.split};
    input_of_coded_.resize(count);
    for (NodeIndex i = 0; i < count; ++i) input_of_coded_[i] = i;
    current_ = plane.nodes;
    const MeshTopology mesh = uniform_topology(u);
    if (!plane.triangles.empty() && canonical_triangles(plane.triangles, current_) != canonical_triangles(mesh.triangles, current_))
      report("plane " + std::to_string(index) + ": the input triangles differ from the uniform split; the split code wins");
    writer_.write(syntax_);
    set_order(mesh, &u, 0);
    return;
  }

  const uint32_t boundary = plane.info.boundary;
  if (options_.keep_node_order) {
    input_of_coded_.resize(count);
    for (NodeIndex i = 0; i < count; ++i) input_of_coded_[i] = i;
  } else {
    try {
      input_of_coded_ = delaunay_node_order(plane.nodes, boundary);
    } catch (const Error& e) {
      throw plane_error(index, e.message());
    }
  }
  current_.resize(count);
  for (NodeIndex i = 0; i < count; ++i) current_[i] = plane.nodes[input_of_coded_[i]];
  MeshTopology mesh;
  try {
    mesh = constrained_delaunay(current_, boundary);
  } catch (const Error& e) {
    throw plane_error(index, e.message());
  }
  if (!plane.triangles.empty()) {
    std::vector<NodeIndex> coded_of_input(count);
    for (NodeIndex i = 0; i < count; ++i) coded_of_input[input_of_coded_[i]] = i;
    std::vector<Triangle> given = plane.triangles;
    for (Triangle& t : given)
      for (NodeIndex& v : t.v) v = coded_of_input[v];
    const std::vector<Triangle> ours = canonical_triangles(mesh.triangles, current_);
    given = canonical_triangles(given, current_);
    if (given != ours) {
      std::vector<Triangle> only_given;
      std::set_difference(given.begin(), given.end(), ours.begin(), ours.end(), std::back_inserter(only_given));
      report("plane " + std::to_string(index) + ": " + std::to_string(only_given.size()) + " of the " +
             std::to_string(given.size()) +
             " input triangles are not in the constrained Delaunay triangulation the decoder builds; the decoder's "
             "triangles win");
    }
  }
  g.mesh_type_code = kMeshTypeDelaunay;
  DelaunayGeometry& d = g.delaunay;
  d.nr_of_mesh_nodes = static_cast<uint32_t>(count);
  d.nr_of_boundary_nodes = boundary;
  d.node0_x = static_cast<uint32_t>(current_[0].x);
  d.node0_y = static_cast<uint32_t>(current_[0].y);
  d.deltas.resize(count - 1);
  for (size_t n = 1; n < count; ++n)
    d.deltas[n - 1] = NodeDelta{delta_code(current_[n].x - current_[n - 1].x), delta_code(current_[n].y - current_[n - 1].y)};
  writer_.write(syntax_);
  set_order(mesh, nullptr, boundary);
}

bool PlaneEncoder::inter(const MeshPlane& plane, int64_t index) {
  const size_t count = current_.size();
  if (plane.nodes.size() != count)
    throw plane_error(index, "a P-plane has " + std::to_string(plane.nodes.size()) + " nodes where the mesh has " +
                                 std::to_string(count));
  // Motion by coded node, and its extent.
  int lo = 0, hi = 0;
  std::vector<Point> motion(count);
  for (NodeIndex i = 0; i < count; ++i) {
    const Point& target = plane.nodes[input_of_coded_[i]];
    const int64_t mx = int64_t{target.x} - current_[i].x, my = int64_t{target.y} - current_[i].y;
    if (mx < -128 || mx > 127 || my < -128 || my > 127) return false;
    motion[i] = Point{static_cast<int32_t>(mx), static_cast<int32_t>(my)};
    lo = std::min({lo, motion[i].x, motion[i].y});
    hi = std::max({hi, motion[i].x, motion[i].y});
  }
  uint32_t code = plane.info.range;
  if (code == 0) code = smallest_motion_range_code(lo, hi);
  const MotionRange range(code);
  if (!range.contains(lo) || !range.contains(hi))
    throw plane_error(index, "motion vectors in [" + std::to_string(lo) + ", " + std::to_string(hi) +
                                 "] do not fit range=" + std::to_string(code));

  syntax_.new_mesh_flag = 0;
  MeshMotion& m = syntax_.motion;
  m.motion_range_code = code;
  m.nodes.resize(count);
  Point* v = vectors_.data();
  for (size_t k = 0; k < count; ++k) {
    const NodeIndex n = order_.node[k];
    const Point vector = motion[n];
    NodeMotion& coded = m.nodes[k];
    coded.node_motion_vector_flag = vector.x != 0 || vector.y != 0;
    if (coded.node_motion_vector_flag) {
      const Point w = predicted_vector(order_, k, v);
      range.code(range.wrap(vector.x - w.x), coded.delta_mv_x, coded.delta_mv_x_res);
      range.code(range.wrap(vector.y - w.y), coded.delta_mv_y, coded.delta_mv_y_res);
    } else {
      coded = NodeMotion{};
    }
    v[n] = vector;
    current_[n].x += vector.x;
    current_[n].y += vector.y;
  }
  writer_.write(syntax_);
  return true;
}

}  // namespace

class Encoder::Impl {
 public:
  explicit Impl(const EncoderOptions& options) : options_(options), planes_(options_) {}

  void add(const MeshPlane& plane) {
    const int64_t index = next_index_++;
    if (index == 0 && !plane.info.intra) throw plane_error(0, "the first plane must be an I-plane");
    if (plane.info.intra) {
      planes_.intra(plane, index);
      last_intra_ = plane.info;
      ++result_.intra_planes;
    } else if (planes_.inter(plane, index)) {
      ++result_.inter_planes;
    } else if (planes_.is_delaunay()) {
      // §10: motion beyond [−128, 127] is coded as a new Delaunay I-plane.
      if (options_.report) options_.report("plane " + std::to_string(index) + ": motion exceeds [-128, 127]; coded as a new I-plane");
      planes_.intra(MeshPlane{last_intra_, plane.nodes, {}}, index);
      ++result_.intra_planes;
    } else {
      throw plane_error(index, "motion exceeds [-128, 127], which a uniform mesh cannot code");
    }
  }

  EncodeResult finish() {
    if (next_index_ == 0) throw plane_error(kNoPlane, "no planes to encode");
    result_.stream = planes_.finish();
    return std::move(result_);
  }

 private:
  const EncoderOptions options_;
  PlaneEncoder planes_;
  PlaneInfo last_intra_;
  int64_t next_index_ = 0;
  EncodeResult result_;
};

Encoder::Encoder(const EncoderOptions& options) : impl_(std::make_unique<Impl>(options)) {}
Encoder::~Encoder() = default;
void Encoder::add(const MeshPlane& plane) { impl_->add(plane); }
EncodeResult Encoder::finish() { return impl_->finish(); }

EncodeResult encode(std::span<const MeshPlane> planes, const EncoderOptions& options) {
  Encoder encoder(options);
  for (const MeshPlane& plane : planes) encoder.add(plane);
  return encoder.finish();
}

}  // namespace m4mesh
