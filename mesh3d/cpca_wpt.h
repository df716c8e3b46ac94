// The normative process of the clustered-PCA codec (codec_id 4,
// ../shared/seeds/002), shared by its encoder and decoder: the clusters
// from the cluster map, and the decoded animation in fixed point, which
// every refinement operator refines in place (Eq. 5 of the report,
// Φᵢ₊₁ = Φᵢ + Bᵢ Sᵢᵢ Vᵢᵀ) with integer arithmetic only.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "common/point3.h"
#include "mesh/topology.h"
#include "mesh3d/affine_fit.h"
#include "mesh3d/base_mesh.h"
#include "mesh3d/mesh_predictor.h"
#include "syntax/mesh3d/cpca_wpt.h"
#include "syntax/mesh3d/entropy_io.h"

namespace m4mesh {

// Each cluster's vertices in index order.
std::vector<std::vector<NodeIndex>> cpca_members(std::span<const uint32_t> cluster_of, uint32_t cluster_count);

// cluster_map_prediction 1 (docs/codec_cpca_wpt.md, "The cluster map"):
// every vertex's cluster ranked by the clusters of its neighbours numbered
// before it, over the base mesh's faces in output numbers (`around`).
template <class IO>
void describe_cluster_map_by_neighbours(IO& io, const MeshPredictor& around, std::span<uint32_t> cluster_of, uint32_t cluster_count) {
  syntax::CpcaRankContexts contexts;
  std::vector<uint32_t> count(cluster_count, 0);
  std::vector<uint32_t> held;  // the clusters the vertex's earlier neighbours hold
  for (uint32_t v = 0; v < cluster_of.size(); ++v) {
    around.for_each_known_corner(v, [v](uint32_t u) { return u < v; }, [&](uint32_t u) {
      if (count[cluster_of[u]]++ == 0) held.push_back(cluster_of[u]);
    });
    // The most frequent first, the lower cluster of equals; without a neighbour, the previous vertex's cluster (0 for the first).
    const auto ahead = [&](uint32_t a, uint32_t b) { return count[a] > count[b] || (count[a] == count[b] && a < b); };
    uint32_t first = v > 0 ? cluster_of[v - 1] : 0, second = first;
    if (!held.empty()) {
      first = held[0];
      second = held[0];
      for (size_t i = 1; i < held.size(); ++i) {
        const uint32_t c = held[i];
        if (ahead(c, first)) {
          second = first;
          first = c;
        } else if (second == first || ahead(c, second)) {
          second = c;
        }
      }
    }
    const uint32_t candidates = held.empty() ? 1 : static_cast<uint32_t>(held.size());
    syntax::describe_ranked_cluster(io, contexts, candidates, first, second, cluster_count, cluster_of[v]);
    for (uint32_t c : held) count[c] = 0;
    held.clear();
  }
}

// The header's cluster map read, as its cluster_map_prediction says; with
// prediction 1 `around` is over the base mesh's faces (output numbers).
template <bool kTraced>
std::vector<uint32_t> read_cluster_map(const CpcaHeader& h, const MeshPredictor& around, uint32_t vertex_count,
                                       const syntax::SectionPlace& place, Trace* trace = nullptr) {
  std::vector<uint32_t> cluster_of(vertex_count);
  syntax::EntropyReadIO<kTraced> symbols(h.map_bins, h.map_raw, place, trace);
  if (h.map_prediction == kCpcaMapByNeighbours) {
    describe_cluster_map_by_neighbours(symbols, around, cluster_of, h.cluster_count);
    symbols.finish("cluster_not_first");
  } else {
    syntax::describe_cluster_map(symbols, cluster_of, h.cluster_count);
    symbols.finish("cluster_of_vertex");
  }
  return cluster_of;
}

// The header's cluster map written, the mirror of read_cluster_map(): the
// sections into `bins` and `raw`, which `h` then points at with their
// lengths; returns the symbols' trace (in the place of `like`).
template <bool kTraced>
std::string write_cluster_map(CpcaHeader& h, std::span<const Triangle> faces, std::vector<uint32_t> cluster_of, std::vector<uint8_t>& bins,
                              std::vector<uint8_t>& raw, const syntax::SectionPlace& place, Trace* like = nullptr) {
  syntax::EntropyWriteIO<kTraced> symbols(place, like);
  if (h.map_prediction == kCpcaMapByNeighbours)
    describe_cluster_map_by_neighbours(symbols, MeshPredictor(faces, static_cast<uint32_t>(cluster_of.size())), cluster_of, h.cluster_count);
  else syntax::describe_cluster_map(symbols, cluster_of, h.cluster_count);
  bins = symbols.finish_bins();
  raw = symbols.finish_raw();
  h.map_bins_bytes = static_cast<uint32_t>(bins.size());
  h.map_bins = bins;
  h.map_raw_bytes = static_cast<uint32_t>(raw.size());
  h.map_raw = raw;
  return symbols.trace_text();
}

// The number of components of a cluster of `members` vertices over
// `frames` frames, the rank bound of its motion matrix: min(3 · members,
// frames) of unit_kind 1 and 2 together, min(members, 3 · frames) of
// unit_kind 3 (trajectories).
inline uint64_t cpca_component_limit(uint32_t kind, size_t members, uint32_t frames) {
  return kind == kCpcaTrajectory ? std::min<uint64_t>(members, 3 * uint64_t{frames}) : std::min<uint64_t>(3 * uint64_t{members}, frames);
}

// The prediction of a component's basis over the base mesh (unit_kind 2
// and 3): a cluster's members in its member order, each predicted from the
// members before it by an affine fit over the mean shape
// (mesh3d/affine_fit.h).
class CpcaMeshPrediction {
 public:
  // faces: the base mesh's, coding_order: its vertices in coding order,
  // mean_shape: its decoded positions. The member order is the position
  // order over the cluster (docs/codec_cpca_wpt.md).
  CpcaMeshPrediction(std::span<const Triangle> faces, std::span<const uint32_t> coding_order, std::span<const uint32_t> cluster_of,
                     uint32_t cluster_count, std::span<const IntPoint3> mean_shape);
  // The same with the faces' predictor built already (a decoder's, shared with the cluster map).
  CpcaMeshPrediction(MeshPredictor predictor, std::span<const uint32_t> coding_order, std::span<const uint32_t> cluster_of,
                     uint32_t cluster_count, std::span<const IntPoint3> mean_shape);

