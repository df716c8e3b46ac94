#include "mesh3d/metrics.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "common/error.h"

namespace m4mesh {

namespace {

double distance(const Vec3& a, const Vec3& b) {
  const double dx = a.x - b.x, dy = a.y - b.y, dz = a.z - b.z;
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

// A NaN or an infinity would turn every figure into nonsense (a KG error of
// 0, a PSNR of inf): refused, naming where.
void require_finite(const MeshSequence& s, const char* which) {
  for (size_t f = 0; f < s.frames.size(); ++f)
    for (size_t i = 0; i < s.frames[f].size(); ++i) {
      const Vec3& v = s.frames[f][i];
      if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
        throw Error(ErrorKind::kInput, "", kNoPlane, kNoOffset,
                    std::string(which) + ": frame " + std::to_string(f) + ", vertex " + std::to_string(i) + " is not a finite point");
    }
}

void require_comparable(const MeshSequence& a, const MeshSequence& b) {
  require_finite(a, "the original");
  require_finite(b, "the decoded sequence");
  std::string differences;
  if (a.vertex_count != b.vertex_count) differences += ", " + std::to_string(a.vertex_count) + "/" + std::to_string(b.vertex_count) + " vertices";
  if (a.frames.size() != b.frames.size()) differences += ", " + std::to_string(a.frames.size()) + "/" + std::to_string(b.frames.size()) + " frames";
  if (differences.empty() && !same_faces(a.faces, b.faces)) differences = ", other faces (or the same faces numbered otherwise: a sequence decoded from a stream of encode3d --reorder is compared through the stream itself)";
  if (!differences.empty()) throw Error(ErrorKind::kInput, "", kNoPlane, kNoOffset, "the sequences differ: " + differences.substr(2));
  if (a.frames.empty()) throw Error(ErrorKind::kInput, "", kNoPlane, kNoOffset, "no frames to compare");
}

// The mean of a frame's positions (KG's per-frame centre).
Vec3 centroid(std::span<const Vec3> frame) {
  Vec3 mean;
  for (const Vec3& v : frame) {
    mean.x += v.x;
    mean.y += v.y;
    mean.z += v.z;
  }
  const double n = static_cast<double>(frame.size());
  return {mean.x / n, mean.y / n, mean.z / n};
}

// Unique undirected edges of the faces.
std::vector<std::pair<NodeIndex, NodeIndex>> edges_of(const MeshSequence& s) {
  std::vector<std::pair<NodeIndex, NodeIndex>> edges;
  for (const Triangle& t : s.faces)
    for (int j = 0; j < 3; ++j) edges.push_back(std::minmax(t.v[j], t.v[(j + 1) % 3]));
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  return edges;
}

// KG error of sequences already found comparable.
double kg_of(const MeshSequence& a, const MeshSequence& b) {
  double error = 0, spread = 0;
  for (size_t f = 0; f < a.frames.size(); ++f) {
    const std::vector<Vec3>& o = a.frames[f];
    const Vec3 mean = centroid(o);
    for (size_t i = 0; i < o.size(); ++i) {
      const Vec3& d = b.frames[f][i];
      error += (o[i].x - d.x) * (o[i].x - d.x) + (o[i].y - d.y) * (o[i].y - d.y) + (o[i].z - d.z) * (o[i].z - d.z);
      spread += (o[i].x - mean.x) * (o[i].x - mean.x) + (o[i].y - mean.y) * (o[i].y - mean.y) + (o[i].z - mean.z) * (o[i].z - mean.z);
    }
  }
  return spread > 0 ? 100.0 * std::sqrt(error) / std::sqrt(spread) : 0.0;
}

// The diagonal of the largest per-frame bounding box (Eq. 5's dmax).
double largest_box_diagonal(const MeshSequence& a) {
  double dmax = 0;
  for (const std::vector<Vec3>& frame : a.frames) {
    const Box3 box = box_of(frame);
    dmax = std::max(dmax, distance(box.lo, box.hi));
  }
  return dmax;
}

double psnr_of(double dmax, double mse) { return mse > 0 ? 10.0 * std::log10(dmax * dmax / mse) : INFINITY; }

}  // namespace

double kg_error(const MeshSequence& a, const MeshSequence& b) {
  require_comparable(a, b);
  return kg_of(a, b);
}

void QualityMeter::add(uint32_t frame, std::span<const Float3> decoded) {
  if (frame != next_) {
    waiting_[frame].assign(decoded.begin(), decoded.end());
    return;
  }
  measure(frame, decoded);
  for (auto it = waiting_.find(next_); it != waiting_.end(); it = waiting_.find(next_)) {
    measure(next_, it->second);
    waiting_.erase(it);
  }
}

void QualityMeter::measure(uint32_t frame, std::span<const Float3> decoded) {
  const std::span<const Vec3> o = reader_.get(frame);
  const Vec3 mean = centroid(o);
  for (size_t i = 0; i < o.size(); ++i) {
    const Vec3 d{decoded[i][0], decoded[i][1], decoded[i][2]};
    if (!std::isfinite(d.x) || !std::isfinite(d.y) || !std::isfinite(d.z))
      throw Error(ErrorKind::kInput, "", kNoPlane, kNoOffset,
                  "the decoded sequence: frame " + std::to_string(frame) + ", vertex " + std::to_string(i) + " is not a finite point");
    error_ += (o[i].x - d.x) * (o[i].x - d.x) + (o[i].y - d.y) * (o[i].y - d.y) + (o[i].z - d.z) * (o[i].z - d.z);
    spread_ += (o[i].x - mean.x) * (o[i].x - mean.x) + (o[i].y - mean.y) * (o[i].y - mean.y) + (o[i].z - mean.z) * (o[i].z - mean.z);
    const double e = distance(o[i], d);
    squared_distances_ += e * e;
    max_error_ = std::max(max_error_, e);
  }
  ++next_;
}

double QualityMeter::kg() const { return spread_ > 0 ? 100.0 * std::sqrt(error_) / std::sqrt(spread_) : 0.0; }

double QualityMeter::psnr() const {
  return psnr_of(original_.scan().largest_frame_diagonal, squared_distances_ / (static_cast<double>(next_) * original_.vertex_count()));
}

double psnr(const MeshSequence& a, const MeshSequence& b) {
  require_comparable(a, b);
  double squared = 0;
  for (size_t f = 0; f < a.frames.size(); ++f)
    for (size_t i = 0; i < a.frames[f].size(); ++i) {
      const double e = distance(a.frames[f][i], b.frames[f][i]);
      squared += e * e;
    }
  return psnr_of(largest_box_diagonal(a), squared / (static_cast<double>(a.frames.size()) * a.vertex_count));
}

std::vector<FrameMetrics> per_frame_metrics(const MeshSequence& a, const MeshSequence& b) {
  require_comparable(a, b);
  const double dmax = largest_box_diagonal(a);
  std::vector<FrameMetrics> out(a.frames.size());
  for (size_t f = 0; f < a.frames.size(); ++f) {
    double squared = 0;
    for (size_t i = 0; i < a.frames[f].size(); ++i) {
      const double e = distance(a.frames[f][i], b.frames[f][i]);
      squared += e * e;
      out[f].max_error = std::max(out[f].max_error, e);
    }
    const double mse = squared / a.vertex_count;
    out[f].rmse = std::sqrt(mse);
    out[f].psnr = psnr_of(dmax, mse);
  }
  return out;
}

std::vector<std::string> metrics_warnings(const MeshSequence& a) {
  std::vector<std::string> warnings;
  if (a.frames.empty() || a.vertex_count == 0) return warnings;
  const char* names = "xyz";
  auto coordinate = [](const Vec3& v, int axis) { return axis == 0 ? v.x : axis == 1 ? v.y : v.z; };
  // Flatness over every frame.
  double extent[3];
  for (int axis = 0; axis < 3; ++axis) {
    double lo = INFINITY, hi = -INFINITY;
    for (const std::vector<Vec3>& frame : a.frames)
      for (const Vec3& v : frame) {
        lo = std::min(lo, coordinate(v, axis));
        hi = std::max(hi, coordinate(v, axis));
      }
    extent[axis] = hi - lo;
  }
  const double largest = std::max({extent[0], extent[1], extent[2]});
  for (int axis = 0; axis < 3; ++axis)
    if (largest > 0 && extent[axis] < 1e-4 * largest)
      warnings.push_back(std::string("the sequence hardly extends along ") + names[axis] + " (" + std::to_string(extent[axis]) + " of " +
                         std::to_string(largest) + "): errors along it barely count, and a grid over the box collapses it");
  // Outliers in frame 0: its box against the box of its middle 98 % per axis.
  double full = 0, middle = 0;
  for (int axis = 0; axis < 3; ++axis) {
    std::vector<double> c;
    c.reserve(a.frames[0].size());
    for (const Vec3& v : a.frames[0]) c.push_back(coordinate(v, axis));
    std::sort(c.begin(), c.end());
    full = std::max(full, c.back() - c.front());
    middle = std::max(middle, c[c.size() - 1 - c.size() / 100] - c[c.size() / 100]);
  }
  if (middle > 0 && full > 100 * middle)
    warnings.push_back("a few vertices lie far from the rest: frame 0's box is " + std::to_string(static_cast<int64_t>(full / middle)) +
                       " times that of 98 % of its vertices, and KG error and PSNR are relative to it");
  return warnings;
}

MetricsReference::MetricsReference(const MeshSequence& a, const StedParams& p) : original_(a), params_(p), edges_(edges_of(a)) {
  if (a.frames.empty()) throw Error(ErrorKind::kInput, "", kNoPlane, kNoOffset, "no frames to compare");
  const size_t V = a.vertex_count, F = a.frames.size();
  // NE(i, d): the edges incident to a vertex within topological distance d of i.
  std::vector<std::vector<NodeIndex>> neighbours(V);
  for (const auto& [u, v] : edges_) {
    neighbours[u].push_back(v);
    neighbours[v].push_back(u);
  }
  std::vector<std::vector<uint32_t>> incident(V);
  for (uint32_t e = 0; e < edges_.size(); ++e) {
    incident[edges_[e].first].push_back(e);
    incident[edges_[e].second].push_back(e);
  }
  neighbourhood_.resize(V);
  for (NodeIndex i = 0; i < V; ++i) {
    std::set<NodeIndex> ring{i};
    std::vector<NodeIndex> frontier{i};
    for (int step = 0; step < p.d; ++step) {
      std::vector<NodeIndex> next;
      for (NodeIndex u : frontier)
        for (NodeIndex v : neighbours[u])
          if (ring.insert(v).second) next.push_back(v);
      frontier = std::move(next);
    }
    std::set<uint32_t> es;
    for (NodeIndex u : ring) es.insert(incident[u].begin(), incident[u].end());
    neighbourhood_[i].assign(es.begin(), es.end());
  }
  if (F < 2) return;
  // ld from the original's first frame.
  const double ld = diameter(a.frames[0]);
  diameter_ = ld > 0 ? ld : 1;
  temporal_edges_.resize(V * (F - 1));
  speeds_.resize(V * (F - 1));
  for (size_t i = 0; i < V; ++i) {
    double* tel = temporal_edges_.data() + i * (F - 1);
    for (size_t f = 0; f + 1 < F; ++f) {
      const Vec3 &u = a.frames[f][i], &v = a.frames[f + 1][i];
      const double dx = (v.x - u.x) / diameter_, dy = (v.y - u.y) / diameter_, dz = (v.z - u.z) / diameter_;
      tel[f] = std::sqrt(dx * dx + dy * dy + dz * dz + p.dt * p.dt);
    }
    // Eq. 17: the mean of tel over the frames of the window that have one.
    for (size_t f = 0; f + 1 < F; ++f) {
      const size_t from = f >= static_cast<size_t>(p.w) ? f - static_cast<size_t>(p.w) : 0;
      const size_t to = std::min(F - 2, f + static_cast<size_t>(p.w));
      double speed = 0;
      for (size_t k = from; k <= to; ++k) speed += tel[k];
      speeds_[i * (F - 1) + f] = speed / static_cast<double>(to - from + 1);
    }
  }
}

void MetricsReference::sted(const MeshSequence& b, double& spatial, double& temporal, double& combined) const {
  const MeshSequence& a = original_;
  const size_t V = a.vertex_count, F = a.frames.size();
  // Spatial error, Eqs. 10–14.
  double spatial_sum = 0;
  std::vector<double> el(edges_.size()), ed(edges_.size());
  for (size_t f = 0; f < F; ++f) {
    for (size_t e = 0; e < edges_.size(); ++e) {
      el[e] = distance(a.frames[f][edges_[e].first], a.frames[f][edges_[e].second]);
      const double distorted = distance(b.frames[f][edges_[e].first], b.frames[f][edges_[e].second]);
      ed[e] = el[e] > 0 ? std::abs(el[e] - distorted) / el[e] : 0.0;
    }
    for (size_t i = 0; i < V; ++i) {
      double weight = 0, mean = 0;
      for (uint32_t e : neighbourhood_[i]) {
        weight += el[e];
        mean += ed[e] * el[e];
      }
      if (weight <= 0) continue;
      mean /= weight;
      double variance = 0;
      for (uint32_t e : neighbourhood_[i]) variance += (ed[e] - mean) * (ed[e] - mean) * el[e];
      spatial_sum += std::sqrt(variance / weight);
    }
  }
  spatial = spatial_sum / (static_cast<double>(V) * static_cast<double>(F));

  // Temporal error, Eqs. 15–19.
  temporal = 0;
  if (F >= 2) {
    double temporal_sum = 0;
    for (size_t i = 0; i < V; ++i)
      for (size_t f = 0; f + 1 < F; ++f) {
        const Vec3 &u = b.frames[f][i], &v = b.frames[f + 1][i];
        const double dx = (v.x - u.x) / diameter_, dy = (v.y - u.y) / diameter_, dz = (v.z - u.z) / diameter_;
        const double tel = std::sqrt(dx * dx + dy * dy + dz * dz + params_.dt * params_.dt);
        temporal_sum += std::abs(temporal_edges_[i * (F - 1) + f] - tel) / speeds_[i * (F - 1) + f];
      }
    temporal = temporal_sum / (static_cast<double>(V) * static_cast<double>(F - 1));
  }
  combined = std::sqrt(spatial * spatial + params_.c * params_.c * temporal * temporal);
}

double diameter(std::span<const Vec3> points) {
  if (points.empty()) return 0;
  // A lower bound from farthest-point sweeps.
  auto farthest = [&](const Vec3& from) {
    size_t at = 0;
    for (size_t i = 1; i < points.size(); ++i)
      if (distance(from, points[i]) > distance(from, points[at])) at = i;
    return at;
  };
  size_t end = 0;
  double best = 0;
  for (int sweep = 0; sweep < 4; ++sweep) {
    const size_t next = farthest(points[end]);
    best = std::max(best, distance(points[end], points[next]));
    end = next;
  }
  // A point is farther than |p − c| + R from none (c the box centre, R the
  // largest distance from c): only points whose bound exceeds the lower
  // bound can end a longer pair, and both ends of one must.
  const auto [lo, hi] = box_of(points);
  const Vec3 centre{(lo.x + hi.x) / 2, (lo.y + hi.y) / 2, (lo.z + hi.z) / 2};
  double radius = 0;
  for (const Vec3& p : points) radius = std::max(radius, distance(p, centre));
  std::vector<Vec3> candidates;
  for (const Vec3& p : points)
    if (distance(p, centre) + radius > best) candidates.push_back(p);
  for (size_t i = 0; i < candidates.size(); ++i)
    for (size_t j = i + 1; j < candidates.size(); ++j) best = std::max(best, distance(candidates[i], candidates[j]));
  return best;
}

void sted(const MeshSequence& a, const MeshSequence& b, const StedParams& p, double& spatial, double& temporal, double& combined) {
  require_comparable(a, b);
  const SequenceMetrics m = MetricsReference(a, p).compare(b);
  spatial = m.sted_spatial;
  temporal = m.sted_temporal;
  combined = m.sted;
}

SequenceMetrics MetricsReference::compare(const MeshSequence& b) const {
  const MeshSequence& a = original_;
  require_comparable(a, b);
  SequenceMetrics m;
  double squared = 0;
  for (size_t f = 0; f < a.frames.size(); ++f)
    for (size_t i = 0; i < a.vertex_count; ++i) {
      const double e = distance(a.frames[f][i], b.frames[f][i]);
      squared += e * e;
      m.max_error = std::max(m.max_error, e);
    }
  const double mse = squared / (static_cast<double>(a.frames.size()) * a.vertex_count);
  m.rmse = std::sqrt(mse);
  m.kg_error = kg_of(a, b);
  m.psnr = psnr_of(largest_box_diagonal(a), mse);
  sted(b, m.sted_spatial, m.sted_temporal, m.sted);
  return m;
}

SequenceMetrics compare_sequences(const MeshSequence& a, const MeshSequence& b, const StedParams& params) {
  require_comparable(a, b);  // before the reference's set-up: an error names what differs
  return MetricsReference(a, params).compare(b);
}

}  // namespace m4mesh
