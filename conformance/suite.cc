#include "conformance/suite.h"

#include <cmath>
#include <map>
#include <numbers>
#include <set>
#include <sstream>
#include <stdexcept>
#include <tuple>

#include "bitstream/start_codes.h"
#include "common/random.h"
#include "encoder/mesh_object_encoder.h"
#include "syntax/mesh_object.h"
#include "syntax/values.h"

namespace m4mesh {

namespace {

using Random = SplitMix64;

// `frames` P-planes of random motion in [lo, hi] after `intra`.
std::vector<MeshPlane> with_motion(MeshPlane intra, int frames, int lo, int hi, uint64_t seed) {
  std::vector<MeshPlane> planes{std::move(intra)};
  Random random(seed);
  for (int k = 0; k < frames; ++k) {
    std::vector<Point> next = planes.back().nodes;
    for (Point& p : next) {
      p.x += random.uniform(lo, hi);
      p.y += random.uniform(lo, hi);
    }
    planes.push_back(inter_plane(std::move(next)));
  }
  return planes;
}

std::vector<uint8_t> encoded(const std::vector<MeshPlane>& planes, MotionMethod method = MotionMethod::kMethod2,
                             bool end_code = true) {
  EncoderOptions options;
  options.method = method;
  options.end_code = end_code;
  return encode(planes, options).stream;
}

// Distinct random nodes strictly inside the axis-aligned box (x0, y0)–(x1, y1).
std::vector<Point> random_inside(int count, int x0, int y0, int x1, int y1, uint64_t seed, std::set<std::pair<int, int>> used = {}) {
  Random random(seed);
  std::vector<Point> nodes;
  while (static_cast<int>(nodes.size()) < count) {
    const Point p{random.uniform(x0 + 1, x1 - 1), random.uniform(y0 + 1, y1 - 1)};
    if (used.insert({p.x, p.y}).second) nodes.push_back(p);
  }
  return nodes;
}

std::vector<Point> concat(std::vector<Point> a, const std::vector<Point>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

// Boundary of the box with `per_side` nodes on each side, counterclockwise from (x0, y0).
std::vector<Point> box_boundary(int x0, int y0, int x1, int y1, int per_side) {
  std::vector<Point> nodes;
  for (int i = 0; i < per_side; ++i) nodes.push_back({x0, y0 + (y1 - y0) * i / per_side});
  for (int i = 0; i < per_side; ++i) nodes.push_back({x0 + (x1 - x0) * i / per_side, y1});
  for (int i = 0; i < per_side; ++i) nodes.push_back({x1, y1 - (y1 - y0) * i / per_side});
  for (int i = 0; i < per_side; ++i) nodes.push_back({x1 - (x1 - x0) * i / per_side, y0});
  return nodes;
}

// A star-shaped polygon of `count` nodes around (512, 512), counterclockwise from its top-left node.
std::vector<Point> star_boundary(int count, int min_radius, int max_radius, uint64_t seed) {
  Random random(seed);
  std::vector<Point> nodes;
  std::set<std::pair<int, int>> used;
  for (int k = 0; static_cast<int>(nodes.size()) < count; ++k) {
    const double angle = 2 * std::numbers::pi * (k + 0.5) / count;
    const double radius = k % 2 ? max_radius : random.uniform(min_radius, max_radius);
    // Counterclockwise as displayed: angle grows with y pointing up.
    const Point p{static_cast<int32_t>(std::lround(512 + radius * std::cos(angle))),
                  static_cast<int32_t>(std::lround(512 - radius * std::sin(angle)))};
    if (used.insert({p.x, p.y}).second) nodes.push_back(p);
  }
  return nodes;
}

}  // namespace

std::vector<Point> comb_boundary() {
  std::vector<Point> comb{{0, 0}, {0, 900}};
  for (int t = 0; t < 10; ++t) {
    comb.push_back({t * 100 + 40, 900});
    comb.push_back({t * 100 + 40, 200});
    comb.push_back({t * 100 + 60, 200});
    comb.push_back({t * 100 + 60, 900});
  }
  comb.push_back({1000, 900});
  comb.push_back({1000, 0});
  return comb;
}

std::vector<Point> spiral_boundary() {
  std::vector<Point> outer, inner;
  int x0 = 0, y0 = 0, x1 = 1000, y1 = 1000;
  const int w = 20;
  outer.push_back({x0, y0});
  while (x1 - x0 > 4 * w && y1 - y0 > 4 * w) {
    outer.push_back({x0, y1});
    outer.push_back({x1, y1});
    outer.push_back({x1, y0 + 2 * w});
    inner.push_back({x0 + w, y0 + w});
    inner.push_back({x0 + w, y1 - w});
    inner.push_back({x1 - w, y1 - w});
    inner.push_back({x1 - w, y0 + 3 * w});
    x0 += 2 * w;
    y0 += 2 * w;
    x1 -= 2 * w;
    y1 -= 2 * w;
    outer.push_back({x0, y0});
  }
  std::vector<Point> spiral = outer;
  spiral.insert(spiral.end(), inner.rbegin(), inner.rend());
  spiral.push_back({w, 0});
  return spiral;
}

std::vector<MeshPlane> hand_stream_planes() {
  std::vector<MeshPlane> planes{uniform_plane(3, 3, 16, 16, 0)};
  std::vector<Point> p1 = planes[0].nodes;
  p1[0] = {1, 0};
  p1[1] = {17, 0};
  p1[4] = {18, 17};
  p1[3] = {0, 14};
  p1[7] = {13, 32};
  planes.push_back(inter_plane(p1));
  std::vector<Point> p2 = p1;
  p2[0] = {41, -1};
  p2[1] = {-23, 0};
  p2[4] = {18, 80};
  planes.push_back(inter_plane(p2));
  return planes;
}

std::vector<MeshPlane> range_limit_planes(uint32_t code) {
  const MotionRange range(code);
  std::vector<MeshPlane> planes{uniform_plane(6, 6, 255, 255, 0)};
  std::vector<Point> nodes = planes[0].nodes;
  for (size_t i = 0; i < nodes.size(); ++i) {
    nodes[i].x += i % 2 ? range.low : range.high;
    nodes[i].y += i % 3 ? range.high : range.low;
  }
  planes.push_back(inter_plane(nodes));
  return planes;
}

std::vector<MeshPlane> wrap_planes(uint32_t code) {
  const MotionRange range(code);
  std::vector<MeshPlane> planes{uniform_plane(4, 4, 100, 100, 2)};
  std::vector<Point> nodes = planes[0].nodes;
  for (size_t i = 0; i < nodes.size(); ++i) {
    const int v = i % 2 ? range.low + 1 : range.high - 1;
    nodes[i].x += v;
    nodes[i].y -= v;
  }
  planes.push_back(inter_plane(nodes, code));
  return planes;
}

namespace {

// ---- negative streams ----------------------------------------------------

struct TracedElement {
  uint64_t offset;
  int bits;
};

// Where each occurrence of each element lies in a valid stream (from the tracer).
std::map<std::string, std::vector<TracedElement>> trace_elements(const std::vector<uint8_t>& stream) {
  std::ostringstream text;
  Trace trace(text);
  syntax::read_mesh_object(stream, &trace);
  std::map<std::string, std::vector<TracedElement>> elements;
  std::istringstream lines(text.str());
  uint64_t offset;
  std::string name;
  int bits;
  std::string value;
  while (lines >> offset >> name >> bits >> value) elements[name].push_back({offset, bits});
  return elements;
}

// Overwrites the n-th occurrence of an element with `value` (same bit count).
std::vector<uint8_t> overwritten(std::vector<uint8_t> stream, const std::string& element, size_t occurrence, int bits,
                                 uint32_t value);

std::vector<uint8_t> patched(const std::vector<uint8_t>& stream, const std::string& element, size_t occurrence, uint32_t value) {
  return overwritten(stream, element, occurrence, trace_elements(stream).at(element).at(occurrence).bits, value);
}

struct Cut {
  std::vector<uint8_t> stream;
  int64_t plane;
};

// The stream cut at a byte boundary strictly inside an element: the first
// occurrence from the n-th on that spans one. The plane is counted from the
// plane start codes before it.
Cut cut_inside(std::vector<uint8_t> stream, const std::string& element, size_t occurrence) {
  const auto elements = trace_elements(stream);
  const std::vector<TracedElement>& found = elements.at(element);
  for (size_t k = occurrence; k < found.size(); ++k) {
    const TracedElement e = found[k];
    const uint64_t boundary = (e.offset / 8 + 1) * 8;
    if (boundary >= e.offset + static_cast<uint64_t>(e.bits)) continue;
    int64_t plane = -1;
    for (const TracedElement& start : elements.at("mesh_object_plane_start_code"))
      if (start.offset < e.offset) ++plane;
    stream.resize(static_cast<size_t>(boundary / 8));
    return {stream, plane};
  }
  throw std::logic_error("no occurrence of " + element + " spans a byte boundary");
}

// Overwrites `bits` bits from the start of the n-th occurrence of an element.
std::vector<uint8_t> overwritten(std::vector<uint8_t> stream, const std::string& element, size_t occurrence, int bits,
                                 uint32_t value) {
  const uint64_t offset = trace_elements(stream).at(element).at(occurrence).offset;
  for (int i = 0; i < bits; ++i) {
    const uint64_t bit = offset + static_cast<uint64_t>(i);
    const uint8_t mask = static_cast<uint8_t>(0x80 >> (bit % 8));
    if ((value >> (bits - 1 - i)) & 1)
      stream[bit / 8] |= mask;
    else
      stream[bit / 8] &= static_cast<uint8_t>(~mask);
  }
  return stream;
}

// A one-plane Delaunay stream written bit by bit, without any check, from
// node0 and raw (x, y) deltas.
std::vector<uint8_t> unchecked_delaunay(uint32_t node_count, uint32_t boundary, Point node0,
                                        const std::vector<std::pair<int, int>>& deltas) {
  BitWriter w;
  w.write(kMeshObjectStartCode, 32);
  w.write(kMeshObjectPlaneStartCode, 32);
  w.write(1, 1);
  w.write(kMeshTypeDelaunay, 2);
  w.write(node_count, 16);
  w.write(boundary, 10);
  w.write(static_cast<uint32_t>(node0.x), 10);
  w.write(static_cast<uint32_t>(node0.y), 10);
  const VlcTable& lengths = delta_length_table();
  for (const auto& [dx, dy] : deltas) {
    for (int d : {dx, dy}) {
      const DeltaCode code = delta_code(d);
      w.write(lengths.code(code.length).bits, lengths.code(code.length).length);
      w.write(code.bits, code.length);
    }
  }
  write_next_start_code(w);
  w.write(kMeshObjectEndCode, 32);
  return w.take_bytes();
}

std::vector<uint8_t> unchecked_delaunay(const std::vector<Point>& nodes, uint32_t boundary) {
  std::vector<std::pair<int, int>> deltas;
  for (size_t i = 1; i < nodes.size(); ++i) deltas.push_back({nodes[i].x - nodes[i - 1].x, nodes[i].y - nodes[i - 1].y});
  return unchecked_delaunay(static_cast<uint32_t>(nodes.size()), boundary, nodes[0], deltas);
}

std::vector<uint8_t> bits_to_bytes(const std::string& bits) {
  BitWriter w;
  for (char c : bits) w.write_bit(c == '1');
  return w.take_bytes();
}

}  // namespace

namespace {

// Collects a group's cases.
class CaseList {
 public:
  void valid(std::string id, std::string purpose, std::vector<std::string> clauses, std::vector<uint8_t> stream,
             MotionMethod method = MotionMethod::kMethod2) {
    cases_.push_back(decode_case(std::move(id), std::move(purpose), std::move(clauses), std::move(stream)));
    cases_.back().method = method;
  }
  void invalid(std::string id, std::string purpose, std::vector<std::string> clauses, std::vector<uint8_t> stream, ErrorKind kind,
               std::string element, int64_t plane) {
    cases_.push_back(reject_case(std::move(id), std::move(purpose), std::move(clauses), std::move(stream), kind, std::move(element), plane));
  }
  std::vector<SuiteCase> take() { return std::move(cases_); }

