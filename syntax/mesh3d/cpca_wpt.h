// The clustered-PCA codec with weighted progressive transmission
// (codec_id 4) syntax (docs/codec_cpca_wpt.md): the codec header with the
// cluster of every vertex, and a refinement unit's data: a cluster's start
// (its mean trajectory) or one of its operators (basis, singular value and
// coefficients folded into two integer vectors and a shift).
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "common/bit_cast.h"
#include "syntax/io.h"
#include "syntax/mesh3d/container.h"
#include "syntax/mesh3d/entropy_io.h"
#include "syntax/mesh3d/grid.h"
#include "syntax/mesh3d/residual.h"

namespace m4mesh {

inline constexpr uint32_t kCpcaMaxClusters = 255;
inline constexpr uint32_t kCpcaMaxFractionBits = 16;
// How the cluster map is coded (cluster_map_prediction): each
// vertex's cluster as its difference to the previous vertex's, or ranked
// by the clusters of its neighbours numbered before it (read once the base
// mesh has given the faces).
inline constexpr uint32_t kCpcaMapByDifference = 0;
inline constexpr uint32_t kCpcaMapByNeighbours = 1;
// The shift of a refinement is stored plus this bias: contributions are
// (basis × coefficient) × 2^−(shift − bias).
inline constexpr uint32_t kCpcaShiftBias = 16;
inline constexpr uint32_t kCpcaMaxShift = 63;
inline constexpr int32_t kCpcaMaxBasis = int32_t{1} << 15;        // |basis value| ≤ 2^15
inline constexpr int32_t kCpcaMaxCoefficient = int32_t{1} << 23;  // |coefficient| ≤ 2^23
inline constexpr int32_t kCpcaMaxTranslation = int32_t{1} << 29;  // |translation| ≤ 2^29
inline constexpr uint32_t kCpcaStart = 0;      // unit_kind: the cluster's mean trajectory
inline constexpr uint32_t kCpcaComponent = 1;  // unit_kind: one principal component
inline constexpr uint32_t kCpcaMeshComponent = 2;  // unit_kind: one, its basis predicted over the base mesh
inline constexpr uint32_t kCpcaTrajectory = 3;     // unit_kind: one of the members' trajectories, predicted over the base mesh
inline constexpr uint32_t kCpcaGroup = 4;          // unit_kind: several refinements of kinds 0 … 3 and 5 in one unit
inline constexpr uint32_t kCpcaContinued = 5;      // unit_kind: a component of the previous segment, with new coefficients
inline constexpr uint32_t kCpcaMaxGroupSize = 255;
// A unit_kind as tools name it.
inline const char* cpca_unit_kind_name(uint32_t kind) {
  static constexpr const char* kNames[] = {"start", "component", "mesh component", "trajectory component", "group", "continued component"};
  return kind <= kCpcaContinued ? kNames[kind] : "unknown";
}
// The decoder holds 24 bytes per vertex and frame of a segment, and the
// bases of two segments: at most 2^22 vertex-frames.

inline constexpr uint64_t kCpcaMaxVertexFrames = uint64_t{1} << 22;

struct CpcaHeader {
  uint32_t bits = 12;  // the grid of the base mesh (the mean shape)
  std::array<uint32_t, 3> origin{};  // binary32 bit patterns
  std::array<uint32_t, 3> step{};
  uint32_t cluster_count = 1;
  uint32_t fraction_bits = 8;  // F: positions accumulate in steps of 2^−F grid units
  uint32_t map_prediction = kCpcaMapByDifference;
  uint32_t segment_frames = 1;
  uint32_t map_bins_bytes = 0;
  std::span<const uint8_t> map_bins;
  uint32_t map_raw_bytes = 0;
  std::span<const uint8_t> map_raw;

