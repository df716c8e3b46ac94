#include "mesh/cdt.h"

#include <algorithm>
#include <array>
#include <numeric>
#include <string>

#include "common/error.h"
#include "common/random.h"

namespace m4mesh {

namespace {

constexpr uint32_t kNone = 0xFFFFFFFF;
constexpr int32_t kMaxCoordinate = 1023;
// An enclosing triangle, clockwise as displayed, around [0, 1023]²; its
// coordinates keep incircle() exact in 64 bits.
constexpr Point kSuper[3] = {{-3072, -1024}, {5120, -1024}, {512, 6144}};

GeometryError geometry_error(const std::string& message, NodeIndex node = kNoNode) { return GeometryError({message, node}); }

inline int next(int i) { return i == 2 ? 0 : i + 1; }
inline int prev(int i) { return i == 0 ? 2 : i - 1; }

// Position along a Hilbert curve over [0, 1024)².
uint32_t hilbert_index(Point p) {
  uint32_t x = static_cast<uint32_t>(p.x), y = static_cast<uint32_t>(p.y), d = 0;
  for (uint32_t s = 512; s > 0; s >>= 1) {
    const uint32_t rx = (x & s) ? 1 : 0, ry = (y & s) ? 1 : 0;
    d += s * s * ((3 * rx) ^ ry);
    if (ry == 0) {
      if (rx == 1) {
        x = s - 1 - (x & (s - 1));
        y = s - 1 - (y & (s - 1));
      }
      std::swap(x, y);
    }
  }
  return d;
}

class Triangulation {
 public:
  Triangulation(std::span<const Point> nodes, uint32_t boundary_count)
      : points_(nodes.begin(), nodes.end()), node_count_(static_cast<uint32_t>(nodes.size())),
        boundary_count_(boundary_count) {
    for (const Point& p : kSuper) points_.push_back(p);
    vertex_triangle_.assign(points_.size(), kNone);
    tris_.reserve(2 * points_.size() + 1);
    add_triangle(node_count_, node_count_ + 1, node_count_ + 2);
  }

  void insert_all(const CdtOptions& options);
  void insert_boundary();
  MeshTopology interior_triangles();

 private:
  struct Tri {
    uint32_t v[3];
    uint32_t n[3];     // neighbour across the edge opposite v[i]
    uint8_t fixed[3];  // that edge is a boundary (constraint) edge
  };

  uint32_t add_triangle(uint32_t a, uint32_t b, uint32_t c) {
    tris_.push_back(Tri{{a, b, c}, {kNone, kNone, kNone}, {0, 0, 0}});
    return static_cast<uint32_t>(tris_.size() - 1);
  }
  void set(uint32_t t, uint32_t a, uint32_t b, uint32_t c, uint32_t na, uint32_t nb, uint32_t nc, uint8_t fa,
           uint8_t fb, uint8_t fc) {
    tris_[t] = Tri{{a, b, c}, {na, nb, nc}, {fa, fb, fc}};
    vertex_triangle_[a] = vertex_triangle_[b] = vertex_triangle_[c] = t;
  }
  void replace_neighbour(uint32_t t, uint32_t from, uint32_t to) {
    if (t == kNone) return;
    for (uint32_t& n : tris_[t].n)
      if (n == from) n = to;
  }
  int index_of(uint32_t t, uint32_t v) const {
    const Tri& tri = tris_[t];
    return tri.v[0] == v ? 0 : tri.v[1] == v ? 1 : 2;
  }
  // The index i with tris_[t].n[i] == neighbour.
  int neighbour_slot(uint32_t t, uint32_t neighbour) const {
    const Tri& tri = tris_[t];
    return tri.n[0] == neighbour ? 0 : tri.n[1] == neighbour ? 1 : 2;
  }
  void fix_edge(uint32_t t, int i) {
    tris_[t].fixed[i] = 1;
    const uint32_t other = tris_[t].n[i];
    tris_[other].fixed[neighbour_slot(other, t)] = 1;
  }
  int64_t orient_v(uint32_t a, uint32_t b, uint32_t c) const { return orient(points_[a], points_[b], points_[c]); }

