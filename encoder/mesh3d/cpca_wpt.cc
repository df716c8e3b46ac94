// The clustered-PCA codec (codec_id 4) encoding (docs/codec_cpca_wpt.md):
// k-means on the vertices' trajectories, per cluster the principal
// components of its motion about the mean shape, each quantized into one
// refinement operator, and the operators sent in decreasing weight (WPT:
// squared error removed per bit) or round robin over the clusters (RPT).
#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <numbers>
#include <optional>

#include "codecs3d/codec_encoder.h"
#include "encoder/mesh3d/codec_options.h"
#include "common/bit_cast.h"
#include "common/error.h"
#include "common/parallel.h"
#include "encoder/mesh3d/base_mesh.h"
#include "mesh3d/cpca_wpt.h"
#include "mesh3d/metrics.h"
#include "mesh3d/quantization.h"
#include "syntax/mesh3d/cpca_wpt.h"
#include "syntax/mesh3d/entropy_io.h"

namespace m4mesh {

namespace {

// The noise step's log2 in half steps (2 log2 Δ): the default, and the
// range --noise and the search take.
constexpr int kDefaultNoise = 8, kMinNoise = -8, kMaxNoise = 24;

// Principal components per cluster: the paper's, and the most --components takes.
constexpr size_t kPaperComponents = 40, kMaxComponents = 4096;
// Trajectory components take their basis this many half steps (√2 each)
// finer than the equal-error rule: measured, 1 to 2 % fewer bytes at the
// same KG on the cow and the horse (the basis is predicted over the mesh,
// the coefficients are not).
constexpr int kTrajectoryBasisFiner = 1;
// Clusters: the paper's.
constexpr int kPaperClusters = 10;
// The mean shape's quantization bits: the default, and the range --bits takes.
constexpr int kDefaultBits = 12, kMinBits = 4, kMaxBits = 24;


// A whole number least … most written in `text`, else a usage error naming the option.
size_t parse_count(const std::string& text, const char* option, size_t most, size_t least = 1) {
  size_t used = 0;
  unsigned long value = 0;
  try {
    value = std::stoul(text, &used);
  } catch (const std::exception&) {
  }
  if (used == 0 || used != text.size() || text[0] == '-' || value < least || value > most)
    throw usage_error(std::string(option) + " is auto or an integer in " + std::to_string(least) + " … " + std::to_string(most) + " (cpca-wpt)");
  return value;
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Vertex v's trajectory is row v: x, y, z of frame 0, then of frame 1, …
Eigen::MatrixXd trajectories(const MeshSequence& s) {
  Eigen::MatrixXd x(s.vertex_count, 3 * static_cast<Eigen::Index>(s.frames.size()));
  for (size_t f = 0; f < s.frames.size(); ++f)
    for (size_t v = 0; v < s.vertex_count; ++v) {
      const Vec3& p = s.frames[f][v];
      x(static_cast<Eigen::Index>(v), static_cast<Eigen::Index>(3 * f)) = p.x;
      x(static_cast<Eigen::Index>(v), static_cast<Eigen::Index>(3 * f + 1)) = p.y;
      x(static_cast<Eigen::Index>(v), static_cast<Eigen::Index>(3 * f + 2)) = p.z;
    }
  return x;
}

// k-means on the trajectories, deterministic: the first center is the
// trajectory farthest from the mean, each next the one farthest from the
// centers so far (ties: the lowest vertex); then Lloyd iterations (ties:
// the lowest cluster) until no vertex moves, at most 50. Clusters are
// numbered by their first vertex; none is empty.
std::vector<uint32_t> cluster_trajectories(const Eigen::MatrixXd& x, int k) {
  const Eigen::Index vertices = x.rows();
  const Eigen::RowVectorXd mean = x.colwise().mean();
  Eigen::VectorXd nearest = (x.rowwise() - mean).rowwise().squaredNorm();
  std::vector<Eigen::Index> seeds;
  for (int c = 0; c < k; ++c) {
    Eigen::Index far = 0;
    nearest.maxCoeff(&far);
    if (c > 0 && !(nearest(far) > 0)) break;  // fewer distinct trajectories than clusters
    seeds.push_back(far);
    nearest = nearest.cwiseMin((x.rowwise() - x.row(far)).rowwise().squaredNorm());
  }
  Eigen::MatrixXd centers(static_cast<Eigen::Index>(seeds.size()), x.cols());
  for (size_t c = 0; c < seeds.size(); ++c) centers.row(static_cast<Eigen::Index>(c)) = x.row(seeds[c]);
  std::vector<uint32_t> cluster(static_cast<size_t>(vertices), UINT32_MAX);
  for (int iteration = 0; iteration < 50; ++iteration) {
    const Eigen::MatrixXd cross = x * centers.transpose();
    const Eigen::VectorXd norms = centers.rowwise().squaredNorm();
    bool moved = false;
    for (Eigen::Index v = 0; v < vertices; ++v) {
      Eigen::Index best = 0;
      (norms.transpose() - 2 * cross.row(v)).minCoeff(&best);
      moved |= cluster[static_cast<size_t>(v)] != static_cast<uint32_t>(best);
      cluster[static_cast<size_t>(v)] = static_cast<uint32_t>(best);
    }
    if (!moved) break;
    Eigen::MatrixXd sums = Eigen::MatrixXd::Zero(centers.rows(), centers.cols());
    std::vector<double> counts(seeds.size(), 0);
    for (Eigen::Index v = 0; v < vertices; ++v) {
      sums.row(cluster[static_cast<size_t>(v)]) += x.row(v);
      counts[cluster[static_cast<size_t>(v)]] += 1;
    }
    for (size_t c = 0; c < seeds.size(); ++c)
      if (counts[c] > 0) centers.row(static_cast<Eigen::Index>(c)) = sums.row(static_cast<Eigen::Index>(c)) / counts[c];
  }
  std::vector<uint32_t> renumbered(seeds.size(), UINT32_MAX);
  uint32_t next = 0;
  for (uint32_t& c : cluster) {
    if (renumbered[c] == UINT32_MAX) renumbered[c] = next++;
    c = renumbered[c];
  }
  return cluster;
}

// The clusters of k-means asked for `requested` clusters, and its seconds:
// computed once per count and shared by a search's candidates.
struct Clustering {
  int requested = 0;
  std::vector<uint32_t> cluster_of;
  double seconds = 0;
};

Clustering clustering(const MeshSequence& s, int requested) {
  const auto start = std::chrono::steady_clock::now();
  Clustering c{requested, cluster_trajectories(trajectories(s), std::min<int>(requested, static_cast<int>(s.vertex_count))), 0};
  c.seconds = seconds_since(start);
  return c;
}

// A principal component of a cluster's motion matrix D (3M × N):
// D ≈ Σ sigma · basis · coefficientsᵀ, basis and coefficients unit vectors.
struct Component {
  double sigma;
  Eigen::VectorXd basis, coefficients;
};

// The components in decreasing sigma, at most `count`, those with sigma
// above 10^−6 of the first: from the eigenvectors of the smaller Gram
// matrix (DᵀD or DDᵀ). The largest coefficient of each is positive.
std::vector<Component> principal_components(const Eigen::MatrixXd& d, size_t count) {
  const bool by_frames = d.rows() >= d.cols();
  const Eigen::MatrixXd gram = by_frames ? Eigen::MatrixXd(d.transpose() * d) : Eigen::MatrixXd(d * d.transpose());
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(gram);
  std::vector<Component> components;
  const Eigen::Index n = gram.rows();
  const double largest = n > 0 ? eigen.eigenvalues()(n - 1) : 0;
  for (Eigen::Index i = n - 1; i >= 0 && components.size() < count; --i) {
    const double lambda = eigen.eigenvalues()(i);
    if (!(lambda > 1e-12 * largest)) break;
    Component c{std::sqrt(lambda), {}, {}};
    if (by_frames) {
      c.coefficients = eigen.eigenvectors().col(i);
      c.basis = d * c.coefficients / c.sigma;
    } else {
      c.basis = eigen.eigenvectors().col(i);
      c.coefficients = d.transpose() * c.basis / c.sigma;
    }
    Eigen::Index at = 0;
    c.coefficients.cwiseAbs().maxCoeff(&at);
    if (c.coefficients(at) < 0) {
      c.coefficients = -c.coefficients;
      c.basis = -c.basis;
    }
    components.push_back(std::move(c));
  }
  return components;
}

// A cluster's translation per frame and axis (3N values, grid units): the
// mean over its vertices of their motion about the mean shape.
using Translation = Eigen::VectorXd;

// One refinement unit as coded, with its weight's terms: a cluster's start
// (translation) or one of its components (basis, coefficients).
struct Operator {
  uint32_t cluster = 0;
  uint32_t kind = kCpcaComponent;
  uint32_t shift = kCpcaShiftBias;
  int basis_exponent = 0, coefficient_exponent = 0;  // the values are the real ones × 2^(exponent / 2)
  std::vector<int32_t> basis, coefficients, translation;
  double gain = 0;    // the squared error it removes (grid units², the decoder's reconstruction)
  uint64_t bytes = 0;  // its unit, start code and header included
};

void apply(CpcaAnimation& animation, std::span<const NodeIndex> members, const Operator& op) {
  if (op.kind == kCpcaStart)
    animation.translate(members, op.translation, op.shift);
  else
    animation.refine(members, op.basis, op.coefficients, op.shift, op.kind == kCpcaTrajectory);
}

// A motion matrix (3M × N) as the members' trajectories (M × 3N): row i,
// column 3n + a holds axis a of member i in frame n.
Eigen::MatrixXd as_trajectories(const Eigen::MatrixXd& d) {
  Eigen::MatrixXd t(d.rows() / 3, 3 * d.cols());
  for (Eigen::Index row = 0; row < d.rows(); ++row)
    for (Eigen::Index n = 0; n < d.cols(); ++n) t(row / 3, 3 * n + row % 3) = d(row, n);
  return t;
}

// Exponent e such that |largest| · 2^e < 2^bits.
int exponent_for(double largest, int bits) { return largest > 0 ? bits - 1 - std::ilogb(largest) : bits; }

// 2^(half / 2), the same on every platform (√2 is a constant).
double power_of_two(int half) { return half % 2 == 0 ? std::ldexp(1.0, half / 2) : std::ldexp(std::numbers::sqrt2, (half - 1) / 2); }

// Floor division by 2.
int half_of(int value) { return value >= 0 ? value / 2 : -((1 - value) / 2); }

std::vector<int32_t> scaled(const Eigen::VectorXd& values, int half_exponent) {
  const double scale = power_of_two(half_exponent);
  std::vector<int32_t> out(static_cast<size_t>(values.size()));
  for (Eigen::Index i = 0; i < values.size(); ++i) out[static_cast<size_t>(i)] = static_cast<int32_t>(std::nearbyint(values(i) * scale));
  return out;
}

// The operator of a component at the noise step Δ = 2^(noise / 2) grid
// units: the coefficients sigma · w in steps of Δ and the basis in steps of
// about Δ / sigma, so that both add noise of Δ's order to the animation
// (each as fine as their ranges, 2^15 and 2^23, allow). The two steps are
// powers of √2 whose product is a power of 2: their product ×
// 2^−(shift − 16) is in steps of 2^−F grid units.
// `basis_finer` half steps make the basis finer than that rule.
Operator quantize(const Component& c, uint32_t cluster, int noise, int fraction_bits, int basis_finer) {
  const Eigen::VectorXd weighted = c.sigma * c.coefficients;
  const int basis_exponent = std::min(2 * std::ilogb(c.sigma) - noise + basis_finer, 2 * exponent_for(c.basis.cwiseAbs().maxCoeff(), 15));
  const int wanted = std::min(-noise, 2 * exponent_for(weighted.cwiseAbs().maxCoeff(), 23));
  const int shift = std::clamp(half_of(basis_exponent + wanted) - fraction_bits, -static_cast<int>(kCpcaShiftBias),
                               static_cast<int>(kCpcaMaxShift - kCpcaShiftBias));
  const int coefficient_exponent = 2 * (shift + fraction_bits) - basis_exponent;
  Operator op;
  op.cluster = cluster;
  op.shift = static_cast<uint32_t>(shift + static_cast<int>(kCpcaShiftBias));
  op.basis_exponent = basis_exponent;
  op.coefficient_exponent = coefficient_exponent;
  op.basis = scaled(c.basis, basis_exponent);
  op.coefficients = scaled(weighted, coefficient_exponent);
  for (int32_t v : op.coefficients)
    if (v > kCpcaMaxCoefficient || v < -kCpcaMaxCoefficient)
      throw Error(ErrorKind::kInput, "", kNoPlane, kNoOffset, "a motion too large for the fixed point of cpca-wpt: use fewer --bits");
  return op;
}

// A cluster's start at the noise step Δ: the translation t is the
// coefficient of the basis (1, …, 1) of norm √M, so it takes steps of about
// Δ / √M (as fine as its range, 2^29, allows, and no finer than 2^−F grid
// units: the shift never rounds, so that a start can be undone exactly).
Operator quantize_start(const Translation& t, uint32_t cluster, size_t members, int noise, int fraction_bits) {
  const int wanted = std::min(half_of(2 * std::ilogb(std::sqrt(static_cast<double>(members))) - noise), exponent_for(t.cwiseAbs().maxCoeff(), 29));
  const int shift = std::clamp(wanted - fraction_bits, -static_cast<int>(kCpcaShiftBias), 0);
  Operator op;
  op.cluster = cluster;
  op.kind = kCpcaStart;
  op.shift = static_cast<uint32_t>(shift + static_cast<int>(kCpcaShiftBias));
  op.coefficient_exponent = 2 * (shift + fraction_bits);
  op.translation = scaled(t, op.coefficient_exponent);
  for (int32_t v : op.translation)
    if (v > kCpcaMaxTranslation || v < -kCpcaMaxTranslation)
      throw Error(ErrorKind::kInput, "", kNoPlane, kNoOffset, "a motion too large for the fixed point of cpca-wpt: use fewer --bits");
  return op;
}

// The squared error a start removes, estimated: M (‖t‖² − ‖t̂ − t‖²).
double estimated_gain(const Translation& t, size_t members, const Operator& op) {
  double removed = 0;
  for (Eigen::Index j = 0; j < t.size(); ++j) {
    const double q = op.translation[static_cast<size_t>(j)] / power_of_two(op.coefficient_exponent);
    removed += t(j) * t(j) - (q - t(j)) * (q - t(j));
  }
  return static_cast<double>(members) * removed;
}

// The squared error removed by an operator, estimated without decoding:
// sigma² less the quantization error ‖b̂ŵᵀ − σbwᵀ‖² (from its inner
// products, b unit).
double estimated_gain(const Component& c, const Operator& op) {
  double bb = 0, bq = 0, ww = 0, wq = 0;
  for (Eigen::Index j = 0; j < c.basis.size(); ++j) {
    const double b = op.basis[static_cast<size_t>(j)] / power_of_two(op.basis_exponent);
    bb += b * b;
    bq += b * c.basis(j);
  }
  for (Eigen::Index n = 0; n < c.coefficients.size(); ++n) {
    const double w = op.coefficients[static_cast<size_t>(n)] / power_of_two(op.coefficient_exponent);
    ww += w * w;
    wq += w * c.sigma * c.coefficients(n);
  }
  const double noise = bb * ww - 2 * bq * wq + c.sigma * c.sigma;
  return c.sigma * c.sigma - noise;
}

// A refinement unit's data.
template <class SymbolIO>
void write_refinement(syntax::WriteIO& io, SymbolIO& symbols, Operator& op, const CpcaMeshPrediction& mesh) {
  if (op.kind == kCpcaStart)
    syntax::describe_start(symbols, op.translation);
  else if (op.kind == kCpcaMeshComponent)
    mesh.describe_operator<3>(symbols, op.cluster, op.basis, op.coefficients);
  else if (op.kind == kCpcaTrajectory)
    mesh.describe_operator<1>(symbols, op.cluster, op.basis, op.coefficients);
  else
    syntax::describe_operator(symbols, op.basis, op.coefficients);
  const std::vector<uint8_t> bins = symbols.finish_bins(), raw = symbols.finish_raw();
  CpcaRefinement r{op.cluster, op.kind, op.shift, static_cast<uint32_t>(bins.size()), bins, raw};
  syntax::describe(io, r);
  if (io.trace()) io.trace()->stream() << symbols.trace_text();
}

void write_refinement(syntax::WriteIO& io, Operator& op, const CpcaMeshPrediction& mesh) {
  const syntax::SectionPlace place{"bins", "raw", 0, 0, io.plane()};
  if (io.trace()) {
    syntax::EntropyWriteIO<true> symbols(place, io.trace());
    write_refinement(io, symbols, op, mesh);
  } else {
    syntax::EntropyWriteIO<false> symbols(place);
    write_refinement(io, symbols, op, mesh);
  }
}

// The operators of one noise step, their order and how many are sent.
struct Plan {
  int noise = 0;  // log2 Δ in half steps
  std::vector<Operator> operators;
  std::vector<size_t> order;  // indices into operators, in stream order
  size_t sent = 0;
  double estimated_kg = 0;  // of the prefix sent, from the gains
  uint64_t bytes = 0;       // of the prefix sent
};

class CpcaEncoder final : public CodecEncoder3d {
 public:
  // coding_order: the base mesh's vertices in coding order.
  CpcaEncoder(const MeshSequence& s, const CodecSettings& settings, int bits, const Clustering& clustering, bool trajectories,
              std::span<const uint32_t> coding_order)
      : max_bytes_(static_cast<uint64_t>(settings.number("max-bytes"))),
        target_kg_(settings.number("target-kg")),
        round_robin_(settings.text("order") == "rpt"),
        basis_prediction_(settings.text("basis")),
        trajectories_(trajectories) {
    if (settings.text("order") != "wpt" && settings.text("order") != "rpt") throw usage_error("--order is wpt or rpt (cpca-wpt)");
    if (basis_prediction_ != "index" && basis_prediction_ != "mesh" && basis_prediction_ != "auto")
      throw usage_error("--basis is index, mesh or auto (cpca-wpt)");
    components_ = settings.text("components") == "auto" ? (max_bytes_ > 0 || target_kg_ > 0 ? kMaxComponents : kPaperComponents)
                                                         : parse_count(settings.text("components"), "--components", kMaxComponents);
    if (settings.text("noise") != "auto") {
      size_t used = 0;
      double value = NAN;
      try {
        value = std::stod(settings.text("noise"), &used);
      } catch (const std::exception&) {
      }
      if (used != settings.text("noise").size() || !(2 * value >= kMinNoise && 2 * value <= kMaxNoise) || 2 * value != std::floor(2 * value))
        throw usage_error("--noise is auto or a multiple of 0.5 in " + std::to_string(kMinNoise / 2) + " … " + std::to_string(kMaxNoise / 2) +
                          " (cpca-wpt)");
      noise_ = static_cast<int>(2 * value);
    }
    if (uint64_t{s.vertex_count} * s.frames.size() > kCpcaMaxVertexFrames)
      throw usage_error("cpca-wpt takes at most 2^22 vertex-frames (vertices × frames)");
    std::vector<Vec3> mean(s.vertex_count);
    for (const std::vector<Vec3>& frame : s.frames)
      for (size_t v = 0; v < s.vertex_count; ++v) mean[v] = {mean[v].x + frame[v].x, mean[v].y + frame[v].y, mean[v].z + frame[v].z};
    const double n = static_cast<double>(s.frames.size());
    for (Vec3& p : mean) p = {p.x / n, p.y / n, p.z / n};
    grid_ = Grid::over(mean, bits, true);
    header_.bits = static_cast<uint32_t>(bits);
    for (int axis = 0; axis < 3; ++axis) {
      header_.origin[axis] = bit_cast<uint32_t>(grid_.origin[axis]);
      header_.step[axis] = bit_cast<uint32_t>(grid_.step[axis]);
    }
    header_.fraction_bits = static_cast<uint32_t>(std::clamp(24 - bits, 0, 8));
    mean_.resize(s.vertex_count);
    for (size_t v = 0; v < s.vertex_count; ++v)
      if (!grid_.quantize(mean[v], mean_[v]))
        throw Error(ErrorKind::kInput, "", kNoPlane, kNoOffset, "the mean of vertex " + std::to_string(v) + " lies outside the grid");
    requested_clusters_ = clustering.requested;
    kmeans_seconds_ = clustering.seconds;
    prepare(s, clustering.cluster_of, coding_order);
  }

  void write_header(syntax::WriteIO& io) override {
    header_.map_bins = map_bins_;
    header_.map_raw = map_raw_;
    syntax::describe(io, header_);
    if (io.trace()) io.trace()->stream() << write_cluster_map(io.trace());
  }

  // The base mesh, then the plan's operators while the stream through the
  // last refinement stays within --max-bytes, then the frames' hashes.
  void encode(const MeshSequence& s, UnitSink& sink) override {
    sink.unit(UnitType::kBaseMesh, 0, [&](syntax::WriteIO& io) { write_base_mesh(io, s.faces, mean_); });
    if (max_bytes_ > 0 && sink.stream_bytes() > max_bytes_)
      throw usage_error("--max-bytes " + std::to_string(max_bytes_) + " is below the " + std::to_string(sink.stream_bytes()) +
                        " bytes of the header and the base mesh (cpca-wpt)");
    CpcaAnimation animation(header_, mean_, static_cast<uint32_t>(s.frames.size()));
    size_t sent = 0;
    for (; sent < plan_.sent; ++sent) {
      Operator& op = plan_.operators[plan_.order[sent]];
      if (max_bytes_ > 0 && sink.stream_bytes() + op.bytes > max_bytes_) break;
      sink.unit(UnitType::kRefinement, 0, [&](syntax::WriteIO& io) { write_refinement(io, op, *mesh_); });
      apply(animation, members_[op.cluster], op);
      sink.progress(sent + 1, plan_.sent);
    }
    plan_.sent = sent;
    kg_ = kg_of_prefix(s, sent);
    if (target_kg_ > 0 && kg_ > target_kg_)
      throw usage_error("--target-kg " + std::to_string(target_kg_) + " is out of reach within --max-bytes (cpca-wpt)");
    for (uint32_t f = 0; f < s.frames.size(); ++f) sink.decoded(f, animation.frame(f));
  }

  // The bytes of the stream planned (estimated: every unit's size, and the
  // fixed part).
  uint64_t planned_bytes() const { return plan_.bytes; }
  int clusters() const { return requested_clusters_; }
  int bits() const { return static_cast<int>(header_.bits); }
  bool trajectory_model() const { return trajectories_; }

  std::vector<CodecStatistic> statistics() const override {
    return {{"clusters", header_.cluster_count},
            {"trajectory model", trajectories_ ? 1.0 : 0.0},
            {"noise step log2", plan_.noise / 2.0},
            {"operators sent", static_cast<double>(plan_.sent)},
            {"operators computed", static_cast<double>(plan_.operators.size())},
            {"KG error", kg_},
            {"k-means seconds", kmeans_seconds_},
            {"SVD seconds", svd_seconds_},
            {"order seconds", order_seconds_}};
  }

 private:
  // Clusters, components, then the plan of the noise step given, or of the
  // best one for --max-bytes (the smallest KG error within it) or
  // --target-kg (the fewest bytes that reach it), else of the default.
  void prepare(const MeshSequence& s, const std::vector<uint32_t>& cluster_of, std::span<const uint32_t> coding_order) {
    cluster_of_ = cluster_of;
    header_.cluster_count = *std::max_element(cluster_of_.begin(), cluster_of_.end()) + 1;
    members_ = cpca_members(cluster_of_, header_.cluster_count);
    mesh_.emplace(s.faces, coding_order, cluster_of_, header_.cluster_count);
    write_cluster_map();
    auto start = std::chrono::steady_clock::now();
    for (uint32_t c = 0; c < header_.cluster_count; ++c) {
      Eigen::MatrixXd d = motion(s, c);
      translations_.push_back(translation_of(d));
      for (Eigen::Index row = 0; row < d.rows(); ++row) d.row(row) -= translations_[c](Eigen::seqN(row % 3, d.cols(), 3)).transpose();
      components_of_.push_back(principal_components(trajectories_ ? as_trajectories(d) : d, components_));
    }
    svd_seconds_ = seconds_since(start);
    start = std::chrono::steady_clock::now();
    const CpcaAnimation mean_only(header_, mean_, static_cast<uint32_t>(s.frames.size()));
    for (uint32_t c = 0; c < header_.cluster_count; ++c) mean_error_.push_back(squared_error(s, mean_only, c));
    spread_ = squared_spread(s);
    fixed_bytes_ = fixed_bytes(s);
    int q = noise_.value_or(kDefaultNoise);
    if (!noise_ && (max_bytes_ > 0 || target_kg_ > 0)) {
      // From the default, towards the better neighbour while it improves
      // (plans from estimated gains), in whole steps, then a half step
      // either side.
      Plan best = plan_for(s, q, false);
      for (const int direction : {2, -2}) {
        for (int next = q + direction; next >= kMinNoise && next <= kMaxNoise; next += direction) {
          Plan plan = plan_for(s, next, false);
          if (!better(plan, best)) break;
          best = std::move(plan);
        }
        if (best.noise != q) break;
      }
      q = best.noise;
      for (const int next : {q - 1, q + 1}) {
        if (next < kMinNoise || next > kMaxNoise) continue;
        Plan plan = plan_for(s, next, false);
        if (better(plan, best)) best = std::move(plan);
      }
      q = best.noise;
    }
    plan_ = plan_for(s, q, true);
    if (target_kg_ > 0) reach_target(s);
    order_seconds_ = seconds_since(start);
  }

  // Every cluster's operators at noise step 2^(q / 2), each kept while it removes
  // error from the decoder's output (exactly, or estimated); their order;
  // the prefix sent.
  Plan plan_for(const MeshSequence& s, int q, bool exact) const {
    Plan plan;
    plan.noise = q;
    std::optional<CpcaAnimation> animation;
    if (exact) animation.emplace(header_, mean_, static_cast<uint32_t>(s.frames.size()));
    std::vector<std::vector<size_t>> per_cluster(header_.cluster_count);
    for (uint32_t c = 0; c < header_.cluster_count; ++c) {
      // The start, then the components while each removes error; a start
      // that would add error moves nothing (all zeros); a cluster whose
      // start and first component remove none is left as it is.
      const size_t members = members_[c].size();
      double error = mean_error_[c];
      std::vector<Operator> sequence;
      auto measure = [&](Operator& op, double estimate) {
        if (animation) {
          apply(*animation, members_[c], op);
          const double after = squared_error(s, *animation, c);
          op.gain = error - after;
          error = after;
        } else {
          op.gain = estimate;
        }
      };
      Operator start = quantize_start(translations_[c], c, members, q, static_cast<int>(header_.fraction_bits));
      if (!(estimated_gain(translations_[c], members, start) > 0)) std::fill(start.translation.begin(), start.translation.end(), 0);
      measure(start, estimated_gain(translations_[c], members, start));
      if (start.gain < 0) {  // the output's rounding: undo (exactly: no shift rounds), and move nothing
        if (animation) {
          for (int32_t& v : start.translation) v = -v;
          apply(*animation, members_[c], start);
          error = squared_error(s, *animation, c);
        }
        std::fill(start.translation.begin(), start.translation.end(), 0);
        start.gain = 0;
      }
      sequence.push_back(std::move(start));
      for (const Component& component : components_of_[c]) {
        Operator op = quantize(component, c, q, static_cast<int>(header_.fraction_bits), trajectories_ ? kTrajectoryBasisFiner : 0);
        if (trajectories_) op.kind = kCpcaTrajectory;
        measure(op, estimated_gain(component, op));
        if (!(op.gain > 0)) break;  // quantization ate the component: the later ones are smaller still
        sequence.push_back(std::move(op));
      }
      if (sequence.size() == 1 && !(sequence[0].gain > 0)) continue;
      for (Operator& op : sequence) {
        if (op.kind != kCpcaComponent)
          op.bytes = unit_bytes(op);
        else
          choose_kind(op);
        per_cluster[c].push_back(plan.operators.size());
        plan.operators.push_back(std::move(op));
      }
    }
    plan.order = round_robin_ ? round_robin(per_cluster) : by_weight(plan.operators, per_cluster);
    double error = 0;
    for (double e : mean_error_) error += e;
    plan.bytes = fixed_bytes_;
    for (size_t i = 0; i < plan.order.size(); ++i) {
      const Operator& op = plan.operators[plan.order[i]];
      if (max_bytes_ > 0 && plan.bytes + op.bytes > max_bytes_) break;
      if (target_kg_ > 0 && kg_of(error) <= target_kg_) break;
      plan.bytes += op.bytes;
      error -= op.gain;
      ++plan.sent;
    }
    plan.estimated_kg = kg_of(error);
    return plan;
  }

  // With --target-kg: reaching it, then fewer bytes (else the smaller
  // error); otherwise the smaller error.
  bool better(const Plan& a, const Plan& b) const {
    if (target_kg_ > 0) {
      const bool a_reaches = a.estimated_kg <= target_kg_, b_reaches = b.estimated_kg <= target_kg_;
      if (a_reaches != b_reaches) return a_reaches;
      if (a_reaches) return a.bytes < b.bytes;
    }
    return a.estimated_kg < b.estimated_kg;
  }

  double kg_of(double squared_error) const { return spread_ > 0 ? 100 * std::sqrt(std::max(squared_error, 0.0) / spread_) : 0; }

  // The exact KG of the plan's prefix, one more operator while above the
  // target (the estimate's sums differ in rounding).
  void reach_target(const MeshSequence& s) {
    while (kg_of_prefix(s, plan_.sent) > target_kg_) {
      if (plan_.sent == plan_.order.size() || (max_bytes_ > 0 && plan_.bytes + plan_.operators[plan_.order[plan_.sent]].bytes > max_bytes_))
        throw usage_error("--target-kg " + std::to_string(target_kg_) +
                          " is out of reach (cpca-wpt: raise --components, --max-bytes or lower --noise)");
      plan_.bytes += plan_.operators[plan_.order[plan_.sent++]].bytes;
    }
  }

  // The mean of a motion matrix's rows per axis, per frame: index 3n + axis.
  static Translation translation_of(const Eigen::MatrixXd& d) {
    Translation t = Translation::Zero(3 * d.cols());
    for (Eigen::Index row = 0; row < d.rows(); ++row) t(Eigen::seqN(row % 3, d.cols(), 3)) += d.row(row).transpose();
    return t / static_cast<double>(d.rows() / 3);
  }

  // Cluster c's motion about the decoded mean shape, in grid units: row
  // 3i + axis for its i-th vertex, column n for frame n.
  Eigen::MatrixXd motion(const MeshSequence& s, uint32_t c) const {
    const std::vector<NodeIndex>& members = members_[c];
    Eigen::MatrixXd d(3 * static_cast<Eigen::Index>(members.size()), static_cast<Eigen::Index>(s.frames.size()));
    for (size_t f = 0; f < s.frames.size(); ++f)
      for (size_t i = 0; i < members.size(); ++i) {
        const Vec3& p = s.frames[f][members[i]];
        const double value[3] = {p.x, p.y, p.z};
        for (int axis = 0; axis < 3; ++axis)
          d(static_cast<Eigen::Index>(3 * i) + axis, static_cast<Eigen::Index>(f)) =
              (value[axis] - static_cast<double>(grid_.origin[axis])) / static_cast<double>(grid_.step[axis]) - mean_[members[i]][axis];
      }
    return d;
  }

  // Cluster c's squared error in grid units, as the decoder outputs it.
  double squared_error(const MeshSequence& s, const CpcaAnimation& animation, uint32_t c) const {
    double sum = 0;
    const double unit = static_cast<double>(grid_.step[0]);
    for (uint32_t f = 0; f < s.frames.size(); ++f) {
      const std::span<const Float3> decoded = animation.frame(f);
      for (NodeIndex v : members_[c]) {
        const Vec3& p = s.frames[f][v];
        const double dx = (p.x - decoded[v][0]) / unit, dy = (p.y - decoded[v][1]) / unit, dz = (p.z - decoded[v][2]) / unit;
        sum += dx * dx + dy * dy + dz * dz;
      }
    }
    return sum;
  }

  // Σ over frames of the squared distances to the frame's centroid, in
  // grid units² (the KG error's denominator).
  double squared_spread(const MeshSequence& s) const {
    const double unit = static_cast<double>(grid_.step[0]);
    double sum = 0;
    for (const std::vector<Vec3>& frame : s.frames) {
      Vec3 c;
      for (const Vec3& p : frame) c = {c.x + p.x, c.y + p.y, c.z + p.z};
      const double n = static_cast<double>(frame.size());
      c = {c.x / n, c.y / n, c.z / n};
      for (const Vec3& p : frame) {
        const double dx = (p.x - c.x) / unit, dy = (p.y - c.y) / unit, dz = (p.z - c.z) / unit;
        sum += dx * dx + dy * dy + dz * dz;
      }
    }
    return sum;
  }

  // The cluster map's sections, and their trace in the place of `like`
  // when given (printed after the header's fields).
  std::string write_cluster_map(Trace* like = nullptr) {
    std::vector<uint32_t> map = cluster_of_;
    const syntax::SectionPlace place{"cluster_map_bins", "cluster_map_raw", 0, 0, kNoPlane};
    std::string text;
    if (like) {
      syntax::EntropyWriteIO<true> symbols(place, like);
      syntax::describe_cluster_map(symbols, map, header_.cluster_count);
      text = symbols.trace_text();
    } else {
      syntax::EntropyWriteIO<false> symbols(place);
      syntax::describe_cluster_map(symbols, map, header_.cluster_count);
      map_bins_ = symbols.finish_bins();
      map_raw_ = symbols.finish_raw();
      header_.map_bins_bytes = static_cast<uint32_t>(map_bins_.size());
      header_.map_raw_bytes = static_cast<uint32_t>(map_raw_.size());
    }
    return text;
  }

  // The bytes of an operator's unit in the stream.
  uint64_t unit_bytes(Operator& op) const {
    BitWriter writer;
    syntax::WriteIO io(writer);
    UnitHeader header{static_cast<uint32_t>(UnitType::kRefinement), 0};
    syntax::describe(io, header);
    write_refinement(io, op, *mesh_);
    return ContainerWriter::unit_size(writer.bytes());
  }

  // A component's unit in the kind --basis asks for, or the smaller.
  void choose_kind(Operator& op) const {
    op.kind = basis_prediction_ == "index" ? kCpcaComponent : kCpcaMeshComponent;
    op.bytes = unit_bytes(op);
    if (basis_prediction_ != "auto") return;
    Operator by_index = op;
    by_index.kind = kCpcaComponent;
    by_index.bytes = unit_bytes(by_index);
    if (by_index.bytes < op.bytes) op = std::move(by_index);
  }

  // The bytes before the first refinement unit: the object (its frame rate
  // assumed 25/1, which may change the escaping by a byte) and the base mesh.
  uint64_t fixed_bytes(const MeshSequence& s) {
    BitWriter object, base;
    syntax::WriteIO object_io(object), base_io(base);
    ObjectHeader header{1, 4, s.vertex_count, static_cast<uint32_t>(s.faces.size()), static_cast<uint32_t>(s.frames.size()), 25, 1};
    syntax::describe(object_io, header);
    write_header(object_io);
    UnitHeader unit{static_cast<uint32_t>(UnitType::kBaseMesh), 0};
    syntax::describe(base_io, unit);
    write_base_mesh(base_io, s.faces, mean_);
    return ContainerWriter::unit_size(object.bytes()) + ContainerWriter::unit_size(base.bytes());
  }

  // RPT: round r sends every cluster's r-th operator, in cluster order.
  static std::vector<size_t> round_robin(const std::vector<std::vector<size_t>>& per_cluster) {
    std::vector<size_t> order;
    for (size_t round = 0;; ++round) {
      const size_t before = order.size();
      for (const std::vector<size_t>& ops : per_cluster)
        if (round < ops.size()) order.push_back(ops[round]);
      if (order.size() == before) return order;
    }
  }

  // WPT: the next unit of the cluster whose next units remove the most
  // error per bit, W = Σ gain / Σ bits over the best run of them (so that
  // a cheap start with little gain counts with the components it opens;
  // ties: the lowest cluster).
  static std::vector<size_t> by_weight(const std::vector<Operator>& operators, const std::vector<std::vector<size_t>>& per_cluster) {
    std::vector<size_t> order, next(per_cluster.size(), 0);
    for (;;) {
      size_t best = SIZE_MAX;
      double best_weight = 0;
      for (size_t c = 0; c < per_cluster.size(); ++c) {
        double gain = 0, bits = 0, weight = -INFINITY;
        for (size_t j = next[c]; j < per_cluster[c].size(); ++j) {
          gain += operators[per_cluster[c][j]].gain;
          bits += 8.0 * static_cast<double>(operators[per_cluster[c][j]].bytes);
          weight = std::max(weight, gain / bits);
        }
        if (next[c] < per_cluster[c].size() && (best == SIZE_MAX || weight > best_weight)) {
          best = c;
          best_weight = weight;
        }
      }
      if (best == SIZE_MAX) return order;
      order.push_back(per_cluster[best][next[best]++]);
    }
  }

  // The KG error of the decoder's output after the plan's first `count`
  // operators, as `m4mesh metrics` measures it.
  double kg_of_prefix(const MeshSequence& s, size_t count) const {
    CpcaAnimation animation(header_, mean_, static_cast<uint32_t>(s.frames.size()));
    for (size_t i = 0; i < count; ++i) {
      const Operator& op = plan_.operators[plan_.order[i]];
      apply(animation, members_[op.cluster], op);
    }
    MeshSequence decoded;
    decoded.vertex_count = s.vertex_count;
    decoded.faces = s.faces;
    for (uint32_t f = 0; f < s.frames.size(); ++f) {
      std::vector<Vec3> frame;
      for (const Float3& p : animation.frame(f)) frame.push_back({p[0], p[1], p[2]});
      decoded.frames.push_back(std::move(frame));
    }
    return kg_error(s, decoded);
  }

  size_t components_ = 0;
  int requested_clusters_ = 0;
  uint64_t max_bytes_;
  double target_kg_;
  bool round_robin_;
  std::string basis_prediction_;  // --basis: index, mesh or auto
  bool trajectories_;  // components of the members' trajectories (unit_kind 3), else of their shapes
  std::optional<int> noise_;  // log2 of the noise step in half steps; none: auto
  Grid grid_;
  CpcaHeader header_;
  std::vector<IntPoint3> mean_;
  std::vector<uint32_t> cluster_of_;
  std::vector<std::vector<NodeIndex>> members_;
  std::optional<CpcaMeshPrediction> mesh_;
  std::vector<uint8_t> map_bins_, map_raw_;
  std::vector<Translation> translations_;
  std::vector<std::vector<Component>> components_of_;
  std::vector<double> mean_error_;  // per cluster, of the mean shape alone
  double spread_ = 0;
  uint64_t fixed_bytes_ = 0;
  Plan plan_;
  double kg_ = 0, kmeans_seconds_ = 0, svd_seconds_ = 0, order_seconds_ = 0;
};

}  // namespace

std::vector<CodecOption> cpca_wpt_options() {
  return {{"bits", "cpca-wpt: quantization bits of the mean shape (the base mesh), 4 … 24, or auto (12; with --target-kg, from 12 "
                   "towards the neighbour whose planned stream is smaller while it shrinks)",
           OptionKind::kText, "auto", 0, 0},
          {"clusters", "cpca-wpt: k, the clusters of k-means on the vertices' trajectories, 1 … 255, or auto (10, the paper's; with "
                       "--target-kg the one of 5, 10, 20 and 40 whose planned stream is smallest, then 0.7 and 1.4 times it if smaller)",
           OptionKind::kText, "auto", 0, 0},
          {"components", "cpca-wpt: at most this many principal components per cluster, 1 … 4096, or auto (40, the paper's, or every "
                         "one for --max-bytes or --target-kg)",
           OptionKind::kText, "auto", 0, 0},
          {"noise", "cpca-wpt: log2 of the quantization step of the coded values in grid units, −4 … 12 in steps of 0.5, or auto (4, "
                    "or the best for --max-bytes or --target-kg)",
           OptionKind::kText, "auto", 0, 0},
          {"basis", "cpca-wpt: how a component's basis values are predicted: index (from the member before in index order, the "
                    "paper's), mesh (by the base mesh's parallelograms, along its traversal) or auto (per component the smaller unit)",
           OptionKind::kText, "auto", 0, 0},
          {"model", "cpca-wpt: the components' space: shape (3 basis values per vertex, 1 coefficient per frame: the paper's), "
                    "trajectory (1 value per vertex, 3 per frame, predicted over the base mesh) or auto (trajectory; with --target-kg the "
                    "one whose planned stream is smallest)",
           OptionKind::kText, "auto", 0, 0},
          {"order", "cpca-wpt: wpt (by squared error removed per bit) or rpt (round robin over the clusters)", OptionKind::kText, "wpt", 0, 0},
          {"max-bytes", "cpca-wpt: the stream's size at most (0: every operator)", OptionKind::kNumber, "0", 0, 1e15},
          {"target-kg", "cpca-wpt: stop at the first operator whose decoded KG error is at most this (0: off)", OptionKind::kNumber, "0", 0,
           100}};
}

std::unique_ptr<CodecEncoder3d> make_cpca_wpt_encoder(const MeshSequence& sequence, const CodecSettings& settings) {
  const std::string& model = settings.text("model");
  if (model != "shape" && model != "trajectory" && model != "auto") throw usage_error("--model is shape, trajectory or auto (cpca-wpt)");
  const bool target = settings.number("target-kg") > 0;
  const bool bits_auto = settings.text("bits") == "auto";
  const int bits = bits_auto ? kDefaultBits : static_cast<int>(parse_count(settings.text("bits"), "--bits", kMaxBits, kMinBits));
  const std::vector<int> cluster_counts =
      settings.text("clusters") != "auto" ? std::vector<int>{static_cast<int>(parse_count(settings.text("clusters"), "--clusters", kCpcaMaxClusters))}
      : target                            ? std::vector<int>{5, 10, 20, 40}
                                          : std::vector<int>{kPaperClusters};
  const std::vector<bool> trajectory_models = model == "shape" ? std::vector<bool>{false}
                                              : model == "trajectory" || !target ? std::vector<bool>{true}
                                                                                  : std::vector<bool>{true, false};
  // The vertices in the base mesh's coding order, once for every candidate.
  const std::vector<uint32_t> coding_order = plan_base_mesh(sequence.faces, sequence.vertex_count, false).input_of;
  if (cluster_counts.size() == 1 && trajectory_models.size() == 1 && !(bits_auto && target))
    return std::make_unique<CpcaEncoder>(sequence, settings, bits, clustering(sequence, cluster_counts[0]), trajectory_models[0], coding_order);
  // The cluster count and model whose plan reaches the target in the fewest
  // bytes, then the counts √2 either side of it, then the mean shape's bits
  // from 12 towards the smaller plan. Candidates run side by side; the
  // first of the smallest is kept, whatever the threads.
  struct Candidate {
    int bits, clusters;
    bool trajectories;
  };
  std::unique_ptr<CpcaEncoder> best;
  std::optional<Error> missed;
  std::map<int, Clustering> clusterings;  // k-means once per count, side by side
  auto cluster_all = [&](const std::vector<Candidate>& candidates) {
    std::vector<int> counts;
    for (const Candidate& c : candidates)
      if (!clusterings.contains(c.clusters) && std::find(counts.begin(), counts.end(), c.clusters) == counts.end()) counts.push_back(c.clusters);
    std::vector<Clustering> computed(counts.size());
    parallel_for(counts.size(), settings.threads(), [&](size_t i) { computed[i] = clustering(sequence, counts[i]); });
    for (size_t i = 0; i < counts.size(); ++i) clusterings[counts[i]] = std::move(computed[i]);
  };
  // Whether one of `candidates` beat the best so far (that one is kept).
  auto try_all = [&](const std::vector<Candidate>& candidates) {
    cluster_all(candidates);
    std::vector<std::unique_ptr<CpcaEncoder>> built(candidates.size());
    std::vector<std::optional<Error>> failed(candidates.size());
    bool improved = false;
    parallel_for(
        candidates.size(), settings.threads(),
        [&](size_t i) {
          try {
            built[i] = std::make_unique<CpcaEncoder>(sequence, settings, candidates[i].bits, clusterings.at(candidates[i].clusters),
                                                     candidates[i].trajectories, coding_order);
          } catch (const Error& e) {
            if (e.kind() != ErrorKind::kUsage) throw;
            failed[i] = e;
          }
        },
        [&](size_t i) {
          if (failed[i]) missed = failed[i];
          if (built[i] && (!best || built[i]->planned_bytes() < best->planned_bytes())) {
            best = std::move(built[i]);
            improved = true;
          }
          built[i].reset();
        });
    return improved;
  };
  std::vector<Candidate> first;
  for (const int clusters : cluster_counts)
    for (const bool trajectories : trajectory_models) first.push_back({bits, clusters, trajectories});
  try_all(first);
  if (!best) throw *missed;
  const int chosen = best->clusters();
  const bool trajectories = best->trajectory_model();
  if (cluster_counts.size() > 1)
    try_all({{bits, chosen * 7 / 10, trajectories}, {bits, chosen * 14 / 10, trajectories}});
  if (bits_auto) {
    const int clusters = best->clusters();
    const uint64_t before = best->planned_bytes();
    try_all({{bits - 1, clusters, trajectories}, {bits + 1, clusters, trajectories}});
    if (best->planned_bytes() < before) {
      const int direction = best->bits() < bits ? -1 : 1;
      for (int b = bits + 2 * direction; b >= kMinBits && b <= kMaxBits && try_all({{b, clusters, trajectories}}); b += direction) {
      }
    }
  }
  return best;
}

}  // namespace m4mesh
