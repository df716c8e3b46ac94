// The clustered-PCA codec (codec_id 4) encoding (docs/codec_cpca_wpt.md):
// k-means on the vertices' trajectories, per cluster the principal
// components of its motion about the mean shape, each quantized into one
// refinement operator, and the operators sent in decreasing weight (WPT:
// squared error removed per bit) or round robin over the clusters (RPT).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <map>
#include <mutex>
#include <utility>
#include <optional>

#include "codecs3d/codec_encoder.h"
#include "common/bit_cast.h"
#include "common/error.h"
#include "common/parallel.h"
#include "encoder/mesh3d/base_mesh.h"
#include "encoder/mesh3d/codec_options.h"
#include "encoder/mesh3d/cpca_wpt_analysis.h"
#include "encoder/mesh3d/cpca_wpt_operators.h"
#include "encoder/mesh3d/cpca_wpt_options.h"
#include "encoder/mesh3d/cpca_wpt_plan.h"
#include "encoder/mesh3d/quality_target.h"
#include "mesh3d/cpca_wpt.h"
#include "mesh3d/metrics.h"
#include "mesh3d/quantization.h"
#include "syntax/mesh3d/cpca_wpt.h"
#include "syntax/mesh3d/entropy_io.h"

namespace m4mesh {

namespace {

using namespace cpca_wpt;

// Trajectory components take their basis this many half steps (√2 each)
// finer than the equal-error rule: measured, 1 to 2 % fewer bytes at the
// same KG on the cow and the horse (the basis is predicted over the mesh,
// the coefficients are not).
constexpr int kTrajectoryBasisFiner = 1;
// Components are computed every one for Gram matrices up to this size,
// else the leading kFirstComponents at first, twice as many each time a
// plan uses them up (an eigen-decomposition costs the size cubed).
constexpr size_t kAllComponentsSize = 192, kFirstComponents = 24;
// A trajectory basis value's residual rounds to the one nearer 0 unless its
// fraction reaches 0.55: the smaller residual saves more bits than its
// error costs (FAMC and tune clips, docs/rate_distortion.md).
constexpr double kTrajectoryBasisRounding = 0.45;

// The bytes of a refinement unit an operator in a group does not pay: the
// start code, the unit header, the refinement fields less its entry in the
// group's list (about a byte), and the arithmetic coder's flush (about 4
// bytes).
constexpr uint64_t kSharedInGroup = 4 + 5 + 7 - 1 + 4;

// Frames first … first + count − 1 of a source, in memory (no faces).
MeshSequence frames_of(const FrameSource& source, uint32_t first, uint32_t count) {
  MeshSequence s;
  s.vertex_count = source.vertex_count();
  s.frames.resize(count);
  for (uint32_t f = 0; f < count; ++f) {
    s.frames[f].resize(s.vertex_count);
    source.read(first + f, s.frames[f]);
  }
  return s;
}

// The frames of a segment: --segment-frames, or every frame when the
// sequence holds at most kCpcaMaxVertexFrames vertex-frames, else as many
// as that holds.
uint32_t segment_length(const Options& options, uint32_t vertex_count, uint32_t frame_count) {
  const uint32_t most = static_cast<uint32_t>(std::max<uint64_t>(1, kCpcaMaxVertexFrames / vertex_count));
  if (options.segment_frames) {
    if (*options.segment_frames > most)
      throw usage_error("--segment-frames " + std::to_string(*options.segment_frames) + ": a segment holds at most 2^22 vertex-frames, " +
                        std::to_string(most) + " frames of " + std::to_string(vertex_count) + " vertices");
    return std::min(*options.segment_frames, frame_count);
  }
  return std::min(most, frame_count);
}

// The bytes and the positions' blend of a base mesh unit.
struct BaseMeshUnit {
  uint64_t bytes = 0;
  uint32_t position_blend = 0;
};

// The bytes of the base mesh unit per mean shape bits (half bits), found
// once for a search's candidates, side by side.
class BaseMeshSizes {
 public:
  BaseMeshUnit of(int half_bits, const std::function<BaseMeshUnit()>& unit) {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      if (auto it = units_.find(half_bits); it != units_.end()) return it->second;
    }
    const BaseMeshUnit written = unit();
    const std::lock_guard<std::mutex> lock(mutex_);
    return units_.emplace(half_bits, written).first->second;
  }