  // Every member's fit support and shape found once and
  // kept (about 200 bytes a vertex), for an encoder that predicts the same
  // members again and again; the predictions do not change. With a
  // cluster, its members' only (a decoder, before its first component
  // over the mesh).
  void keep_fits();
  void keep_fits(uint32_t cluster);

  // A cluster's members in member order.
  std::span<const uint32_t> members_in_order(uint32_t cluster) const { return in_order_[cluster]; }
  // The points member v's fit reads (affine_fit_support over its cluster); the channel.
  int fit_support(uint32_t v, std::vector<uint32_t>& points) const {
    return affine_fit_support(predictor_, v, [&](uint32_t u) { return rank_[u] < rank_[v] && cluster_of_[u] == cluster_of_[v]; }, points);
  }

  // A component over the mesh: D basis values per member (unit_kind 2:
  // D = 3, x, y, z; unit_kind 3: D = 1) at basis[D·i + a], i the member's
  // slot in the cluster's index order, for the members in member order:
  // the residual from the prediction, on channel a after a parallelogram,
  // D + a after an affine fit without a parallelogram, else (no neighbour known) D + a from the
  // member before (0 for the first); |basis| ≤ 2^15.
  // Then the coefficients (3/D per frame) as the differences to the same
  // lane the frame before, on channels 2D + lane; |coefficient| ≤ 2^23.
  template <size_t D, class IO>
  void describe_operator(IO& io, syntax::ResidualCoder<2 * D + 3 / D>& coder, uint32_t cluster, std::span<int32_t> basis,
                         std::span<int32_t> coefficients) const {
    static_assert(D == 1 || D == 3);
    const syntax::ResidualNames& basis_names = D == 3 ? syntax::kCpcaMeshBasis : syntax::kCpcaTrajectoryBasis;
    const syntax::ResidualNames& coefficient_names = D == 3 ? syntax::kCpcaCoefficient : syntax::kCpcaTrajectoryCoefficient;
    std::array<int64_t, D> p{}, previous{};
    std::vector<uint32_t> points;
    for (const uint32_t v : in_order_[cluster]) {
      int channel = predict<D>(cluster, v, basis, points, p);
      if (channel < 0) p = previous;
      channel = channel == syntax::kParallelogramChannel ? 0 : static_cast<int>(D);
      for (size_t a = 0; a < D; ++a) {
        int32_t& b = basis[D * size_t{slot_[v]} + a];
        int32_t residual = 0;
        if constexpr (!IO::kReading) residual = static_cast<int32_t>(b - p[a]);
        coder.describe(io, channel + static_cast<int>(a), residual, basis_names);
        const int64_t decoded = p[a] + residual;
        if (decoded < -kCpcaMaxBasis || decoded > kCpcaMaxBasis) io.fail(ErrorKind::kOutOfRange, basis_names.element, "a basis value beyond ±2^15");
        b = static_cast<int32_t>(decoded);
        previous[a] = decoded;
      }
    }
    syntax::describe_differences(io, coder, coefficients, 2 * D, 3 / D, -kCpcaMaxCoefficient, kCpcaMaxCoefficient, coefficient_names,
                                 "a coefficient beyond ±2^23");
  }