  float origin_value(int axis) const { return bit_cast<float>(origin[axis]); }
  float step_value(int axis) const { return bit_cast<float>(step[axis]); }
};

// One refinement: the cluster it refines, what it carries (unit_kind 0 … 3)
// and the shift.
struct CpcaRefinementHeader {
  uint32_t cluster = 0;
  uint32_t kind = kCpcaComponent;
  uint32_t shift = kCpcaShiftBias;
  uint32_t reference = 0;  // unit_kind 5: the component continued, in the cluster's list of the previous segment
};

// A refinement unit's data: one refinement, or a group of them (unit_kind
// 4, its own cluster and shift 0), the bin section's length, the bins and
// the raw bits.
struct CpcaRefinement {
  uint32_t cluster = 0;
  uint32_t kind = kCpcaComponent;
  uint32_t shift = kCpcaShiftBias;
  std::vector<CpcaRefinementHeader> group;
  uint32_t arithmetic_bytes = 0;
  std::span<const uint8_t> bins;
  std::span<const uint8_t> raw;
  uint32_t reference = 0;  // unit_kind 5

  // The refinements the unit carries, in order.
  std::vector<CpcaRefinementHeader> refinements() const {
    return kind == kCpcaGroup ? group : std::vector<CpcaRefinementHeader>{{cluster, kind, shift, reference}};
  }
};

namespace syntax {

inline constexpr ResidualNames kCpcaCluster = M4MESH_RESIDUAL_NAMES("cluster", "cluster_of_vertex");
inline constexpr ResidualNames kCpcaBasis = M4MESH_RESIDUAL_NAMES("basis", "basis");
inline constexpr ResidualNames kCpcaCoefficient = M4MESH_RESIDUAL_NAMES("coefficient", "coefficient");
inline constexpr ResidualNames kCpcaMeshBasis = M4MESH_RESIDUAL_NAMES("mesh_basis", "mesh_basis");
inline constexpr ResidualNames kCpcaTrajectoryBasis = M4MESH_RESIDUAL_NAMES("trajectory_basis", "trajectory_basis");
inline constexpr ResidualNames kCpcaTrajectoryCoefficient = M4MESH_RESIDUAL_NAMES("trajectory_coefficient", "trajectory_coefficient");
inline constexpr ResidualNames kCpcaTranslation = M4MESH_RESIDUAL_NAMES("translation", "translation");
inline constexpr ResidualNames kCpcaContinuedCoefficient = M4MESH_RESIDUAL_NAMES("continued_coefficient", "continued_coefficient");
inline constexpr int kCpcaCoefficientChannel = 3;  // the basis uses 0 … 2 (x, y, z)

template <class IO>
void describe(IO& io, CpcaHeader& h) {
  io.field_in("quantization_bits", 8, h.bits, 4, 24);
  describe_grid(io, h.origin, h.step);
  io.field_in("cluster_count", 8, h.cluster_count, 1, kCpcaMaxClusters);
  io.field_in("fraction_bits", 8, h.fraction_bits, 0, kCpcaMaxFractionBits);
  io.field_in("cluster_map_prediction", 8, h.map_prediction, kCpcaMapByDifference, kCpcaMapByNeighbours);
  io.field_in("segment_frames", 32, h.segment_frames, 1, UINT32_MAX);
  io.field("cluster_map_bins_bytes", 32, h.map_bins_bytes);
  io.require_length("cluster_map_bins_bytes", h.map_bins_bytes);
  io.section("cluster_map_bins", h.map_bins_bytes, h.map_bins);
  io.field("cluster_map_raw_bytes", 32, h.map_raw_bytes);
  io.require_length("cluster_map_raw_bytes", h.map_raw_bytes);
  io.section("cluster_map_raw", h.map_raw_bytes, h.map_raw);
}

// `check` sees the unit's own refinement (unit_kind 0 … 3 and 5) as soon
// as its fields are read; a group's list is read with its symbols
// (describe_group_list).
template <class IO, class Check>
void describe(IO& io, CpcaRefinement& r, Check&& check) {
  io.field_in("cluster", 8, r.cluster, 0, kCpcaMaxClusters - 1);
  io.field_in("unit_kind", 8, r.kind, kCpcaStart, kCpcaContinued);
  io.field_in("shift", 8, r.shift, 0, kCpcaMaxShift);
  if (r.kind == kCpcaContinued || kTableOf<IO>) {
    if constexpr (kTableOf<IO>) io.open("if (unit_kind == 5)");
    io.field("reference", 32, r.reference);
    if constexpr (kTableOf<IO>) io.close();
  }
  if (r.kind == kCpcaGroup || kTableOf<IO>) {
    if constexpr (kTableOf<IO>) io.open("if (unit_kind == 4)");
    io.require(r.cluster == 0, ErrorKind::kStructure, "cluster", "a group's cluster field is not 0");
    io.require(r.shift == 0, ErrorKind::kStructure, "shift", "a group's shift field is not 0");
    uint32_t size = static_cast<uint32_t>(r.group.size());
    io.field_in("group_size", 8, size, 1, kCpcaMaxGroupSize);
    io.resize(r.group, size, "group_size", 1);  // each refinement takes at least a bit of the symbols
    if constexpr (kTableOf<IO>) io.close();
  } else {
    check(CpcaRefinementHeader{r.cluster, r.kind, r.shift, r.reference}, false);
  }
  io.field("arithmetic_bytes", 32, r.arithmetic_bytes);
  io.require_length("arithmetic_bytes", r.arithmetic_bytes);
  io.section("bins", r.arithmetic_bytes, r.bins);
  io.tail_section("raw", r.raw);
}

template <class IO>
void describe(IO& io, CpcaRefinement& r) {
  describe(io, r, [](const CpcaRefinementHeader&, bool) {});
}

// values[j] as the difference to values[j − stride] (`before` for the
// first stride), on channel first_channel + j mod stride, each within
// [lo, hi] (else out-of-range, named names.element).
template <class IO, int kChannels>
void describe_differences(IO& io, ResidualCoder<kChannels>& coder, std::span<int32_t> values, int first_channel, size_t stride, int64_t lo,
                          int64_t hi, const ResidualNames& names, const char* beyond, std::array<int64_t, 3> before = {}) {
  std::array<int64_t, 3> previous = before;
  for (size_t j = 0; j < values.size(); ++j) {
    const size_t lane = j % stride;
    int32_t difference = 0;
    if constexpr (!IO::kReading) difference = static_cast<int32_t>(int64_t{values[j]} - previous[lane]);
    coder.describe(io, first_channel + static_cast<int>(lane), difference, names);
    const int64_t value = previous[lane] + difference;
    if (value < lo || value > hi) io.fail(ErrorKind::kOutOfRange, names.element, beyond);
    values[j] = static_cast<int32_t>(value);
    previous[lane] = value;
  }
}

// The cluster of every vertex in index order, each coded as the difference
// to the previous vertex's (the first to 0); every cluster below
// cluster_count.
template <class IO>
void describe_cluster_map(IO& io, std::span<uint32_t> cluster_of, uint32_t cluster_count) {
  ResidualCoder<1> coder;
  // A signed view of the same values (the aliasing rules allow it; clusters are below 255).
  const std::span<int32_t> clusters(reinterpret_cast<int32_t*>(cluster_of.data()), cluster_of.size());
  describe_differences(io, coder, clusters, 0, 1, 0, int64_t{cluster_count} - 1, kCpcaCluster, "a cluster beyond cluster_count");
}

// The contexts of cluster_map_prediction 1, starting at the map.
struct CpcaRankContexts {
  BinContext not_first[3];   // by min(candidates, 3) − 1
  BinContext not_second[2];  // by min(candidates, 3) − 2
};

// One vertex's cluster under cluster_map_prediction 1. Its earlier
// neighbours hold `candidates` clusters (at least 1), `first` and `second`
// the two most frequent (`second` with 2 or more); any other cluster is
// named by its rank among the clusters left, in increasing number.
template <class IO>
void describe_ranked_cluster(IO& io, CpcaRankContexts& c, uint32_t candidates, uint32_t first, uint32_t second, uint32_t cluster_count,
                             uint32_t& cluster) {
  const uint32_t shown = std::min<uint32_t>(candidates, 3);
  bool not_first = cluster != first;
  io.bin("cluster_not_first", c.not_first[shown - 1], static_cast<int>(shown - 1), not_first);
  if (!not_first) {
    cluster = first;
    return;
  }
  uint32_t low = first, high = first;
  if (candidates >= 2) {
    bool not_second = cluster != second;
    io.bin("cluster_not_second", c.not_second[shown - 2], static_cast<int>(shown - 2), not_second);
    if (!not_second) {
      cluster = second;
      return;
    }
    low = std::min(first, second);
    high = std::max(first, second);
  }
  const uint32_t left_out = low == high ? 1 : 2;
  if (cluster_count <= left_out) io.fail(ErrorKind::kOutOfRange, "cluster_rank", "no cluster left to name");
  uint32_t rank = 0;
  if constexpr (!IO::kReading) rank = cluster - (cluster > low ? 1 : 0) - (left_out == 2 && cluster > high ? 1 : 0);
  io.raw("cluster_rank", std::bit_width(cluster_count - left_out - 1), rank);
  if (rank >= cluster_count - left_out) io.fail(ErrorKind::kOutOfRange, "cluster_rank", "a rank beyond the clusters left");
  if constexpr (IO::kReading) {
    cluster = rank;
    if (cluster >= low) ++cluster;
    if (left_out == 2 && cluster >= high) ++cluster;
  }
}

// The residual coders of a refinement unit, one per refinement kind: they
// start afresh in every unit, and a group's refinements of one kind
// continue the same coder.
struct CpcaCoders {
  ResidualCoder<3> start;
  ResidualCoder<4> component;
  ResidualCoder<7> mesh_component;  // 2D + 3/D channels, D = 3
  ResidualCoder<5> trajectory;      // D = 1
  ResidualCoder<4> continued;       // channel 0: a shape component's coefficients, 1 … 3: a trajectory component's lanes
};

inline constexpr ResidualNames kCpcaGroupShift = M4MESH_RESIDUAL_NAMES("group_shift", "group_shift");

// The contexts of a group's list, fresh in every unit.
struct CpcaGroupContexts {
  BinContext trajectory, mesh, continued;
  ResidualCoder<2> shift;  // channel 0: starts, 1: components
};

// A group's list, first in its unit's arithmetic-coded section. Each
// refinement's cluster in bit_width(cluster_count − 1) raw bits (below
// cluster_count); its kind a start when started(cluster) is false, else,
// when previous(cluster) (the cluster's components in the
// previous segment) is not 0, a continued component (bin group_continued,
// then the component's place in that list, raw bits below previous), else
// a trajectory component (bin group_trajectory), a component over the mesh
// (bin group_mesh) or a component; its shift the difference to the
// previous shift of its class in the list (starts, components; 16 before
// the first), 0 … 63. `check` sees each refinement as soon as it is read;
// it is what makes started() true for a cluster the group starts.
template <class IO, class Started, class Previous, class Check>
void describe_group_list(IO& io, CpcaGroupContexts& c, std::span<CpcaRefinementHeader> group, uint32_t cluster_count, Started&& started,
                         Previous&& previous, Check&& check) {
  const int cluster_bits = std::bit_width(cluster_count - 1);
  std::array<int64_t, 2> previous_shift{kCpcaShiftBias, kCpcaShiftBias};
  for (CpcaRefinementHeader& h : group) {
    if (cluster_bits > 0)
      io.raw("group_cluster", cluster_bits, h.cluster);
    else if constexpr (IO::kReading)
      h.cluster = 0;
    if (h.cluster >= cluster_count)
      io.fail(ErrorKind::kOutOfRange, "group_cluster", "cluster " + std::to_string(h.cluster) + " of " + std::to_string(cluster_count));
    const bool start = !started(h.cluster);
    if constexpr (!IO::kReading)
      if (start != (h.kind == kCpcaStart)) io.fail(ErrorKind::kStructure, "group_kind", "a start only, and only, of a cluster not started");
    if (!start) {
      const uint32_t continuable = previous(h.cluster);
      bool continued = h.kind == kCpcaContinued;
      if (continuable > 0) io.bin("group_continued", c.continued, 0, continued);
      if (continued) {
        io.raw("group_reference", std::bit_width(continuable - 1), h.reference);
        if (h.reference >= continuable)
          io.fail(ErrorKind::kOutOfRange, "group_reference",
                  "component " + std::to_string(h.reference) + " of the " + std::to_string(continuable) + " the previous segment sent");
        if constexpr (IO::kReading) h.kind = kCpcaContinued;
      } else {
        bool trajectory = h.kind == kCpcaTrajectory;
        io.bin("group_trajectory", c.trajectory, 0, trajectory);
        bool mesh = h.kind == kCpcaMeshComponent;
        if (!trajectory) io.bin("group_mesh", c.mesh, 0, mesh);
        if constexpr (IO::kReading) h.kind = trajectory ? kCpcaTrajectory : mesh ? kCpcaMeshComponent : kCpcaComponent;
      }
    } else if constexpr (IO::kReading) {
      h.kind = kCpcaStart;
    }
    const int lane = start ? 0 : 1;
    int32_t difference = static_cast<int32_t>(int64_t{h.shift} - previous_shift[lane]);
    c.shift.describe(io, lane, difference, kCpcaGroupShift);
    const int64_t shift = previous_shift[lane] + difference;
    if (shift < 0 || shift > kCpcaMaxShift) io.fail(ErrorKind::kOutOfRange, "group_shift", "a shift beyond 0 … 63");
    h.shift = static_cast<uint32_t>(shift);
    previous_shift[lane] = shift;
    check(h, true);
  }
}

// The element a refinement's end-of-section errors name.
inline const char* cpca_last_element(uint32_t kind) {
  return kind == kCpcaStart        ? "translation"
         : kind == kCpcaTrajectory ? "trajectory_coefficient"
         : kind == kCpcaContinued  ? "continued_coefficient"
                                   : "coefficient";
}

// An operator's symbols: the basis value of each member vertex and axis
// (members in index order, x, y, z), each as the difference to the same
// axis of the member before (the first to 0), then the coefficient of
// every frame as the difference to the frame before's (the first to 0);
// |basis| ≤ 2^15, |coefficient| ≤ 2^23.
template <class IO>
void describe_operator(IO& io, ResidualCoder<4>& coder, std::span<int32_t> basis, std::span<int32_t> coefficients) {
  describe_differences(io, coder, basis, 0, 3, -kCpcaMaxBasis, kCpcaMaxBasis, kCpcaBasis, "a basis value beyond ±2^15");
  describe_differences(io, coder, coefficients, kCpcaCoefficientChannel, 1, -kCpcaMaxCoefficient, kCpcaMaxCoefficient, kCpcaCoefficient,
                       "a coefficient beyond ±2^23");
}

// A start's symbols: the cluster's translation of every frame and axis
// (frame 0's x, y, z, then frame 1's, …), each as the difference to the
// same axis of the frame before (the first to `before`: 0, or the previous
// segment's last, cpca_carried); |translation| ≤ 2^29.
template <class IO>
void describe_start(IO& io, ResidualCoder<3>& coder, std::span<int32_t> translation, std::array<int64_t, 3> before = {}) {
  describe_differences(io, coder, translation, 0, 3, -kCpcaMaxTranslation, kCpcaMaxTranslation, kCpcaTranslation,
                       "a translation beyond ±2^29", before);
}

// A continued component's symbols (unit_kind 5): its coefficients alone,
// each frame's as the difference to the frame before's (the first to
// `before`, the component's last in the previous segment, cpca_carried):
// one per frame on channel 0 for a component of the shapes, three per
// frame (lanes x, y, z) on channels 1 … 3 for a trajectory component;
// |coefficient| ≤ 2^23.
template <class IO>
void describe_continued(IO& io, ResidualCoder<4>& coder, bool trajectory, std::span<int32_t> coefficients, std::array<int64_t, 3> before) {
  describe_differences(io, coder, coefficients, trajectory ? 1 : 0, trajectory ? 3 : 1, -kCpcaMaxCoefficient, kCpcaMaxCoefficient,
                       kCpcaContinuedCoefficient, "a coefficient beyond ±2^23", before);
}

// A segment's last value of a translation or coefficient lane, coded at
// shift `from`, as the first difference's base of the next segment's at
// shift `to`: value × 2^(to − from), halves rounded up, within ±limit
// (|value| ≤ 2^29).
inline int64_t cpca_carried(int64_t value, uint32_t from, uint32_t to, int64_t limit) {
  const int d = static_cast<int>(to) - static_cast<int>(from);
  int64_t r = 0;
  if (d > 30)
    r = value > 0 ? limit : value < 0 ? -limit : 0;
  else if (d >= 0)
    r = value * (int64_t{1} << d);
  else
    r = (value + (int64_t{1} << (-d - 1))) >> -d;
  return std::clamp(r, -limit, limit);
}

}  // namespace syntax

}  // namespace m4mesh