 private:
  std::mutex mutex_;
  std::map<int, BaseMeshUnit> units_;
};

// A component a segment sent, which the next one may continue: its basis
// as coded, and its coefficients' last values.
struct ListedBasis {
  std::vector<int32_t> basis;
  int exponent = 0;  // the basis is the real one × 2^(exponent / 2)
  CpcaCarried coefficients;
};

class CpcaEncoder final : public CodecEncoder3d {
 public:
  // `first`: the first segment's frames, with the faces; the stream has
  // `frame_count` frames in segments of `segment_frames`. coding_order:
  // the base mesh's vertices in coding order. The mean shape (of the first
  // segment) has a grid of 2^(half_bits / 2) − 1 steps.
  CpcaEncoder(const MeshSequence& first, uint32_t frame_count, uint32_t segment_frames, const Options& options, int half_bits,
              const Clustering& clustering, bool trajectories, std::span<const uint32_t> coding_order, BaseMeshSizes* base_mesh_sizes = nullptr)
      : components_(options.components),
        max_bytes_(options.max_bytes),
        group_bytes_(options.group_bytes),
        group_growth_(options.group_growth),
        target_kg_(options.target_kg),
        round_robin_(options.round_robin),
        basis_prediction_(options.basis),
        trajectories_(trajectories),
        noise_(options.noise),
        base_mesh_(options.base_mesh),
        threads_(options.threads),
        frame_count_(frame_count) {
    const MeshSequence& s = first;
    std::vector<Vec3> mean(s.vertex_count);
    for (const std::vector<Vec3>& frame : s.frames)
      for (size_t v = 0; v < s.vertex_count; ++v) mean[v] = {mean[v].x + frame[v].x, mean[v].y + frame[v].y, mean[v].z + frame[v].z};
    const double n = static_cast<double>(s.frames.size());
    for (Vec3& p : mean) p = {p.x / n, p.y / n, p.z / n};
    grid_ = Grid::over_half_bits(mean, half_bits, true);
    half_bits_ = half_bits;
    const int bits = (half_bits + 1) / 2;
    header_.bits = static_cast<uint32_t>(bits);
    for (int axis = 0; axis < 3; ++axis) {
      header_.origin[axis] = bit_cast<uint32_t>(grid_.origin[axis]);
      header_.step[axis] = bit_cast<uint32_t>(grid_.step[axis]);
    }
    header_.fraction_bits = static_cast<uint32_t>(std::clamp(24 - bits, 0, 8));
    header_.segment_frames = segment_frames;
    mean_.resize(s.vertex_count);
    for (size_t v = 0; v < s.vertex_count; ++v)
      if (!grid_.quantize(mean[v], mean_[v]))
        throw Error(ErrorKind::kInput, "", kNoPlane, kNoOffset, "the mean of vertex " + std::to_string(v) + " lies outside the grid");
    requested_clusters_ = clustering.requested;
    kmeans_seconds_ = clustering.seconds;
    set_up(s, clustering.cluster_of, coding_order, base_mesh_sizes);
    prepare(s, 0, fixed_bytes_, segment_limit(fixed_bytes_, 0, static_cast<uint32_t>(s.frames.size())));
    first_segment_bytes_ = plan_.bytes;
  }

  // The map's symbols are traced where the decoder reads them: after the
  // header's fields, or after the base mesh with prediction 1.
  void write_header(syntax::WriteIO& io) override {
    header_.map_bins = map_bins_;
    header_.map_raw = map_raw_;
    syntax::describe(io, header_);
    if (!io.trace()) return;
    map_trace_ = io.trace();
    map_trace_text_ = write_cluster_map<true>(header_, faces_, cluster_of_, map_bins_, map_raw_, map_place(), io.trace());
    if (header_.map_prediction == kCpcaMapByDifference) map_trace_->stream() << std::exchange(map_trace_text_, {});
  }

  // The base mesh, then segment after segment the plan's operators while
  // the stream through the last refinement stays within the segment's
  // share of --max-bytes, then the segment's frames' hashes.
  void encode(const FrameSource& frames, UnitSink& sink) override {
    sink.unit(UnitType::kBaseMesh, 0, [&](syntax::WriteIO& io) { write_base_mesh(io, faces_, mean_, base_mesh_); });
    if (map_trace_) map_trace_->stream() << std::exchange(map_trace_text_, {});
    if (max_bytes_ > 0 && sink.stream_bytes() > max_bytes_)
      throw usage_error("--max-bytes " + std::to_string(max_bytes_) + " is below the " + std::to_string(sink.stream_bytes()) +
                        " bytes of the header and the base mesh (cpca-wpt)");
    QualityMeter meter(frames);
    sent_total_ = 0;
    for (uint32_t first = 0; first < frame_count_; first += header_.segment_frames) {
      const uint32_t count = std::min(header_.segment_frames, frame_count_ - first);
      // The first segment was planned when the stream's model was chosen.
      const MeshSequence segment = frames_of(frames, first, count);
      const uint64_t limit = segment_limit(sink.stream_bytes(), first, count);
      if (first > 0) prepare(segment, first, sink.stream_bytes(), limit);
      emit(segment, first, limit, sink, meter);
    }
    kg_ = meter.kg();
  }

  // The stream's bytes through the first segment before its hash units: as
  // coded with --target-kg, else estimated (every operator's bytes and the
  // fixed part).
  uint64_t planned_bytes() const { return first_segment_bytes_; }
  int clusters() const { return requested_clusters_; }
  int half_bits() const { return half_bits_; }
  bool trajectory_model() const { return trajectories_; }