  // The encoder's basis values nearest `target` (the real values in basis
  // steps), each residual from its prediction rounded towards 0 when its
  // fraction is below 1 − `rounding` (0.5: to nearest).
  template <size_t D>
  void quantize(uint32_t cluster, std::span<const double> target, double rounding, std::span<int32_t> basis) const {
    std::array<int64_t, D> p{}, previous{};
    std::vector<uint32_t> points;
    for (const uint32_t v : in_order_[cluster]) {
      if (predict<D>(cluster, v, basis, points, p) < 0) p = previous;
      for (size_t a = 0; a < D; ++a) {
        const size_t i = D * size_t{slot_[v]} + a;
        const double x = target[i] - static_cast<double>(p[a]);
        const int64_t residual = static_cast<int64_t>(std::copysign(std::floor(std::abs(x) + rounding), x));
        previous[a] = std::clamp<int64_t>(p[a] + residual, -kCpcaMaxBasis, kCpcaMaxBasis);
        basis[i] = static_cast<int32_t>(previous[a]);
      }
    }
  }

 private:
  // Member v's prediction from the members of `cluster` before it; the
  // channel as MeshPredictor::predict's.
  template <size_t D>
  int predict(uint32_t cluster, uint32_t v, std::span<const int32_t> basis, std::vector<uint32_t>& points, std::array<int64_t, D>& p) const {
    const uint32_t rank = rank_[v];
    const auto known = [&](uint32_t u) { return rank_[u] < rank && cluster_of_[u] == cluster; };
    const auto value = [&](uint32_t u) {
      std::array<int32_t, D> values;
      for (size_t a = 0; a < D; ++a) values[a] = basis[D * slot_[u] + a];
      return values;
    };
    if (!fits_.empty() && kept_[cluster]) {
      const KeptFit& fit = fits_[v];
      const std::span<const uint32_t> support(fit_points_.data() + fit.first, fit.count);
      if (fit.channel >= 0) affine_fit_values<D>(fit.shape, support, std::span(fit_q_.data() + fit.first, fit.count), value, p);
      return fit.channel;
    }
    const int channel = affine_fit_support(predictor_, v, known, points);
    if (channel >= 0) affine_fit(mean_shape_, v, points, value, p);
    return channel;
  }

  // A member's fit as keep_fits() found it: its support is
  // fit_points_[first … first + count − 1], their differences fit_q_.
  struct KeptFit {
    int channel = -1;
    uint32_t first = 0, count = 0;
    AffineFitShape shape;
  };