 private:
  std::vector<SuiteCase> cases_;
};

const std::vector<std::string> kUniformClauses{"1", "2.1", "2.2", "3", "3.1", "4", "4.2", "5", "7.1", "7.2", "9"};
const std::vector<std::string> kDelaunayClauses{"1", "2.1", "2.2", "3", "3.1", "4", "4.1", "4.2", "6.1", "6.2", "7.1", "7.2", "9", "10"};

// Uniform meshes: splits, sizes, motion ranges and wraps, emulation, intra changes.
std::vector<SuiteCase> uniform_cases() {
  CaseList suite;
  suite.valid("p01-hand-3x3", "the 3×3 stream worked out by hand in tests/hand_stream_test.cc", kUniformClauses,
        encoded(hand_stream_planes()));
  for (uint32_t split = 0; split < 4; ++split)
    suite.valid("p0" + std::to_string(2 + split) + "-uniform-split" + std::to_string(split),
          "triangle_split_code '" + std::string(split < 2 ? "0" : "1") + (split % 2 ? "1" : "0") + "' on a 6×5 mesh with motion",
          kUniformClauses, encoded(with_motion(uniform_plane(6, 5, 20, 18, split), 3, -20, 20, 100 + split)));
  suite.valid("p06-uniform-2x2", "the smallest uniform mesh", kUniformClauses, encoded(with_motion(uniform_plane(2, 2, 100, 100, 1), 2, -30, 30, 6)));
  suite.valid("p07-uniform-1023x2", "the widest uniform mesh", kUniformClauses, encoded(with_motion(uniform_plane(1023, 2, 1, 50, 2), 1, -3, 3, 7)));
  suite.valid("p08-uniform-2x1023", "the tallest uniform mesh", kUniformClauses, encoded(with_motion(uniform_plane(2, 1023, 50, 1, 3), 1, -3, 3, 8)));
  suite.valid("p09-uniform-rect-1-255", "mesh_rect_size at 1 and 255", kUniformClauses, encoded(with_motion(uniform_plane(8, 5, 1, 255, 0), 2, -9, 9, 9)));
  for (uint32_t code = 1; code <= 3; ++code)
    suite.valid("p" + std::to_string(9 + code) + "-range" + std::to_string(code) + "-limits",
          "motion_range_code " + std::to_string(code) + " with vectors at low and high", kUniformClauses,
          encoded(range_limit_planes(code)));
  for (uint32_t code = 1; code <= 3; ++code)
    suite.valid("p" + std::to_string(12 + code) + "-range" + std::to_string(code) + "-wrap",
          "differences that wrap in both directions, range " + std::to_string(code), kUniformClauses,
          encoded(wrap_planes(code)));
  {
    std::vector<MeshPlane> planes{uniform_plane(40, 40, 8, 8, 0)};
    for (int k = 0; k < 3; ++k) planes.push_back(inter_plane(planes[0].nodes));
    std::vector<Point> moved = planes[0].nodes;
    moved[1599].y -= 1;
    planes.push_back(inter_plane(moved));
    auto clauses = kUniformClauses;
    clauses.push_back("2.3");
    suite.valid("p16-zero-motion-runs", "long runs of node_motion_vector_flag '0': start-code emulation inside planes", clauses, encoded(planes));
  }
  {
    std::vector<MeshPlane> planes = with_motion(uniform_plane(5, 4, 30, 30, 1), 2, -10, 10, 17);
    std::vector<MeshPlane> second = with_motion(delaunay_plane(concat(box_boundary(100, 100, 500, 500, 2), random_inside(20, 100, 100, 500, 500, 17)), 8), 2, -10, 10, 18);
    planes.insert(planes.end(), second.begin(), second.end());
    planes.push_back(uniform_plane(3, 7, 9, 9, 3));
    auto clauses = kDelaunayClauses;
    clauses.push_back("5");
    suite.valid("p17-repeated-intra", "I-planes that change the topology: uniform, Delaunay, uniform", clauses, encoded(planes));
  }
  suite.valid("p18-no-end-code", "a stream without mesh_object_end_code (a warning, not an error)", kUniformClauses,
        encoded(with_motion(uniform_plane(4, 3, 12, 12, 0), 2, -5, 5, 18), MotionMethod::kMethod2, false));

  return suite.take();
}

// Delaunay meshes: convex, non-convex and degenerate boundaries, node orders.
std::vector<SuiteCase> delaunay_cases() {
  CaseList suite;
  suite.valid("p19-delaunay-convex", "a square boundary with 200 interior nodes and motion", kDelaunayClauses,
        encoded(with_motion(delaunay_plane(concat(box_boundary(50, 60, 950, 940, 1), random_inside(200, 50, 60, 950, 940, 19)), 4), 3, -25, 25, 19)));
  {
    std::vector<Point> comb = comb_boundary();
    const uint32_t b = static_cast<uint32_t>(comb.size());
    std::set<std::pair<int, int>> used;
    for (const Point& p : comb) used.insert({p.x, p.y});
    comb = concat(comb, random_inside(60, 0, 0, 1000, 200, 20, used));
    suite.valid("p20-delaunay-nonconvex", "a non-convex comb boundary with interior nodes", kDelaunayClauses,
          encoded(with_motion(delaunay_plane(comb, b), 2, -8, 8, 20)));
  }
  {
    std::vector<Point> nodes = box_boundary(0, 0, 1000, 1000, 40);
    const uint32_t b = static_cast<uint32_t>(nodes.size());
    nodes = concat(nodes, random_inside(300, 0, 0, 1000, 1000, 21));
    suite.valid("p21-delaunay-collinear", "collinear boundary runs (160 boundary nodes on a square)", kDelaunayClauses,
          encoded(with_motion(delaunay_plane(nodes, b), 2, -5, 5, 21)));
  }
  {
    std::vector<Point> nodes{{0, 0}, {0, 300}, {300, 300}, {300, 0}};
    for (int y = 1; y < 30; ++y)
      for (int x = 1; x < 30; ++x) nodes.push_back({x * 10, y * 10});
    suite.valid("p22-delaunay-cocircular-lattice", "a lattice: every cell cocircular, the §6.2 fan rule everywhere", kDelaunayClauses,
          encoded(with_motion(delaunay_plane(nodes, 4), 1, -2, 2, 22)));
  }
  {
    std::vector<Point> ring{{495, 500}, {496, 503}, {497, 504}, {500, 505}, {503, 504}, {504, 503},
                            {505, 500}, {504, 497}, {503, 496}, {500, 495}, {497, 496}, {496, 497}};
    suite.valid("p23-delaunay-circle", "twelve nodes on one circle: a fan from node 0", kDelaunayClauses,
          encoded(with_motion(delaunay_plane(ring, 12), 1, -3, 3, 23)));
  }
  suite.valid("p24-delaunay-3-nodes", "the smallest Delaunay mesh", kDelaunayClauses,
        encoded(with_motion(delaunay_plane({{10, 10}, {10, 500}, {600, 20}}, 3), 2, -60, 60, 24)));
  {
    std::vector<Point> nodes = star_boundary(1023, 420, 511, 25);
    std::set<std::pair<int, int>> used;
    for (const Point& p : nodes) used.insert({p.x, p.y});
    nodes = concat(nodes, random_inside(65535 - 1023, 230, 230, 794, 794, 25, used));
    std::vector<MeshPlane> planes{delaunay_plane(nodes, 1023)};
    std::vector<Point> moved = nodes;
    for (size_t i = 0; i < moved.size(); i += 97) moved[i].x += 3;
    planes.push_back(inter_plane(moved));
    suite.valid("p25-delaunay-65535-nodes", "the largest Delaunay mesh: 65,535 nodes, 1,023 of them on the boundary", kDelaunayClauses, encoded(planes));
  }
  {
    std::vector<Point> nodes = star_boundary(1023, 300, 500, 26);
    std::set<std::pair<int, int>> used;
    for (const Point& p : nodes) used.insert({p.x, p.y});
    suite.valid("p26-delaunay-1023-boundary", "1,023 boundary nodes on a star-shaped polygon", kDelaunayClauses,
          encoded(with_motion(delaunay_plane(concat(nodes, random_inside(100, 312, 312, 712, 712, 26, used)), 1023), 1, -4, 4, 26)));
  }
  {
    std::vector<Point> nodes{{0, 0}, {0, 1023}, {1023, 1023}, {1023, 0}, {1, 1}, {1022, 1022}, {1, 1022}, {1022, 1}};
    suite.valid("p27-delaunay-coordinate-extremes", "node coordinates at 0 and 1023", kDelaunayClauses,
          encoded(with_motion(delaunay_plane(nodes, 4), 1, -2, 2, 27)));
  }
  {
    // Down the left side with steps 1, 2, 4, …, 512: every delta length 0 … 10.
    std::vector<Point> nodes{{0, 0}};
    for (int step = 1; step <= 512; step *= 2) nodes.push_back({0, nodes.back().y + step});
    nodes.push_back({1023, 1023});
    nodes.push_back({1023, 0});
    const uint32_t b = static_cast<uint32_t>(nodes.size());
    std::set<std::pair<int, int>> used;
    for (const Point& p : nodes) used.insert({p.x, p.y});
    suite.valid("p28-delaunay-delta-lengths", "node deltas of every length 0 … 10 (11 cannot occur in a valid stream)", kDelaunayClauses,
          encoded(with_motion(delaunay_plane(concat(nodes, random_inside(40, 0, 0, 1023, 1023, 28, used)), b), 1, -3, 3, 28)));
  }
  {
    const std::vector<Point> spiral = spiral_boundary();
    suite.valid("p29-delaunay-spiral", "a spiral corridor boundary", kDelaunayClauses,
          encoded(with_motion(delaunay_plane(spiral, static_cast<uint32_t>(spiral.size())), 1, -5, 5, 29)));
  }
  {
    MeshPlane intra = delaunay_plane(concat(box_boundary(200, 200, 800, 800, 3), random_inside(150, 200, 200, 800, 800, 30)), 12);
    std::vector<MeshPlane> planes{intra};
    Random random(30);
    for (int limit : {31, 63, 127}) {
      std::vector<Point> next = planes.back().nodes;
      for (Point& p : next) {
        p.x += random.uniform(-limit / 2, limit / 2);
        p.y += random.uniform(-limit / 2, limit / 2);
      }
      next[5].x = planes.back().nodes[5].x + limit;
      planes.push_back(inter_plane(next));
    }
    suite.valid("p30-delaunay-all-ranges", "Method II on a Delaunay mesh with each motion_range_code", kDelaunayClauses, encoded(planes));
  }
  {
    std::vector<MeshPlane> planes{delaunay_plane(concat(box_boundary(0, 0, 200, 200, 1), random_inside(30, 0, 0, 200, 200, 31)), 4)};
    for (int k = 0; k < 3; ++k) {
      std::vector<Point> next = planes.back().nodes;
      for (Point& p : next) {
        p.x -= 100;
        p.y -= 100;
      }
      planes.push_back(inter_plane(next));
    }
    suite.valid("p31-positions-outside", "P-planes that move nodes to negative coordinates (positions are not range-limited)",
          kDelaunayClauses, encoded(planes));
  }
  suite.valid("p32-intra-only", "a single uniform I-plane", kUniformClauses, encoded({uniform_plane(9, 9, 7, 11, 2)}));
  {
    auto clauses = kUniformClauses;
    clauses.push_back("8");
    suite.valid("p33-method1-uniform", "Method I on a uniform mesh (decode with Method I)", clauses,
          encoded(with_motion(uniform_plane(7, 6, 14, 14, 2), 3, -15, 15, 33), MotionMethod::kMethod1), MotionMethod::kMethod1);
    auto dclauses = kDelaunayClauses;
    dclauses.push_back("8");
    suite.valid("p34-method1-delaunay", "Method I on a Delaunay mesh (decode with Method I)", dclauses,
          encoded(with_motion(delaunay_plane(concat(box_boundary(0, 0, 400, 400, 2), random_inside(50, 0, 0, 400, 400, 34)), 8), 3, -15, 15, 34),
                  MotionMethod::kMethod1),
          MotionMethod::kMethod1);
  }
  suite.valid("p35-long-sequence", "100 P-planes of small motion", kUniformClauses, encoded(with_motion(uniform_plane(5, 5, 20, 20, 3), 100, -2, 2, 35)));
  {
    std::vector<MeshPlane> planes{delaunay_plane(concat(box_boundary(0, 0, 300, 300, 1), random_inside(40, 0, 0, 300, 300, 36)), 4)};
    std::vector<Point> moved = planes[0].nodes;
    for (Point& p : moved) p.x += 300;  // beyond [−128, 127]: coded as a new I-plane
    planes.push_back(inter_plane(moved));
    for (Point& p : moved) p.y += 100;
    planes.push_back(inter_plane(moved));
    suite.valid("p36-delaunay-refresh", "motion beyond the largest range, coded as a new Delaunay I-plane (§10)", kDelaunayClauses, encoded(planes));
  }
  {
    std::vector<Point> nodes = box_boundary(0, 0, 1016, 1016, 128);
    suite.valid("p37-node0-origin", "node 0 at (0, 0) after 512 boundary nodes: 29 zero bits in a row (start-code emulation)",
          [&] {
            auto c = kDelaunayClauses;
            c.push_back("2.3");
            return c;
          }(),
          encoded(with_motion(delaunay_plane(concat(nodes, random_inside(100, 0, 0, 1016, 1016, 37)), 512), 1, -1, 1, 37)));
  }
  suite.valid("p38-range3-residuals", "large motion: range 3 with every residual value", kUniformClauses,
        encoded(with_motion(uniform_plane(10, 10, 60, 60, 0), 3, -128, 127, 38)));
  suite.valid("p39-uniform-odd-checkerboard", "split '10' on odd node counts", kUniformClauses, encoded(with_motion(uniform_plane(7, 3, 33, 21, 2), 2, -12, 12, 39)));
  suite.valid("p40-uniform-even-checkerboard", "split '11' on even node counts", kUniformClauses, encoded(with_motion(uniform_plane(8, 4, 21, 33, 3), 2, -12, 12, 40)));
  suite.valid("p41-delaunay-square-centre", "a square with one interior node", kDelaunayClauses,
        encoded(with_motion(delaunay_plane({{0, 0}, {0, 10}, {10, 10}, {10, 0}, {5, 5}}, 4), 2, -4, 4, 41)));
  suite.valid("p42-uniform-max-rect", "mesh_rect_size 255 both ways with range 3 motion", kUniformClauses,
        encoded(with_motion(uniform_plane(5, 5, 255, 255, 1), 2, -100, 100, 42)));

  return suite.take();
}

// Streams a decoder must reject, each with the error it must report.
std::vector<SuiteCase> rejected_cases() {
  CaseList suite;
  const std::vector<uint8_t> small = encoded(with_motion(uniform_plane(4, 3, 16, 16, 0), 2, -20, 20, 50));
  const std::vector<uint8_t> large_motion = encoded(with_motion(uniform_plane(4, 3, 16, 16, 0), 1, -100, 100, 51));
  const std::vector<uint8_t> small_delaunay =
      encoded(with_motion(delaunay_plane(concat(box_boundary(0, 0, 100, 100, 1), random_inside(10, 0, 0, 100, 100, 52)), 4), 1, -5, 5, 52));
  suite.invalid("n01-truncated-start-code", "the data ends inside mesh_object_start_code", {"2.1", "11"},
          std::vector<uint8_t>(small.begin(), small.begin() + 3), ErrorKind::kTruncated, "mesh_object_start_code", kNoPlane);
  for (const auto& [id, element, occurrence, base] :
       {std::tuple{"n02-truncated-uniform", "nr_of_mesh_nodes_verti", 0, &small},
        std::tuple{"n03-truncated-delaunay", "delta_x", 4, &small_delaunay},
        std::tuple{"n04-truncated-motion", "delta_mv_x_vlc", 3, &large_motion}}) {
    const Cut cut = cut_inside(*base, element, static_cast<size_t>(occurrence));
    suite.invalid(id, std::string("the data ends inside ") + element, {"3", "11"}, cut.stream, ErrorKind::kTruncated, element, cut.plane);
  }
  suite.invalid("n05-truncated-plane-start-code", "the data ends inside a plane start code", {"2.1", "11"},
          cut_inside(small, "mesh_object_plane_start_code", 2).stream, ErrorKind::kTruncated, "mesh_object_end_code", kNoPlane);
  suite.invalid("n06-mesh-type-10", "reserved mesh_type_code '10'", {"4", "11"}, patched(small, "mesh_type_code", 0, 2),
          ErrorKind::kReservedValue, "mesh_type_code", 0);
  suite.invalid("n07-mesh-type-11", "reserved mesh_type_code '11'", {"4", "11"}, patched(small, "mesh_type_code", 0, 3),
          ErrorKind::kReservedValue, "mesh_type_code", 0);
  suite.invalid("n08-motion-range-code-0", "reserved motion_range_code 0", {"4", "4.2", "11"}, patched(small, "motion_range_code", 1, 0),
          ErrorKind::kReservedValue, "motion_range_code", 2);
  {
    const TracedElement stuffing = trace_elements(small).at("next_start_code").at(0);
    suite.invalid("n09-bad-stuffing", "next_start_code() bits that are not '0' then '1's", {"2.2", "11"},
            patched(small, "next_start_code", 0, stuffing_pattern(stuffing.bits) ^ 1), ErrorKind::kBadStuffing, "next_start_code", 0);
  }
  suite.invalid("n10-nodes-hori-1", "nr_of_mesh_nodes_hori 1", {"4", "11"}, patched(small, "nr_of_mesh_nodes_hori", 0, 1),
          ErrorKind::kOutOfRange, "nr_of_mesh_nodes_hori", 0);
  suite.invalid("n11-rect-size-0", "mesh_rect_size_verti 0", {"4", "11"}, patched(small, "mesh_rect_size_verti", 0, 0),
          ErrorKind::kOutOfRange, "mesh_rect_size_verti", 0);
  suite.invalid("n12-nodes-2", "nr_of_mesh_nodes 2", {"4", "11"}, patched(small_delaunay, "nr_of_mesh_nodes", 0, 2),
          ErrorKind::kOutOfRange, "nr_of_mesh_nodes", 0);
  suite.invalid("n13-boundary-exceeds-nodes", "nr_of_boundary_nodes above nr_of_mesh_nodes", {"4", "11"},
          patched(small_delaunay, "nr_of_boundary_nodes", 0, 15), ErrorKind::kOutOfRange, "nr_of_boundary_nodes", 0);
  suite.invalid("n14-boundary-2", "nr_of_boundary_nodes 2", {"4", "11"}, patched(small_delaunay, "nr_of_boundary_nodes", 0, 2),
          ErrorKind::kOutOfRange, "nr_of_boundary_nodes", 0);
  suite.invalid("n15-clockwise-boundary", "a clockwise boundary", {"6.1", "11"},
          unchecked_delaunay({{0, 0}, {100, 0}, {100, 100}, {0, 100}, {50, 50}}, 4), ErrorKind::kGeometry, "MeshGeometry", 0);
  suite.invalid("n16-self-intersecting-boundary", "boundary edges that cross", {"6.1", "11"},
          unchecked_delaunay({{0, 0}, {0, 200}, {100, 0}, {120, 140}}, 4), ErrorKind::kGeometry, "MeshGeometry", 0);
  suite.invalid("n17-interior-node-outside", "an interior node outside the boundary", {"6.1", "11"},
          unchecked_delaunay({{0, 0}, {0, 100}, {100, 100}, {100, 0}, {150, 50}}, 4), ErrorKind::kGeometry, "MeshGeometry", 0);
  suite.invalid("n18-interior-node-on-boundary", "an interior node on a boundary edge", {"6.1", "11"},
          unchecked_delaunay({{0, 0}, {0, 100}, {100, 100}, {100, 0}, {100, 50}}, 4), ErrorKind::kGeometry, "MeshGeometry", 0);
  suite.invalid("n19-duplicate-nodes", "two nodes at the same place", {"6.1", "11"},
          unchecked_delaunay({{0, 0}, {0, 100}, {100, 100}, {100, 0}, {50, 50}, {50, 50}}, 4), ErrorKind::kGeometry, "MeshGeometry", 0);
  suite.invalid("n20-node0-not-top-left", "node 0 is not the top-left node", {"6.1", "11"},
          unchecked_delaunay({{50, 50}, {0, 100}, {100, 100}, {100, 0}}, 4), ErrorKind::kGeometry, "MeshGeometry", 0);
  {
    // 3 nodes, node0 (0, 0), then nine '1's: a dmv_length of 12 or more.
    std::string bits;
    auto put = [&](uint32_t v, int n) {
      for (int i = n - 1; i >= 0; --i) bits += ((v >> i) & 1) ? '1' : '0';
    };
    put(kMeshObjectStartCode, 32);
    put(kMeshObjectPlaneStartCode, 32);
    bits += "1" "01";
    put(3, 16);
    put(3, 10);
    put(0, 20);
    bits += "1111111110";
    bits += "0000000000000000000000";
    while (bits.size() % 8) bits += '0';
    put(kMeshObjectEndCode, 32);
    suite.invalid("n21-delta-length-12", "delta_x_len_vlc '1111111110': length 12 is not part of this syntax", {"4.1", "11"},
            bits_to_bytes(bits), ErrorKind::kInvalidCode, "delta_x_len_vlc", 0);
  }
  suite.invalid("n22-coordinate-past-1023", "a node x coordinate of 1024", {"4", "4.1", "11"},
          unchecked_delaunay(3, 3, {0, 0}, {{0, 1000}, {1024, -1000}}), ErrorKind::kOutOfRange, "delta_x", 0);
  suite.invalid("n23-coordinate-below-0", "a node y coordinate of −1", {"4", "4.1", "11"},
          unchecked_delaunay(3, 3, {5, 0}, {{-5, -1}, {10, 10}}), ErrorKind::kOutOfRange, "delta_y", 0);
  {
    // The P-plane of `small` with the I-plane removed.
    const auto starts = trace_elements(small).at("mesh_object_plane_start_code");
    std::vector<uint8_t> stream(small.begin(), small.begin() + 4);
    stream.insert(stream.end(), small.begin() + static_cast<std::ptrdiff_t>(starts[1].offset / 8), small.end());
    suite.invalid("n24-p-plane-first", "a P-plane before any I-plane", {"3.1", "11"}, stream, ErrorKind::kStructure, "new_mesh_flag", 0);
  }
  {
    std::vector<uint8_t> stream = small;
    stream.push_back(0x00);
    suite.invalid("n25-trailing-data", "a byte after mesh_object_end_code", {"3.1", "11"}, stream, ErrorKind::kTrailingData,
            "mesh_object_end_code", kNoPlane);
  }
  suite.invalid("n26-missing-object-start-code", "a stream that starts with a plane start code", {"2.1", "3", "11"},
          std::vector<uint8_t>(small.begin() + 4, small.end()), ErrorKind::kMissingStartCode, "mesh_object_start_code", kNoPlane);
  suite.invalid("n27-invalid-motion-code", "delta_mv_x_vlc of twelve '0' bits: no motion code starts so", {"4.2", "11"},
          overwritten(small, "delta_mv_x_vlc", 0, 12, 0), ErrorKind::kInvalidCode, "delta_mv_x_vlc", 1);
  suite.invalid("n28-huge-count", "nr_of_mesh_nodes 65535 with a few bytes of data: rejected before allocating", {"4", "11"},
          patched(small_delaunay, "nr_of_mesh_nodes", 0, 65535), ErrorKind::kTruncated, "delta_x_len_vlc", 0);
  suite.invalid("n29-garbage-start-code", "a start code that is neither a plane nor the end code", {"2.1", "3", "11"},
          [&] {
            std::vector<uint8_t> s = small;
            s[s.size() - 1] = 0xB6;
            return s;
          }(),
          ErrorKind::kMissingStartCode, "mesh_object_end_code", kNoPlane);
  suite.invalid("n30-nodes-verti-1", "nr_of_mesh_nodes_verti 1", {"4", "11"}, patched(small, "nr_of_mesh_nodes_verti", 0, 1),
          ErrorKind::kOutOfRange, "nr_of_mesh_nodes_verti", 0);
  suite.invalid("n31-rect-size-hori-0", "mesh_rect_size_hori 0", {"4", "11"}, patched(small, "mesh_rect_size_hori", 0, 0),
          ErrorKind::kOutOfRange, "mesh_rect_size_hori", 0);
  suite.invalid("n32-delta-y-length-11", "a delta_y of 1024, the shortest of length 11: a node y coordinate of 1024", {"4", "4.1", "11"},
          unchecked_delaunay(3, 3, {0, 0}, {{10, 1024}, {10, -1000}}), ErrorKind::kOutOfRange, "delta_y", 0);
  suite.invalid("n33-boundary-zero-area", "a boundary of three collinear nodes: zero area", {"6.1", "11"},
          unchecked_delaunay({{0, 0}, {0, 100}, {0, 50}}, 3), ErrorKind::kGeometry, "MeshGeometry", 0);
  suite.invalid("n34-boundary-folds-back", "a boundary that runs back along its own edge at node 3", {"6.1", "11"},
          unchecked_delaunay({{0, 0}, {0, 100}, {100, 100}, {100, 0}, {100, 50}}, 5), ErrorKind::kGeometry, "MeshGeometry", 0);
  suite.invalid("n35-boundary-edges-touch", "a boundary node on a non-adjacent boundary edge", {"6.1", "11"},
          unchecked_delaunay({{0, 0}, {0, 200}, {200, 200}, {200, 0}, {100, 200}}, 5), ErrorKind::kGeometry, "MeshGeometry", 0);
  {
    // The '1's right, the first bit '1' too: only the rule that stuffing starts with '0' rejects it.
    const TracedElement stuffing = trace_elements(small).at("next_start_code").at(0);
    suite.invalid("n36-stuffing-first-bit-one", "next_start_code() bits all '1's: the first is not '0'", {"2.2", "11"},
            patched(small, "next_start_code", 0, stuffing_pattern(stuffing.bits) | 1u << (stuffing.bits - 1)), ErrorKind::kBadStuffing,
            "next_start_code", 0);
  }
  return suite.take();
}

}  // namespace

SuiteCase decode_case(std::string id, std::string purpose, std::vector<std::string> clauses, std::vector<uint8_t> stream) {
  SuiteCase c;
  c.id = std::move(id);
  c.purpose = std::move(purpose);
  c.clauses = std::move(clauses);
  c.stream = std::move(stream);
  return c;
}

SuiteCase reject_case(std::string id, std::string purpose, std::vector<std::string> clauses, std::vector<uint8_t> stream, ErrorKind kind,
                      std::string element, int64_t plane) {
  SuiteCase c = decode_case(std::move(id), std::move(purpose), std::move(clauses), std::move(stream));
  c.valid = false;
  c.error_kind = kind;
  c.error_element = std::move(element);
  c.error_plane = plane;
  return c;
}

std::vector<SuiteCase> build_suite() {
  std::vector<SuiteCase> suite;
  for (auto group : {uniform_cases, delaunay_cases, rejected_cases})
    for (SuiteCase& c : group()) suite.push_back(std::move(c));
  return suite;
}

}  // namespace m4mesh