  std::vector<CodecStatistic> statistics() const override {
    return {{"mean shape bits", half_bits_ / 2.0},
            {"clusters", header_.cluster_count},
            {"trajectory model", trajectories_ ? 1.0 : 0.0},
            {"segment frames", header_.segment_frames},
            {"noise step log2", plan_.noise / 2.0},
            {"operators sent", static_cast<double>(sent_total_)},
            {"operators computed", static_cast<double>(computed_total_)},
            {"KG error", kg_},
            {"k-means seconds", kmeans_seconds_},
            {"SVD seconds", svd_seconds_},
            {"order seconds", order_seconds_}};
  }

 private:
  syntax::SectionPlace map_place() const { return {"cluster_map_bins", "cluster_map_raw", 0, 0, kNoPlane}; }

  // With --max-bytes, the most bytes of the stream through a segment of
  // `count` frames from `first`, the stream holding `so_far` before it: it
  // adds the bytes left in proportion to its frames; else no limit (0).
  uint64_t segment_limit(uint64_t so_far, uint32_t first, uint32_t count) const {
    if (max_bytes_ == 0) return 0;
    const uint64_t left = max_bytes_ > so_far ? max_bytes_ - so_far : 0;
    return so_far + (first + count == frame_count_ ? left : left * count / (frame_count_ - first));
  }

  // The map's prediction of fewer bytes (by the differences of equals).
  void choose_cluster_map() {
    header_.map_prediction = kCpcaMapByDifference;
    write_cluster_map<false>(header_, faces_, cluster_of_, map_bins_, map_raw_, map_place());
    CpcaHeader by_neighbours = header_;
    by_neighbours.map_prediction = kCpcaMapByNeighbours;
    std::vector<uint8_t> bins, raw;
    write_cluster_map<false>(by_neighbours, faces_, cluster_of_, bins, raw, map_place());
    if (bins.size() + raw.size() >= map_bins_.size() + map_raw_.size()) return;
    header_ = by_neighbours;
    map_bins_ = std::move(bins);
    map_raw_ = std::move(raw);
  }

  // What the stream fixes once: the clusters, the prediction over the
  // mesh, the cluster map, the bytes before the first refinement.
  void set_up(const MeshSequence& s, const std::vector<uint32_t>& cluster_of, std::span<const uint32_t> coding_order,
              BaseMeshSizes* base_mesh_sizes) {
    cluster_of_ = cluster_of;
    header_.cluster_count = *std::max_element(cluster_of_.begin(), cluster_of_.end()) + 1;
    members_ = cpca_members(cluster_of_, header_.cluster_count);
    faces_ = s.faces;
    mesh_.emplace(faces_, coding_order, cluster_of_, header_.cluster_count, mean_);
    mesh_->keep_fits();
    choose_cluster_map();
    fixed_bytes_ = fixed_bytes(s, base_mesh_sizes);
  }

  // A segment's analysis, then the plan of the noise step given, or of the
  // best one for --max-bytes (the smallest KG error within `limit`, the
  // stream's bytes through the segment, which holds `start_bytes` before
  // it) or --target-kg (the fewest bytes that reach it), else of the
  // default.
  void prepare(const MeshSequence& s, uint32_t first, uint64_t start_bytes, uint64_t limit) {
    limit_ = limit;
    segment_start_bytes_ = start_bytes;
    // A basis serves the segments left (continued), each adding its quantization error: finer by √ of their count.
    const double segments_left = std::ceil(static_cast<double>(frame_count_ - first) / header_.segment_frames);
    reuse_finer_ = static_cast<int>(std::lround(std::log2(segments_left)));
    translations_.assign(header_.cluster_count, {});
    components_of_.assign(header_.cluster_count, {});
    continued_.assign(header_.cluster_count, {});
    asked_.assign(header_.cluster_count, 0);
    mean_error_.clear();
    auto start = std::chrono::steady_clock::now();
    parallel_for(header_.cluster_count, threads_, [&](size_t c) { analyze(s, static_cast<uint32_t>(c)); });
    svd_seconds_ += seconds_since(start);
    start = std::chrono::steady_clock::now();
    const CpcaAnimation mean_only(header_, mean_, members_, static_cast<uint32_t>(s.frames.size()));
    for (uint32_t c = 0; c < header_.cluster_count; ++c) mean_error_.push_back(squared_error(s, mean_only, c));
    spread_ = squared_spread(s);
    int q = noise_.value_or(first > 0 ? plan_.noise : kDefaultNoise);
    if (!noise_ && (max_bytes_ > 0 || target_kg_ > 0)) {
      // From the default (a later segment: the previous segment's step),
      // towards the better neighbour while it improves (plans from
      // estimated gains), in whole steps (a later segment: none), then a
      // half step either side.
      Plan best = plan(s, q, false);
      for (const int direction : {2, -2}) {
        if (first > 0) break;
        for (int next = q + direction; next >= kMinNoise && next <= kMaxNoise; next += direction) {
          Plan tried = plan(s, next, false);
          if (!better(tried, best)) break;
          best = std::move(tried);
        }
        if (best.noise != q) break;
      }
      q = best.noise;
      for (const int next : {q - 1, q + 1}) {
        if (next < kMinNoise || next > kMaxNoise) continue;
        Plan tried = plan(s, next, false);
        if (better(tried, best)) best = std::move(tried);
      }
      q = best.noise;
    }
    plan_ = plan(s, q, true);
    if (target_kg_ > 0) {
      reach_target(s);
      plan_.bytes = coded_bytes();
    }
    computed_total_ += plan_.operators.size();
    order_seconds_ += seconds_since(start);
  }