  MeshPredictor predictor_;
  std::vector<IntPoint3> mean_shape_;
  std::vector<uint32_t> rank_;                         // per vertex: its place in its cluster's member order
  std::vector<uint32_t> slot_;                         // per vertex: its index among its cluster's members
  std::vector<uint32_t> cluster_of_;
  std::vector<std::vector<uint32_t>> in_order_;        // per cluster: its members in member order
  std::vector<KeptFit> fits_;                          // per vertex, with keep_fits()
  std::vector<uint8_t> kept_;                          // per cluster: its members' fits are in fits_
  std::vector<uint32_t> fit_points_;
  std::vector<std::array<int32_t, 3>> fit_q_;
};

// One refinement's symbols with the unit's coders: a start's translation
// (3N values), or a component's basis (3 or, for unit_kind 3, 1 per member
// of its cluster) and coefficients (N or 3N), each span of that size; a
// continued component (unit_kind 5) its coefficients alone, N or, when it
// continues a trajectory component (`trajectory`), 3N. A start's and a
// continued component's first differences are to `before` (cpca_carried).
template <class IO>
void describe_refinement(IO& io, syntax::CpcaCoders& coders, const CpcaMeshPrediction& mesh, const CpcaRefinementHeader& h, bool trajectory,
                         std::array<int64_t, 3> before, std::span<int32_t> translation, std::span<int32_t> basis,
                         std::span<int32_t> coefficients) {
  if (h.kind == kCpcaStart)
    syntax::describe_start(io, coders.start, translation, before);
  else if (h.kind == kCpcaMeshComponent)
    mesh.describe_operator<3>(io, coders.mesh_component, h.cluster, basis, coefficients);
  else if (h.kind == kCpcaTrajectory)
    mesh.describe_operator<1>(io, coders.trajectory, h.cluster, basis, coefficients);
  else if (h.kind == kCpcaContinued)
    syntax::describe_continued(io, coders.continued, trajectory, coefficients, before);
  else
    syntax::describe_operator(io, coders.component, basis, coefficients);
}

// A segment's last value per lane (a translation's 3 axes, a component's
// 1 or 3 coefficient lanes) and its shift: the base of the next segment's
// first differences of the same start or component (docs/codec_cpca_wpt.md,
// "Segments").
struct CpcaCarried {
  std::array<int32_t, 3> last{};
  uint32_t shift = 0;

  std::array<int64_t, 3> at(uint32_t shift_to, int64_t limit) const {
    std::array<int64_t, 3> before{};
    for (size_t l = 0; l < 3; ++l) before[l] = syntax::cpca_carried(last[l], shift, shift_to, limit);
    return before;
  }
  // The last frame's lanes of `values`, `lanes` per frame.
  static CpcaCarried of(std::span<const int32_t> values, size_t lanes, uint32_t shift) {
    CpcaCarried c{{}, shift};
    for (size_t l = 0; l < lanes; ++l) c.last[l] = values[values.size() - lanes + l];
    return c;
  }
};

// The reconstruction's integers (docs/codec_cpca_wpt.md, "Reconstruction"):
// per frame, vertex and axis a 64-bit integer in steps of 2^−F grid units,
// starting at the mean shape's grid index × 2^F (arithmetic modulo 2^64).
// A frame's integers are kept in slots, each cluster's members in member
// order, clusters in order, so that a unit's terms on a frame add to one
// contiguous run. CpcaSlots holds that order, the mean shape in it, and the
// output's conversion to binary32.
class CpcaSlots {
 public:
  // members: each cluster's vertices in member order (cpca_members); every vertex is in one.
  CpcaSlots(const CpcaHeader& header, std::span<const IntPoint3> mean_shape, std::span<const std::vector<NodeIndex>> members);

  size_t vertex_count() const { return slot_of_vertex_.size(); }
  // The mean shape's integers, 3 a slot.
  const std::vector<uint64_t>& mean() const { return mean_; }
  // Where cluster c's values start among a frame's 3 a slot, and how many.
  size_t first_value(uint32_t cluster) const { return 3 * first_slot_[cluster]; }
  size_t value_count(uint32_t cluster) const { return 3 * (first_slot_[cluster + 1] - first_slot_[cluster]); }
  size_t largest_cluster() const { return largest_; }

  // The position of `values` (3 integers).
  Float3 position(const uint64_t* values) const;
  // The positions of the slots from `first_slot` on, given their integers, into their vertices.
  void convert(const uint64_t* values, size_t first_slot, size_t slots, std::span<Float3> positions) const;
  // The same, the integers in cpca_blocked's order.
  void convert_blocked(const uint64_t* values, size_t first_slot, size_t slots, std::span<Float3> positions) const;
  NodeIndex slot_of(NodeIndex v) const { return slot_of_vertex_[v]; }