  uint32_t locate(uint32_t start, const Point& p, int& edge_hit);
  void insert(uint32_t v, uint32_t& hint);
  void flip(uint32_t t, int i, uint32_t& t_out, uint32_t& u_out);
  void legalize(uint32_t t, int i);
  bool find_edge(uint32_t u, uint32_t w, uint32_t& t, int& i) const;
  void insert_constraint(uint32_t a, uint32_t b);
  [[noreturn]] void node_on_edge(uint32_t node, uint32_t a, uint32_t b) const;

  std::vector<Point> points_;
  uint32_t node_count_;
  uint32_t boundary_count_;
  std::vector<Tri> tris_;
  std::vector<uint32_t> vertex_triangle_;
  std::vector<std::pair<uint32_t, int>> stack_;
};

// Visibility walk from `start`; returns the triangle holding p and, in
// edge_hit, the index of the edge p lies on (or −1).
uint32_t Triangulation::locate(uint32_t start, const Point& p, int& edge_hit) {
  uint32_t t = start;
  uint32_t previous = kNone;
  while (true) {
    const Tri& tri = tris_[t];
    int zero = -1;
    uint32_t step = kNone;
    for (int i = 0; i < 3; ++i) {
      const int64_t o = orient(points_[tri.v[next(i)]], points_[tri.v[prev(i)]], p);
      if (o < 0 && tri.n[i] != previous) {
        step = tri.n[i];
        break;
      }
      if (o < 0) step = tri.n[i];
      if (o == 0) zero = i;
    }
    if (step == kNone) {
      edge_hit = zero;
      return t;
    }
    previous = t;
    t = step;
  }
}

void Triangulation::insert(uint32_t v, uint32_t& hint) {
  const Point& p = points_[v];
  int on_edge = -1;
  const uint32_t t = locate(hint, p, on_edge);
  const Tri old = tris_[t];
  if (on_edge < 0) {
    const uint32_t t1 = add_triangle(0, 0, 0), t2 = add_triangle(0, 0, 0);
    set(t, v, old.v[1], old.v[2], old.n[0], t1, t2, old.fixed[0], 0, 0);
    set(t1, v, old.v[2], old.v[0], old.n[1], t2, t, old.fixed[1], 0, 0);
    set(t2, v, old.v[0], old.v[1], old.n[2], t, t1, old.fixed[2], 0, 0);
    replace_neighbour(old.n[1], t, t1);
    replace_neighbour(old.n[2], t, t2);
    legalize(t, 0);
    legalize(t1, 0);
    legalize(t2, 0);
  } else {
    // p on the edge (a, b) opposite x in t = (x, a, b), shared with u = (y, b, a).
    const int i = on_edge;
    const uint32_t u = old.n[i];
    const Tri uo = tris_[u];
    const int j = neighbour_slot(u, t);
    const uint32_t x = old.v[i], a = old.v[next(i)], b = old.v[prev(i)], y = uo.v[j];
    const uint32_t n_xa = old.n[prev(i)], n_bx = old.n[next(i)];
    const uint32_t n_ay = uo.n[next(j)], n_yb = uo.n[prev(j)];
    const uint8_t f_xa = old.fixed[prev(i)], f_bx = old.fixed[next(i)];
    const uint8_t f_ay = uo.fixed[next(j)], f_yb = uo.fixed[prev(j)];
    const uint32_t t2 = add_triangle(0, 0, 0), t3 = add_triangle(0, 0, 0);
    set(t, v, x, a, n_xa, u, t3, f_xa, 0, 0);
    set(u, v, a, y, n_ay, t2, t, f_ay, 0, 0);
    set(t2, v, y, b, n_yb, t3, u, f_yb, 0, 0);
    set(t3, v, b, x, n_bx, t, t2, f_bx, 0, 0);
    replace_neighbour(n_yb, u, t2);
    replace_neighbour(n_bx, t, t3);
    legalize(t, 0);
    legalize(u, 0);
    legalize(t2, 0);
    legalize(t3, 0);
  }
  hint = vertex_triangle_[v];
}

// Flips the edge opposite v[i] of t. With t = (p, a, b) and its neighbour
// (q, b, a), the results are t' = (p, a, q) and u' = (p, q, b).
void Triangulation::flip(uint32_t t, int i, uint32_t& t_out, uint32_t& u_out) {
  const Tri to = tris_[t];
  const uint32_t u = to.n[i];
  const Tri uo = tris_[u];
  const int j = neighbour_slot(u, t);
  const uint32_t p = to.v[i], a = to.v[next(i)], b = to.v[prev(i)], q = uo.v[j];
  const uint32_t n_pa = to.n[prev(i)], n_bp = to.n[next(i)];
  const uint32_t n_qb = uo.n[prev(j)], n_aq = uo.n[next(j)];
  set(t, p, a, q, n_aq, u, n_pa, uo.fixed[next(j)], 0, to.fixed[prev(i)]);
  set(u, p, q, b, n_qb, n_bp, t, uo.fixed[prev(j)], to.fixed[next(i)], 0);
  replace_neighbour(n_aq, u, t);
  replace_neighbour(n_bp, t, u);
  t_out = t;
  u_out = u;
}

// Restores the Delaunay property from the edge opposite v[i] of t outwards.
void Triangulation::legalize(uint32_t t0, int i0) {
  stack_.clear();
  stack_.push_back({t0, i0});
  while (!stack_.empty()) {
    auto [t, i] = stack_.back();
    stack_.pop_back();
    const Tri& tri = tris_[t];
    const uint32_t u = tri.n[i];
    if (u == kNone || tri.fixed[i]) continue;
    const Tri& ut = tris_[u];
    const int j = neighbour_slot(u, t);
    const uint32_t p = tri.v[i], a = tri.v[next(i)], b = tri.v[prev(i)], q = ut.v[j];
    // (b, p, a) and (b, a, q) are the clockwise triangles on either side of (b, a).
    if (!delaunay_flip(points_[b], points_[p], points_[a], points_[q], b, p, a, q)) continue;
    uint32_t t1, u1;
    flip(t, i, t1, u1);
    // t1 = (p, a, q), u1 = (p, q, b): the edges that may have become illegal.
    stack_.push_back({t1, 0});
    stack_.push_back({u1, 0});
    stack_.push_back({t1, 2});
    stack_.push_back({u1, 1});
  }
}

bool Triangulation::find_edge(uint32_t u, uint32_t w, uint32_t& t_out, int& i_out) const {
  // Turn around a node of the mesh: its fan is closed (an enclosing corner's is not).
  if (u >= node_count_) std::swap(u, w);
  const uint32_t start = vertex_triangle_[u];
  uint32_t t = start;
  do {
    const int k = index_of(t, u);
    const Tri& tri = tris_[t];
    if (tri.v[next(k)] == w) {
      t_out = t;
      i_out = prev(k);
      return true;
    }
    if (tri.v[prev(k)] == w) {
      t_out = t;
      i_out = next(k);
      return true;
    }
    t = tri.n[next(k)];
  } while (t != start && t != kNone);
  return false;
}

void Triangulation::node_on_edge(uint32_t node, uint32_t a, uint32_t b) const {
  const std::string edge = "(" + std::to_string(a) + ", " + std::to_string(b) + ")";
  if (node >= boundary_count_)
    throw geometry_error("interior node " + std::to_string(node) + " is not strictly inside the boundary: it lies on boundary edge " + edge,
                         node);
  throw geometry_error("boundary node " + std::to_string(node) + " lies on boundary edge " + edge + ": the boundary is not simple", node);
}

// Makes (a, b) an edge (Sloan's flips), then restores the Delaunay
// property around the new edges.
void Triangulation::insert_constraint(uint32_t a, uint32_t b) {
  uint32_t t;
  int i;
  if (!find_edge(a, b, t, i)) {
    // The triangle around a that the segment a → b leaves through.
    const Point &pa = points_[a], &pb = points_[b];
    uint32_t u = kNone, w = kNone;
    const uint32_t start = vertex_triangle_[a];
    t = start;
    do {
      const int k = index_of(t, a);
      const uint32_t r = tris_[t].v[next(k)], l = tris_[t].v[prev(k)];
      const int64_t o_r = orient(pa, points_[r], pb);
      if (o_r == 0 && (int64_t{points_[r].x} - pa.x) * (pb.x - pa.x) + (int64_t{points_[r].y} - pa.y) * (pb.y - pa.y) > 0)
        node_on_edge(r, a, b);
      if (o_r > 0 && orient(pa, points_[l], pb) < 0) {
        u = r;
        w = l;
        break;
      }
      t = tris_[t].n[next(k)];
    } while (t != start);
    if (u == kNone) throw geometry_error("cannot place boundary edge (" + std::to_string(a) + ", " + std::to_string(b) + ")");

    // Walk along the segment collecting the crossed edges (u right of a → b, w left).
    std::vector<std::pair<uint32_t, uint32_t>> crossing{{u, w}};
    uint32_t current = t;
    while (true) {
      const Tri& tri = tris_[current];
      const int k = index_of(current, u);
      // The neighbour across (u, w) and its far node.
      const int edge = tri.v[next(k)] == w ? prev(k) : next(k);
      if (tri.fixed[edge]) throw geometry_error("boundary edges cross: the boundary is not simple");
      const uint32_t nt = tri.n[edge];
      const uint32_t z = tris_[nt].v[neighbour_slot(nt, current)];
      if (z == b) break;
      const int64_t side = orient(pa, pb, points_[z]);
      if (side == 0) node_on_edge(z, a, b);
      if (side > 0)
        w = z;
      else
        u = z;
      crossing.push_back({u, w});
      current = nt;
    }

    // Flip crossing edges until none is left (Sloan 1993).
    std::vector<std::pair<uint32_t, uint32_t>> created;
    size_t head = 0;
    while (head < crossing.size()) {
      const auto [eu, ew] = crossing[head++];
      uint32_t et;
      int ei;
      find_edge(eu, ew, et, ei);
      const Tri& tri = tris_[et];
      const uint32_t nt = tri.n[ei];
      const uint32_t p = tri.v[ei], q = tris_[nt].v[neighbour_slot(nt, et)];
      const uint32_t ea = tri.v[next(ei)], eb = tri.v[prev(ei)];
      if (orient_v(p, ea, q) <= 0 || orient_v(p, q, eb) <= 0) {
        crossing.push_back({eu, ew});  // not convex yet: retry later
        continue;
      }
      uint32_t t1, u1;
      flip(et, ei, t1, u1);
      const bool crosses = p != a && p != b && q != a && q != b &&
                           ((orient(pa, pb, points_[p]) > 0) != (orient(pa, pb, points_[q]) > 0));
      if (crosses)
        crossing.push_back({p, q});
      else
        created.push_back({p, q});
    }
    find_edge(a, b, t, i);
    fix_edge(t, i);
    for (const auto& [cu, cw] : created) {
      uint32_t ct;
      int ci;
      if (find_edge(cu, cw, ct, ci)) legalize(ct, ci);
    }
    return;
  }
  fix_edge(t, i);
}

void Triangulation::insert_all(const CdtOptions& options) {
  std::vector<uint32_t> order(node_count_);
  std::iota(order.begin(), order.end(), 0u);
  if (options.shuffle) {
    SplitMix64 random(options.insertion_seed);
    for (size_t i = order.size(); i > 1; --i) std::swap(order[i - 1], order[random.next() % i]);
    // BRIO: the later half of each prefix is one round, sorted along a Hilbert curve
    // (keys: Hilbert index above, node below).
    std::vector<uint64_t> keys(node_count_);
    for (size_t k = 0; k < order.size(); ++k) keys[k] = uint64_t{hilbert_index(points_[order[k]])} << 32 | order[k];
    for (size_t end = keys.size(); end > 0; end /= 2) {
      const size_t begin = end / 2 < 64 ? 0 : end / 2;
      std::sort(keys.begin() + static_cast<std::ptrdiff_t>(begin), keys.begin() + static_cast<std::ptrdiff_t>(end));
      if (begin == 0) break;
    }
    for (size_t k = 0; k < order.size(); ++k) order[k] = static_cast<uint32_t>(keys[k]);
  }
  uint32_t hint = 0;
  for (uint32_t v : order) insert(v, hint);
}

void Triangulation::insert_boundary() {
  for (uint32_t k = 0; k < boundary_count_; ++k) insert_constraint(k, (k + 1) % boundary_count_);
}

MeshTopology Triangulation::interior_triangles() {
  // Everything reachable from the enclosing triangle's corners without
  // crossing the boundary is outside.
  std::vector<uint8_t> outside(tris_.size(), 0);
  std::vector<uint32_t> stack;
  for (uint32_t t = 0; t < tris_.size(); ++t) {
    const Tri& tri = tris_[t];
    if (tri.v[0] >= node_count_ || tri.v[1] >= node_count_ || tri.v[2] >= node_count_) {
      outside[t] = 1;
      stack.push_back(t);
    }
  }
  while (!stack.empty()) {
    const uint32_t t = stack.back();
    stack.pop_back();
    for (int i = 0; i < 3; ++i) {
      const uint32_t n = tris_[t].n[i];
      if (n != kNone && !tris_[t].fixed[i] && !outside[n]) {
        outside[n] = 1;
        stack.push_back(n);
      }
    }
  }
  MeshTopology mesh;
  std::vector<uint32_t> output_index(tris_.size(), kNoTriangle);
  for (uint32_t t = 0; t < tris_.size(); ++t) {
    if (outside[t]) continue;
    output_index[t] = static_cast<uint32_t>(mesh.triangles.size());
    mesh.triangles.push_back(Triangle{{tris_[t].v[0], tris_[t].v[1], tris_[t].v[2]}});
  }
  std::vector<uint8_t> covered(node_count_, 0);
  mesh.neighbours.reserve(mesh.triangles.size());
  for (uint32_t t = 0; t < tris_.size(); ++t) {
    if (outside[t]) continue;
    const Tri& tri = tris_[t];
    std::array<uint32_t, 3> n;
    for (int i = 0; i < 3; ++i) n[i] = tri.n[i] == kNone ? kNoTriangle : output_index[tri.n[i]];
    mesh.neighbours.push_back(n);
    covered[tri.v[0]] = covered[tri.v[1]] = covered[tri.v[2]] = 1;
  }
  for (uint32_t v = boundary_count_; v < node_count_; ++v)
    if (!covered[v]) throw geometry_error("interior node " + std::to_string(v) + " lies outside the boundary", v);
  return mesh;
}

}  // namespace

bool delaunay_flip(const Point& pa, const Point& pb, const Point& pc, const Point& pd, NodeIndex a, NodeIndex b,
                   NodeIndex c, NodeIndex d) {
  const int64_t det = incircle(pa, pb, pc, pd);
  if (det != 0) return det > 0;
  return std::min(b, d) < std::min(a, c);
}

GeometryError::GeometryError(const GeometryViolation& v) : Error(ErrorKind::kGeometry, "", kNoPlane, kNoOffset, v.message), node_(v.node) {}

std::vector<GeometryViolation> delaunay_node_violations(std::span<const Point> nodes, uint32_t boundary_count, size_t max_reports) {
  std::vector<GeometryViolation> found;
  auto report = [&](std::string message, NodeIndex node = kNoNode) {
    if (found.size() < max_reports) found.push_back({std::move(message), node});
  };
  const uint32_t n = static_cast<uint32_t>(nodes.size());
  if (boundary_count < 3 || boundary_count > n) {
    report("need 3 … " + std::to_string(n) + " boundary nodes");
    return found;
  }
  bool coordinates_ok = true;
  for (uint32_t i = 0; i < n; ++i) {
    if (nodes[i].x < 0 || nodes[i].x > kMaxCoordinate || nodes[i].y < 0 || nodes[i].y > kMaxCoordinate) {
      report("node " + std::to_string(i) + " lies outside 0…1023", i);
      coordinates_ok = false;
    }
  }
  if (!coordinates_ok) return found;
  NodeIndex top_left = 0;
  for (uint32_t i = 1; i < n; ++i)
    if (more_top_left(nodes[i], nodes[top_left])) top_left = i;
  if (top_left != 0) report("node 0 is not the top-left node (node " + std::to_string(top_left) + " is)", top_left);

  // Coordinates are 10-bit: an occupancy bitmap finds duplicates in linear time.
  std::vector<uint64_t> occupied((size_t{1} << 20) / 64, 0);
  for (uint32_t i = 0; i < n; ++i) {
    const uint32_t cell = static_cast<uint32_t>(nodes[i].y) << 10 | static_cast<uint32_t>(nodes[i].x);
    const uint64_t bit = uint64_t{1} << (cell % 64);
    if (occupied[cell / 64] & bit) {
      const uint32_t first = static_cast<uint32_t>(std::find(nodes.begin(), nodes.begin() + i, nodes[i]) - nodes.begin());
      report("nodes " + std::to_string(first) + " and " + std::to_string(i) + " coincide", i);
    }
    occupied[cell / 64] |= bit;
  }

  const uint32_t b = boundary_count;
  int64_t area = 0;
  for (uint32_t i = 0; i < b; ++i) {
    const Point &p = nodes[i], &q = nodes[(i + 1) % b];
    area += int64_t{p.x} * q.y - int64_t{q.x} * p.y;
  }
  if (area == 0) report("the boundary polygon has zero area");
  if (area > 0) report("the boundary polygon is clockwise (area " + std::to_string(area) + " > 0)");

  // Simple: adjacent edges do not fold back, non-adjacent edges do not touch.
  auto on_segment = [](const Point& p, const Point& q, const Point& r) {
    return std::min(p.x, q.x) <= r.x && r.x <= std::max(p.x, q.x) && std::min(p.y, q.y) <= r.y && r.y <= std::max(p.y, q.y);
  };
  auto touch = [&](const Point& p1, const Point& p2, const Point& q1, const Point& q2) {
    const int64_t d1 = orient(q1, q2, p1), d2 = orient(q1, q2, p2), d3 = orient(p1, p2, q1), d4 = orient(p1, p2, q2);
    if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) return true;
    return (d1 == 0 && on_segment(q1, q2, p1)) || (d2 == 0 && on_segment(q1, q2, p2)) ||
           (d3 == 0 && on_segment(p1, p2, q1)) || (d4 == 0 && on_segment(p1, p2, q2));
  };
  for (uint32_t i = 0; i < b; ++i) {
    const Point &p0 = nodes[(i + b - 1) % b], &p1 = nodes[i], &p2 = nodes[(i + 1) % b];
    if (orient(p0, p1, p2) == 0 &&
        (int64_t{p0.x} - p1.x) * (p2.x - p1.x) + (int64_t{p0.y} - p1.y) * (p2.y - p1.y) > 0)
      report("the boundary folds back on itself at node " + std::to_string(i), i);
  }
  struct Box {
    int32_t x0, y0, x1, y1;
  };
  std::vector<Box> boxes(b);
  for (uint32_t i = 0; i < b; ++i) {
    const Point &p = nodes[i], &q = nodes[(i + 1) % b];
    boxes[i] = {std::min(p.x, q.x), std::min(p.y, q.y), std::max(p.x, q.x), std::max(p.y, q.y)};
  }
  // Sweep in x: only edges whose x-ranges overlap are compared.
  std::vector<uint32_t> by_x(b);
  std::iota(by_x.begin(), by_x.end(), 0u);
  std::sort(by_x.begin(), by_x.end(), [&](uint32_t l, uint32_t r) { return boxes[l].x0 != boxes[r].x0 ? boxes[l].x0 < boxes[r].x0 : l < r; });
  std::vector<std::pair<uint32_t, uint32_t>> touching;
  for (uint32_t a = 0; a < b; ++a) {
    const Box& l = boxes[by_x[a]];
    for (uint32_t c = a + 1; c < b && boxes[by_x[c]].x0 <= l.x1; ++c) {
      const uint32_t i = std::min(by_x[a], by_x[c]), j = std::max(by_x[a], by_x[c]);
      if (j == i + 1 || (i == 0 && j == b - 1)) continue;  // adjacent edges
      const Box& r = boxes[by_x[c]];
      if (l.y1 < r.y0 || r.y1 < l.y0) continue;
      if (touch(nodes[i], nodes[(i + 1) % b], nodes[j], nodes[(j + 1) % b])) touching.push_back({i, j});
    }
  }
  std::sort(touching.begin(), touching.end());
  for (const auto& [i, j] : touching)
    report("boundary edges (" + std::to_string(i) + ", " + std::to_string((i + 1) % b) + ") and (" + std::to_string(j) + ", " +
           std::to_string((j + 1) % b) + ") touch: the boundary is not simple");
  return found;
}

void validate_delaunay_nodes(std::span<const Point> nodes, uint32_t boundary_count) {
  const std::vector<GeometryViolation> violations = delaunay_node_violations(nodes, boundary_count, 1);
  if (!violations.empty()) throw GeometryError(violations.front());
}

MeshTopology constrained_delaunay(std::span<const Point> nodes, uint32_t boundary_count, const CdtOptions& options) {
  validate_delaunay_nodes(nodes, boundary_count);
  Triangulation triangulation(nodes, boundary_count);
  triangulation.insert_all(options);
  triangulation.insert_boundary();
  return triangulation.interior_triangles();
}

}  // namespace m4mesh