  // Cluster c's translation, its components continuing the previous
  // segment's, and the leading components of what they leave: asked_[c]
  // of them, first every one where that is cheap (Gram matrices up to
  // kAllComponentsSize), else the first kFirstComponents, twice as many
  // each time a plan runs out of them (plan()).
  void analyze(const MeshSequence& s, uint32_t c) {
    Eigen::MatrixXd d = motion(s, c);
    translations_[c] = translation_of(d);
    for (Eigen::Index row = 0; row < d.rows(); ++row) d.row(row) -= translations_[c](Eigen::seqN(row % 3, d.cols(), 3)).transpose();
    Eigen::MatrixXd m = trajectories_ ? as_trajectories(d) : d;
    continued_[c] = continue_listed(c, m);
    const size_t size = static_cast<size_t>(std::min(m.rows(), m.cols()));
    if (asked_[c] == 0) asked_[c] = size <= kAllComponentsSize ? components_ : std::min(components_, kFirstComponents);
    components_of_[c] = principal_components(m, asked_[c]);
  }

  // plan_for, with more components for the clusters whose chain of
  // components the plan used up while more may follow.
  Plan plan(const MeshSequence& s, int q, bool exact) {
    for (;;) {
      Plan p = plan_for(s, q, exact);
      std::vector<uint32_t> more;
      for (uint32_t c = 0; c < header_.cluster_count; ++c)
        if (p.chains[c] == components_of_[c].size() && components_of_[c].size() == asked_[c] && asked_[c] < components_) {
          asked_[c] = std::min(components_, 2 * asked_[c]);
          more.push_back(c);
        }
      if (more.empty()) return p;
      parallel_for(more.size(), threads_, [&](size_t i) { analyze(s, more[i]); });
    }
  }

  // The segment's units: the plan's operators while the stream stays
  // within `limit` (0: none), then the decoded frames and their hashes;
  // the components sent are the ones the next segment may continue.
  void emit(const MeshSequence& s, uint32_t first, uint64_t limit, UnitSink& sink, QualityMeter& meter) {
    const uint32_t count = static_cast<uint32_t>(s.frames.size());
    CpcaAnimation animation(header_, mean_, members_, count);
    std::vector<uint8_t> started(header_.cluster_count, 0);
    const std::vector<uint32_t> continuable = continuable_counts();
    std::vector<std::vector<ListedBasis>> listed(header_.cluster_count);
    std::vector<std::optional<CpcaCarried>> started_last(header_.cluster_count);
    size_t sent = 0;
    double group_bytes = static_cast<double>(group_bytes_);
    while (sent < plan_.sent) {
      std::vector<Operator*> unit = next_unit(sent, static_cast<uint64_t>(group_bytes));
      group_bytes = std::min(group_bytes * group_growth_, kMaxGroupGrowth * static_cast<double>(group_bytes_));
      const size_t planned = unit.size();
      if (limit > 0)
        while (!unit.empty()) {
          std::vector<uint8_t> after = started;
          if (sink.stream_bytes() + unit_bytes(unit, after, continuable) <= limit) break;
          unit.pop_back();
        }
      if (unit.empty()) break;
      sink.unit(UnitType::kRefinement, first,
                [&](syntax::WriteIO& io) { write_refinements(io, unit, *mesh_, started, continuable); });
      for (const Operator* op : unit) {
        apply(animation, *op);
        if (op->kind == kCpcaStart)
          started_last[op->cluster] = CpcaCarried::of(op->translation, 3, op->shift);
        else
          listed[op->cluster].push_back({op->basis, op->basis_exponent, CpcaCarried::of(op->coefficients, op->trajectory ? 3 : 1, op->shift)});
      }
      sent += unit.size();
      sink.progress(first + count * sent / std::max<size_t>(plan_.sent, 1), frame_count_);
      if (unit.size() < planned) break;  // --max-bytes reached
    }
    sent_total_ += sent;
    if (target_kg_ > 0 && sent < plan_.sent && kg_of_prefix(s, sent) > target_kg_)
      throw usage_error("--target-kg " + std::to_string(target_kg_) + " is out of reach within --max-bytes (cpca-wpt)");
    std::vector<Float3> decoded(s.vertex_count);
    for (uint32_t f = 0; f < count; ++f) {
      animation.frame(f, decoded);
      sink.decoded(first + f, decoded);
      meter.add(first + f, decoded);
    }
    sink.end_segment();
    listed_ = std::move(listed);
    started_last_ = std::move(started_last);
  }

  // Whether the segment being planned may continue the previous one's starts and components.
  bool continuing() const { return !started_last_.empty(); }

  std::vector<uint32_t> continuable_counts() const {
    std::vector<uint32_t> counts(header_.cluster_count, 0);
    if (continuing())
      for (uint32_t c = 0; c < header_.cluster_count; ++c) counts[c] = static_cast<uint32_t>(listed_[c].size());
    return counts;
  }