 private:
  std::vector<NodeIndex> vertex_of_slot_, slot_of_vertex_;
  std::vector<size_t> first_slot_;  // per cluster, then the vertex count
  size_t largest_ = 0;
  std::vector<uint64_t> mean_;
  std::array<double, 3> origin_, unit_;  // unit: the grid step × 2^−F
};

// One refinement's terms on one frame's run of a cluster's integers (3 a
// member): run[3i + a] += scale(b × w) with b = basis[3i + a], w = lanes[a]
// (a component: the three lanes equal), or with `trajectory` b = basis[i];
// `subtract` takes them away. |basis| ≤ 2^15, |lanes| ≤ 2^23.
void cpca_add_terms(std::span<uint64_t> run, std::span<const int32_t> basis, const std::array<int64_t, 3>& lanes, uint32_t shift,
                    bool trajectory, bool subtract = false);

// A cluster's values in blocks (CpcaTermSum): each whole block of
// kCpcaBlock members axis by axis (x of its members, then y, then z), the
// members after the last whole block as they were (3 a member).
inline constexpr size_t kCpcaBlock = 4;
template <class T>
void cpca_blocked(const T* values, size_t members, T* blocked) {
  size_t i = 0;
  for (; i + kCpcaBlock <= members; i += kCpcaBlock)
    for (size_t m = 0; m < kCpcaBlock; ++m)
      for (size_t axis = 0; axis < 3; ++axis) blocked[3 * i + kCpcaBlock * axis + m] = values[3 * (i + m) + axis];
  std::copy(values + 3 * i, values + 3 * members, blocked + 3 * i);
}

// A segment's terms on a cluster, summed a frame at a time and a block at
// a time with every term in SIMD lanes (CpcaSegment::frames): each value
// is loaded and stored once, not once a term, and a trajectory
// component's basis value meets the three axes' coefficients with no
// shuffle. The terms' values stay with their owner (CpcaSegment).
class CpcaTermSum {
 public:
  CpcaTermSum();
  // No terms.
  void clear();
  // A start: translation[3n + a] on frame n, axis a.
  void translate(const int32_t* translation, uint32_t shift);
  // A component's terms, as cpca_add_terms adds them on frame n with lanes coefficients[n] (trajectory:
  // coefficients[3n + a]); `blocked` is basis in cpca_blocked's order (a trajectory's basis is its own), `count`
  // values, and largest_basis the greatest |basis value|.
  void add(const int32_t* basis, const int32_t* blocked, size_t count, const int32_t* coefficients, uint32_t shift, bool trajectory,
           int32_t largest_basis);
  // Frame n's run of the cluster's `members` members, in cpca_blocked's order: mean + translations + terms.
  void sum(uint32_t n, const uint64_t* mean, size_t members, uint64_t* run);

 private:
  // The whole blocks' sums; returns how many members they took.
  size_t sum_blocks(const uint64_t* mean, size_t members, uint64_t* run, bool narrow, bool paired) const;
  // Whether frame n's terms and every partial sum of them fit in int32 (the narrow loops'); fills their
  // narrow coefficients.
  bool narrow_on(uint32_t n);
  // After narrow_on: whether frame n's coefficients of the paired terms, shifted left by their −u, fit in
  // int16; fills the term pairs' coefficients.
  bool term_pairs_on(uint32_t n);

  // A term: its values, u, and as the vector loops take it, frame n's coefficient per axis (int64 with AVX2,
  // binary64's bits with SSE2, four int32 with SIMD128), what is added before the shift, and the shift; for
  // the narrow loops, frame n's coefficient of the axes x, y, z, x, y, z four times each (the axes of two
  // blocks' values) and the rounding half.
  struct Lanes {
    const int32_t* basis;
    const int32_t* blocked;
    const int32_t* coefficients;
    int u;
    int32_t largest_basis;
#ifdef __wasm_simd128__
    alignas(16) std::array<int32_t, 4> coefficient[3];  // a splat in memory: LLVM 14 then keeps i64x2.extmul
#else
    std::array<uint64_t, 3> coefficient;
#endif
    uint64_t before, right, left;
    alignas(32) std::array<int32_t, 6 * kCpcaBlock> narrow;
    int32_t half;
  };
  // Two terms of one kind with u ≤ 0 and |basis| < 2^15 (lanes_[·][kPaired][2p] and [2p + 1] of pair p): where
  // frame n's coefficients shifted left by −u fit in int16 too, each int32 lane takes both terms' products
  // and their sum in one multiply-add of int16 halves (the first term's low), exact: b₁ · (w₁ · 2^−u₁) +
  // b₂ · (w₂ · 2^−u₂) is the sum of their terms.
  struct TermPair {
    std::vector<int32_t> basis;                            // both terms' basis values as halves, in `blocked`'s order
    alignas(32) std::array<int32_t, 6 * kCpcaBlock> narrow;  // frame n's shifted coefficients as halves, axes as Lanes::narrow's
  };
  static constexpr size_t kUnrounded = 0, kRounded = 1, kPaired = 2;
  [[maybe_unused]] bool integer_ = false;  // products in int64 lanes (AVX2, WebAssembly SIMD128), else binary64
  std::vector<std::pair<const int32_t*, int>> starts_;  // translations and u
  std::array<uint64_t, 3> offset_{};                      // frame n's translations
  uint64_t after_ = 0;                                    // what the vector loops' rounded terms add beyond their values: 2^(63 − u) each
  std::vector<Lanes> lanes_[2][3];                        // per trajectory (1) or not (0), then kUnrounded (u ≤ 0), kRounded, kPaired
  std::vector<TermPair> term_pairs_[2];                   // per trajectory
  std::array<size_t, 2> unpaired_{};                      // per trajectory: 1 + the index in kUnrounded of a term that pairs, else 0
};

// A segment's frames as decoded so far, every integer kept: refinements add
// to them at once and can be undone exactly (the encoder's analysis).
class CpcaAnimation {
 public:
  CpcaAnimation(const CpcaHeader& header, std::span<const IntPoint3> mean_shape, std::span<const std::vector<NodeIndex>> members,
                uint32_t frames);