  // The least-squares coefficients of cluster c's motion `m` (a row per
  // basis value) on the bases the previous segment sent, as components;
  // `m` keeps what they leave.
  std::vector<Component> continue_listed(uint32_t c, Eigen::MatrixXd& m) const {
    if (!continuing() || listed_[c].empty()) return {};
    const std::vector<ListedBasis>& listed = listed_[c];
    Eigen::MatrixXd b(m.rows(), static_cast<Eigen::Index>(listed.size()));
    for (size_t j = 0; j < listed.size(); ++j) {
      const double scale = 1 / power_of_sqrt2(listed[j].exponent);
      for (Eigen::Index i = 0; i < m.rows(); ++i) b(i, static_cast<Eigen::Index>(j)) = listed[j].basis[static_cast<size_t>(i)] * scale;
    }
    Eigen::MatrixXd gram = b.transpose() * b;
    gram.diagonal().array() += 1e-9 * std::max(gram.trace(), 1e-30);
    const Eigen::MatrixXd y = gram.ldlt().solve(b.transpose() * m);
    m -= b * y;
    std::vector<Component> continued;
    for (Eigen::Index j = 0; j < y.rows(); ++j) continued.push_back({0, b.col(j), y.row(j).transpose()});
    return continued;
  }

  // Every cluster's operators at noise step 2^(q / 2), each kept while it removes
  // error from the decoder's output (exactly, or estimated); their order;
  // the prefix sent.
  Plan plan_for(const MeshSequence& s, int q, bool exact) const {
    Plan plan;
    plan.noise = q;
    plan.chains.assign(header_.cluster_count, 0);
    std::optional<CpcaAnimation> animation;
    if (exact) animation.emplace(header_, mean_, members_, static_cast<uint32_t>(s.frames.size()));
    // Each cluster's chain on a thread (a cluster changes its own members' positions alone), then joined in cluster order.
    std::vector<std::vector<Operator>> sequences(header_.cluster_count);
    parallel_for(header_.cluster_count, threads_, [&](size_t index) {
      const uint32_t c = static_cast<uint32_t>(index);
      // The start, then the components while each removes error; a start
      // that would add error moves nothing (all zeros); a cluster whose
      // start and first component remove none is left as it is.
      const size_t members = members_[c].size();
      double error = mean_error_[c];
      std::vector<Operator>& sequence = sequences[c];
      auto measure = [&](Operator& op, double estimate) {
        if (animation) {
          apply(*animation, op);
          const double after = squared_error(s, *animation, c);
          op.gain = error - after;
          error = after;
        } else {
          op.gain = estimate;
        }
      };
      // An operator that removes no error leaves the animation as it was.
      auto undo = [&](const Operator& op) {
        if (!animation) return;
        apply(*animation, op, true);
        error = squared_error(s, *animation, c);
      };
      Operator start = quantize_start(translations_[c], c, members, q, static_cast<int>(header_.fraction_bits));
      if (continuing() && started_last_[c]) start.before = started_last_[c]->at(start.shift, kCpcaMaxTranslation);
      if (!(estimated_gain(translations_[c], members, start) > 0)) std::fill(start.translation.begin(), start.translation.end(), 0);
      measure(start, estimated_gain(translations_[c], members, start));
      if (start.gain < 0) {  // the output's rounding: undo (exactly: no shift rounds), and move nothing
        undo(start);
        std::fill(start.translation.begin(), start.translation.end(), 0);
        start.gain = 0;
      }
      sequence.push_back(std::move(start));
      // A segment takes at most the rank bound of its motion's components per cluster, continued ones included.
      const uint64_t limit = cpca_component_limit(trajectories_ ? kCpcaTrajectory : kCpcaComponent, members, static_cast<uint32_t>(s.frames.size()));
      for (size_t j = 0; j < continued_[c].size() && sequence.size() <= limit; ++j) {
        const ListedBasis& listed = listed_[c][j];
        const Component& component = continued_[c][j];
        Operator op = quantize_continued(listed.basis, listed.exponent, component.coefficients, c, static_cast<uint32_t>(j), trajectories_, q,
                                         static_cast<int>(header_.fraction_bits));
        op.before = listed.coefficients.at(op.shift, kCpcaMaxCoefficient);
        Component unit{component.basis.norm() * component.coefficients.norm(), component.basis.normalized(),
                       component.coefficients.normalized()};
        measure(op, unit.sigma > 0 ? estimated_gain(unit, op) : 0);
        if (!(op.gain > 0)) {
          undo(op);
          continue;
        }
        op.bytes = operator_bytes(op);
        sequence.push_back(std::move(op));
      }
      for (const Component& component : components_of_[c]) {
        if (sequence.size() > limit) break;
        Operator op =
            quantize(component, c, q, static_cast<int>(header_.fraction_bits), (trajectories_ ? kTrajectoryBasisFiner : 0) + reuse_finer_);
        if (trajectories_) {
          op.kind = kCpcaTrajectory;
          op.trajectory = true;
          const double scale = power_of_sqrt2(op.basis_exponent);
          std::vector<double> target(static_cast<size_t>(component.basis.size()));
          for (size_t i = 0; i < target.size(); ++i) target[i] = component.basis(static_cast<Eigen::Index>(i)) * scale;
          mesh_->quantize<1>(c, target, kTrajectoryBasisRounding, op.basis);
        }
        measure(op, estimated_gain(component, op));
        if (!(op.gain > 0)) break;  // quantization ate the component: the later ones are smaller still
        sequence.push_back(std::move(op));
        ++plan.chains[c];
      }
      if (sequence.size() == 1 && !(sequence[0].gain > 0)) {
        sequence.clear();
        return;
      }
      for (Operator& op : sequence) {
        if (op.kind == kCpcaComponent)
          choose_kind(op);
        else if (op.kind != kCpcaContinued)
          op.bytes = operator_bytes(op);
      }
    });
    std::vector<std::vector<size_t>> per_cluster(header_.cluster_count);
    for (uint32_t c = 0; c < header_.cluster_count; ++c)
      for (Operator& op : sequences[c]) {
        per_cluster[c].push_back(plan.operators.size());
        plan.operators.push_back(std::move(op));
      }
    plan.order = round_robin_ ? round_robin(per_cluster) : by_weight(plan.operators, per_cluster);
    double error = 0;
    for (double e : mean_error_) error += e;
    plan.bytes = segment_start_bytes_;
    for (size_t i = 0; i < plan.order.size(); ++i) {
      const Operator& op = plan.operators[plan.order[i]];
      if (limit_ > 0 && plan.bytes + op.bytes > limit_) break;
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
      if (plan_.sent == plan_.order.size() || (limit_ > 0 && plan_.bytes + plan_.operators[plan_.order[plan_.sent]].bytes > limit_))
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
    for (uint32_t f = 0; f < s.frames.size(); ++f)
      for (NodeIndex v : members_[c]) {
        const Vec3& p = s.frames[f][v];
        const Float3 decoded = animation.position(f, v);
        const double dx = (p.x - decoded[0]) / unit, dy = (p.y - decoded[1]) / unit, dz = (p.z - decoded[2]) / unit;
        sum += dx * dx + dy * dy + dz * dz;
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

  // The plan's operators from its `first` that the next unit carries: one,
  // then more while their bytes stay below `group_bytes` (at most 255).
  std::vector<Operator*> next_unit(size_t first, uint64_t group_bytes) {
    std::vector<Operator*> unit;
    uint64_t bytes = 0;
    for (size_t i = first; i < plan_.sent && unit.size() < kCpcaMaxGroupSize && (unit.empty() || bytes < group_bytes); ++i) {
      unit.push_back(&plan_.operators[plan_.order[i]]);
      bytes += unit.back()->bytes;
    }
    return unit;
  }

  // The bytes before the segment's hash units of the stream that sends the
  // plan, its operators in the units `encode` makes.
  uint64_t coded_bytes() {
    uint64_t bytes = segment_start_bytes_;
    std::vector<uint8_t> started(header_.cluster_count, 0);
    const std::vector<uint32_t> continuable = continuable_counts();
    double group_bytes = static_cast<double>(group_bytes_);
    for (size_t sent = 0; sent < plan_.sent;) {
      const std::vector<Operator*> unit = next_unit(sent, static_cast<uint64_t>(group_bytes));
      group_bytes = std::min(group_bytes * group_growth_, kMaxGroupGrowth * static_cast<double>(group_bytes_));
      bytes += unit_bytes(unit, started, continuable);
      sent += unit.size();
    }
    return bytes;
  }

  // The bytes of the unit of these operators in the stream, after the
  // starts `started` lists; the unit's starts are added to it.
  uint64_t unit_bytes(std::span<Operator* const> operators, std::vector<uint8_t>& started, std::span<const uint32_t> continuable) const {
    BitWriter writer;
    syntax::WriteIO io(writer);
    UnitHeader header{static_cast<uint32_t>(UnitType::kRefinement), 0};
    syntax::describe(io, header);
    write_refinements(io, operators, *mesh_, started, continuable);
    return ContainerWriter::unit_size(writer.bytes());
  }

  // An operator's bytes in the stream: its own unit's, or with groups
  // (estimated) those less the unit's framing and fields, which a group
  // shares, plus its entry in the group's list.
  uint64_t operator_bytes(Operator& op) const {
    Operator* const alone[] = {&op};
    std::vector<uint8_t> none_started(header_.cluster_count, 0);
    const uint64_t bytes = unit_bytes(alone, none_started, continuable_counts());
    return group_bytes_ > 0 ? std::max<uint64_t>(bytes, kSharedInGroup + 1) - kSharedInGroup : bytes;
  }

  // A component's unit in the kind --basis asks for, or the smaller.
  void choose_kind(Operator& op) const {
    op.kind = basis_prediction_ == "index" ? kCpcaComponent : kCpcaMeshComponent;
    op.bytes = operator_bytes(op);
    if (basis_prediction_ != "auto") return;
    Operator by_index = op;
    by_index.kind = kCpcaComponent;
    by_index.bytes = operator_bytes(by_index);
    if (by_index.bytes < op.bytes) op = std::move(by_index);
  }

  // The bytes before the first refinement unit: the object (its frame rate
  // assumed 25/1, which may change the escaping by a byte) and the base mesh.
  // The base mesh unit depends on the mean shape's bits alone: a search's
  // candidates share it. Its blend, once chosen, is the one encode() writes.
  uint64_t fixed_bytes(const MeshSequence& s, BaseMeshSizes* shared) {
    BitWriter object;
    syntax::WriteIO object_io(object);
    ObjectHeader header{kFormatVersion, 4, s.vertex_count, static_cast<uint32_t>(s.faces.size()), frame_count_, 25, 1};
    syntax::describe(object_io, header);
    write_header(object_io);
    const auto base_mesh_unit = [&] {
      BitWriter base;
      syntax::WriteIO base_io(base);
      UnitHeader unit{static_cast<uint32_t>(UnitType::kBaseMesh), 0};
      syntax::describe(base_io, unit);
      const uint32_t blend = write_base_mesh(base_io, s.faces, mean_, base_mesh_);
      return BaseMeshUnit{ContainerWriter::unit_size(base.bytes()), blend};
    };
    const BaseMeshUnit base = shared ? shared->of(half_bits_, base_mesh_unit) : base_mesh_unit();
    base_mesh_.position_blend = base.position_blend;
    return ContainerWriter::unit_size(object.bytes()) + base.bytes;
  }

  // The KG error of the decoder's output of the segment after the plan's
  // first `count` operators, as `m4mesh metrics` measures it.
  double kg_of_prefix(const MeshSequence& s, size_t count) const {
    CpcaAnimation animation(header_, mean_, members_, static_cast<uint32_t>(s.frames.size()));
    for (size_t i = 0; i < count; ++i) {
      const Operator& op = plan_.operators[plan_.order[i]];
      apply(animation, op);
    }
    const SequenceSource original(s);
    QualityMeter meter(original);
    std::vector<Float3> decoded(s.vertex_count);
    for (uint32_t f = 0; f < s.frames.size(); ++f) {
      animation.frame(f, decoded);
      meter.add(f, decoded);
    }
    return meter.kg();
  }

  size_t components_ = 0;
  int requested_clusters_ = 0;
  uint64_t max_bytes_;
  uint64_t group_bytes_;  // each segment's first group's; 0: a unit per operator
  double group_growth_;
  double target_kg_;
  bool round_robin_;
  std::string basis_prediction_;  // --basis: index, mesh or auto
  bool trajectories_;  // components of the members' trajectories (unit_kind 3), else of their shapes
  std::optional<int> noise_;  // log2 of the noise step in half steps; none: auto
  BaseMeshCoding base_mesh_;
  unsigned threads_;  // clusters analysed and planned at once (0: every core)
  uint32_t frame_count_;
  Grid grid_;
  CpcaHeader header_;
  std::vector<IntPoint3> mean_;
  std::vector<uint32_t> cluster_of_;
  std::vector<std::vector<NodeIndex>> members_;
  std::optional<CpcaMeshPrediction> mesh_;
  std::vector<uint8_t> map_bins_, map_raw_;
  std::vector<Triangle> faces_;  // the base mesh's, which predict the map
  Trace* map_trace_ = nullptr;
  std::string map_trace_text_;  // the map's symbols, traced after the base mesh with prediction 1
  uint64_t fixed_bytes_ = 0;
  uint64_t first_segment_bytes_ = 0;
  // The segment being planned: per cluster its translation, the components
  // continuing the previous segment's (as listed_), its own components;
  // its frames' spread, the bytes of the stream before it and the most
  // through it (0: no limit); its plan.
  std::vector<Translation> translations_;
  std::vector<std::vector<Component>> continued_;
  std::vector<std::vector<Component>> components_of_;
  std::vector<size_t> asked_;       // per cluster, the components asked of its analysis
  std::vector<double> mean_error_;  // per cluster, of the mean shape alone
  double spread_ = 0;
  uint64_t segment_start_bytes_ = 0, limit_ = 0;
  int reuse_finer_ = 0;  // half steps finer the segment's new bases are quantized
  Plan plan_;
  // Per cluster, the components the segment before sent, in stream order,
  // and its start's last translation (empty before the second segment).
  std::vector<std::vector<ListedBasis>> listed_;
  std::vector<std::optional<CpcaCarried>> started_last_;
  size_t sent_total_ = 0, computed_total_ = 0;
  int half_bits_ = 0;
  double kg_ = 0, kmeans_seconds_ = 0, svd_seconds_ = 0, order_seconds_ = 0;
};

}  // namespace

std::unique_ptr<CodecEncoder3d> make_cpca_wpt_encoder(const FrameSource& source, const CodecSettings& settings) {
  using namespace cpca_wpt;
  const Options options = parse_options(settings);
  const uint32_t frame_count = source.frame_count(), segment_frames = segment_length(options, source.vertex_count(), frame_count);
  // The first segment chooses the stream's model; the vertices in the base mesh's coding order, once for every candidate.
  MeshSequence sequence = frames_of(source, 0, std::min(segment_frames, frame_count));
  sequence.faces.assign(source.faces().begin(), source.faces().end());
  const bool target = options.target_kg > 0;
  const bool bits_auto = !options.bits;
  const int half_bits = 2 * options.bits.value_or(kDefaultBits);
  // A large first segment is searched on its first frames (at least 16),
  // with fewer candidates (the trajectory model, whole bits): they compare
  // their plans of those frames, and the one kept codes the segment.
  const uint32_t searched = static_cast<uint32_t>(std::clamp<uint64_t>(kWholeSearchVertexFrames / sequence.vertex_count,
                                                                         std::min<size_t>(16, sequence.frames.size()), sequence.frames.size()));
  const bool windowed = searched < sequence.frames.size();
  const std::vector<int> cluster_counts = options.clusters ? std::vector<int>{*options.clusters}
                                          : target && windowed ? std::vector<int>{10, 20, 40}
                                          : target             ? std::vector<int>{5, 10, 20, 40}
                                                               : std::vector<int>{kPaperClusters};
  const std::vector<bool> trajectory_models = options.model == "shape"                                  ? std::vector<bool>{false}
                                              : options.model == "trajectory" || !target || windowed ? std::vector<bool>{true}
                                                                                                      : std::vector<bool>{true, false};
  const std::vector<uint32_t> coding_order = settings.coding_order().empty()
                                                 ? plan_base_mesh(sequence.faces, sequence.vertex_count, false).input_of
                                                 : std::vector<uint32_t>(settings.coding_order().begin(), settings.coding_order().end());
  if (cluster_counts.size() == 1 && trajectory_models.size() == 1 && !(bits_auto && target))
    return std::make_unique<CpcaEncoder>(sequence, frame_count, segment_frames, options, half_bits, clustering(sequence, cluster_counts[0]),
                                         trajectory_models[0], coding_order);
  MeshSequence window;
  if (windowed) {
    window.vertex_count = sequence.vertex_count;
    window.faces = sequence.faces;
    window.frames.assign(sequence.frames.begin(), sequence.frames.begin() + searched);
  }
  const MeshSequence& candidate_frames = windowed ? window : sequence;
  BaseMeshSizes base_mesh_sizes;
  // The cluster count and model whose plan reaches the target in the fewest
  // bytes, then the counts √2 either side of it, then the mean shape's bits
  // from 12 towards the smaller plan, then half a bit either side, then the
  // counts 2^(1/4) and 2^(1/8) either side at those bits.
  // Candidates run side by side; the first of the smallest is kept, whatever
  // the threads.
  struct Candidate {
    int half_bits, clusters;
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
    parallel_for(counts.size(), settings.threads(), [&](size_t i) { computed[i] = clustering(candidate_frames, counts[i]); });
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
            built[i] = std::make_unique<CpcaEncoder>(candidate_frames, frame_count, segment_frames, options, candidates[i].half_bits,
                                                     clusterings.at(candidates[i].clusters), candidates[i].trajectories, coding_order,
                                                     &base_mesh_sizes);
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
    for (const bool trajectories : trajectory_models) first.push_back({half_bits, clusters, trajectories});
  try_all(first);
  if (!best) throw *missed;
  const int chosen = best->clusters();
  const bool trajectories = best->trajectory_model();
  if (cluster_counts.size() > 1)
    try_all({{half_bits, chosen * 7 / 10, trajectories}, {half_bits, chosen * 14 / 10, trajectories}});
  if (bits_auto) {
    const int clusters = best->clusters();
    const uint64_t before = best->planned_bytes();
    try_all({{half_bits - 2, clusters, trajectories}, {half_bits + 2, clusters, trajectories}});
    if (best->planned_bytes() < before) {
      const int direction = best->half_bits() < half_bits ? -2 : 2;
      for (int h = half_bits + 2 * direction; h >= 2 * kMinBits && h <= 2 * kMaxBits && try_all({{h, clusters, trajectories}}); h += direction) {
      }
    }
    const int whole = best->half_bits();
    std::vector<Candidate> halves;
    for (const int h : {whole - 1, whole + 1})
      if (h >= 2 * kMinBits && h <= 2 * kMaxBits && !windowed) halves.push_back({h, clusters, trajectories});
    try_all(halves);
  }
  if (cluster_counts.size() > 1 && !windowed) {
    const int h = best->half_bits();
    for (const int percent : {119, 109}) {
      const int c = best->clusters();
      std::vector<Candidate> near;
      for (const int n : {c * 100 / percent, c * percent / 100})
        if (n >= 1 && n != c) near.push_back({h, n, trajectories});
      try_all(near);
    }
  }
  if (searched == sequence.frames.size()) return best;
  // The window's encoder goes before the segment's is built.
  const Candidate kept{best->half_bits(), best->clusters(), best->trajectory_model()};
  best.reset();
  return std::make_unique<CpcaEncoder>(sequence, frame_count, segment_frames, options, kept.half_bits, clusterings.at(kept.clusters),
                                       kept.trajectories, coding_order);
}

}  // namespace m4mesh