  uint32_t frames() const { return frames_; }

  // Adds round(translation[3n + a] × 2^−(shift − 16)) to frame n, axis a
  // of every member of `cluster` (its start); `undo` subtracts the same terms.
  void translate(uint32_t cluster, std::span<const int32_t> translation, uint32_t shift, bool undo = false);
  // Adds round(basis[3i + a] × coefficients[n] × 2^−(shift − 16)) to
  // frame n, member i of `cluster`, axis a (|basis| ≤ 2^15, |coefficients| ≤ 2^23).
  // With `trajectory`, basis[i] × coefficients[3n + a] instead; `undo` subtracts the same terms.
  void refine(uint32_t cluster, std::span<const int32_t> basis, std::span<const int32_t> coefficients, uint32_t shift, bool trajectory = false,
              bool undo = false);

  Float3 position(uint32_t f, NodeIndex v) const;
  void frame(uint32_t f, std::span<Float3> positions) const;

 private:
  CpcaSlots slots_;
  uint32_t frames_;
  std::vector<uint64_t> fixed_;  // frame-major, then slot, then axis
};

// A segment's refinements as decoded, cluster by cluster, and its frames
// summed from them one frame at a time when asked for (the decoder: a
// frame's integers never outlive it, and the terms of a cluster meet in
// the cache). The same integers as CpcaAnimation's: the terms add modulo 2^64.
class CpcaSegment {
 public:
  CpcaSegment(const CpcaHeader& header, std::span<const IntPoint3> mean_shape, std::span<const std::vector<NodeIndex>> members,
              uint32_t frames);
  CpcaSegment(const CpcaSegment&) = delete;  // sums_ points into terms_
  CpcaSegment& operator=(const CpcaSegment&) = delete;

  uint32_t frames() const { return frames_; }
  // CpcaAnimation::translate and refine, kept to be summed.
  void translate(uint32_t cluster, std::vector<int32_t> translation, uint32_t shift);
  void refine(uint32_t cluster, std::shared_ptr<const std::vector<int32_t>> basis, std::vector<int32_t> coefficients, uint32_t shift,
              bool trajectory);
  // No refinement, in `frames` frames (the next segment's).
  void reset(uint32_t frames);

  void frame(uint32_t f, std::span<Float3> positions) const;
  // Frames first, first + 1, … into positions[0], [1], …, the same as frame() on each.
  void frames(uint32_t first, std::span<const std::span<Float3>> positions) const;
  // A frame no refinement has reached: the mean shape.
  void mean_frame(std::span<Float3> positions) const;

 private:
  // A refinement's values, which sums_ points into.
  struct Term {
    std::shared_ptr<const std::vector<int32_t>> basis;  // none for a start
    std::vector<int32_t> values;                        // a start's translations, else the coefficients
    std::vector<int32_t> blocked;                       // a component's basis in cpca_blocked's order (a trajectory's is its own)
  };

  CpcaSlots slots_;
  std::vector<uint64_t> blocked_mean_;  // the mean shape's integers, each cluster in cpca_blocked's order
  uint32_t frames_;
  std::vector<std::vector<Term>> terms_;  // per cluster, in the order decoded
  mutable std::vector<uint64_t> run_;     // one cluster's integers of the frame being summed
  mutable std::vector<CpcaTermSum> sums_;  // per cluster
};

}  // namespace m4mesh
