// The clustered-PCA codec's streams (docs/codec_cpca_wpt.md) and those to reject.
#include <algorithm>
#include <bit>
#include <functional>
#include <optional>

#include "conformance/suite3d/cases.h"
#include "conformance/suite3d/fit_readings.h"
#include "conformance/suite3d/inputs.h"
#include "conformance/suite3d/stream_edits.h"
#include "decoder/mesh3d/container_decoder.h"
#include "decoder/mesh3d/cpca_wpt.h"
#include "encoder/mesh3d/base_mesh.h"
#include "mesh3d/cpca_wpt.h"
#include "syntax/mesh3d/cpca_wpt.h"
#include "syntax/mesh3d/entropy_io.h"

namespace m4mesh::suite3d {

size_t refinement_unit(const ContainerParts& parts, size_t n) {
  for (size_t k = 0; k < parts.units.size(); ++k)
    if (unit_header_of(parts.units[k].payload).type() == UnitType::kRefinement && n-- == 0) return k;
  throw Error(ErrorKind::kStructure, "", kNoPlane, kNoOffset, "suite: no such refinement unit");
}

FieldBytes refinement_field(const char* name) { return unit_field<CpcaRefinement>(name); }

std::vector<uint8_t> refinement_unit_bytes(CpcaRefinement r, syntax::EntropyWriteIO<false>& symbols, uint32_t frame) {
  const std::vector<uint8_t> bins = symbols.finish_bins(), raw = symbols.finish_raw();
  r.arithmetic_bytes = static_cast<uint32_t>(bins.size());
  r.bins = bins;
  r.raw = raw;
  BitWriter writer;
  syntax::WriteIO io(writer);
  UnitHeader header{static_cast<uint32_t>(UnitType::kRefinement), frame};
  syntax::describe(io, header);
  syntax::describe(io, r);
  return writer.take_bytes();
}

std::vector<uint8_t> refinement_bytes(uint32_t cluster, uint32_t kind, uint32_t shift, syntax::EntropyWriteIO<false>& symbols, uint32_t frame) {
  return refinement_unit_bytes(CpcaRefinement{cluster, kind, shift, {}, 0, {}, {}}, symbols, frame);
}

// The encoder's stream of `s` in one cluster, without hash units: what the
// streams written symbol by symbol start from.
ContainerParts cpca_one_cluster_parts(const MeshSequence& s) {
  Encode3dOptions o = cpca({{"clusters", "1"}});
  o.hashes = false;
  return split_container(encode_mesh3d(s, o).stream);
}

// The start of a clustered-PCA stream written symbol by symbol: the object
// header and base mesh of `parts` (cpca_one_cluster_parts()), the header's
// cluster map replaced by `cluster_of` (and F by `fraction_bits` when
// given); refinement units follow. The base mesh's positions (base_mesh_of)
// predict the components over the mesh.
ContainerWriter cpca_written_start(ContainerParts parts, const std::vector<uint32_t>& cluster_of, uint32_t clusters,
                                   std::optional<uint32_t> fraction_bits, std::optional<uint32_t> segment_frames) {
  auto [object, header] = read_headers<CpcaHeader>(parts);
  header.cluster_count = clusters;
  header.map_prediction = kCpcaMapByDifference;
  if (fraction_bits) header.fraction_bits = *fraction_bits;
  if (segment_frames) header.segment_frames = *segment_frames;
  std::vector<uint8_t> map_bins, map_raw;
  write_cluster_map<false>(header, {}, cluster_of, map_bins, map_raw, syntax::SectionPlace{});
  BitWriter payload;
  syntax::WriteIO out(payload);
  syntax::describe(out, object);
  syntax::describe(out, header);
  ContainerWriter writer;
  writer.object(payload.take_bytes());
  writer.unit(unit_of(parts, UnitType::kBaseMesh, 0).payload);
  return writer;
}

namespace {

uint32_t unit_kind(const ContainerUnit& unit) { return static_cast<uint32_t>(field_value(unit.payload, refinement_field("unit_kind"))); }
bool is_refinement(const ContainerUnit& unit) { return unit_header_of(unit.payload).type() == UnitType::kRefinement; }

// A group unit (unit_kind 4) of these refinements: its list in bins, of
// clusters `started` tells (the list's starts set it), then the symbols
// `data` writes.
std::vector<uint8_t> group_bytes(std::vector<CpcaRefinementHeader> group, std::vector<uint8_t>& started,
                                 const std::function<void(syntax::EntropyWriteIO<false>&)>& data) {
  syntax::EntropyWriteIO<false> symbols(syntax::SectionPlace{});
  syntax::CpcaGroupContexts contexts;
  syntax::describe_group_list(
      symbols, contexts, std::span(group), static_cast<uint32_t>(started.size()), [&](uint32_t cluster) { return started.at(cluster) != 0; },
      [](uint32_t) { return 0u; },
      [&](const CpcaRefinementHeader& h, bool) {
        if (h.kind == kCpcaStart) started.at(h.cluster) = 1;
      });
  data(symbols);
  return refinement_unit_bytes(CpcaRefinement{0, kCpcaGroup, 0, std::move(group), 0, {}, {}}, symbols);
}

// A group unit's field: `group_size`.
FieldBytes group_field(const char* name) {
  UnitHeader header;
  CpcaRefinement group{0, kCpcaGroup, 0, std::vector<CpcaRefinementHeader>(1), 0, {}, {}};
  return field_bytes(name, header, group);
}

// A refinement unit (frame 0, shift 16) whose symbols are the residuals
// given, channel and value, in order: values the encoder's description
// refuses to write, for the decoder to reject.
std::vector<uint8_t> crafted_refinement(uint32_t cluster, uint32_t kind, const std::vector<std::pair<int, int32_t>>& residuals) {
  syntax::ResidualCoder<7> coder;  // the most channels of a unit kind (2)
  syntax::EntropyWriteIO<false> symbols(syntax::SectionPlace{});
  for (auto [channel, value] : residuals) coder.describe(symbols, channel, value, syntax::kCpcaBasis);
  return refinement_bytes(cluster, kind, kCpcaShiftBias, symbols);
}

// What a rewritten clustered-PCA header starts from: the stream's map and
// its base mesh's faces (which predict a map by neighbours).
struct CpcaMap {
  std::vector<uint32_t> cluster_of;
  std::vector<Triangle> faces;
};

// `stream` with its clustered-PCA header rewritten: `edit` changes the
// header and writes the cluster map's sections.
std::vector<uint8_t> with_cpca_header(const std::vector<uint8_t>& stream,
                                      const std::function<void(CpcaHeader&, const CpcaMap&, std::vector<uint8_t>&, std::vector<uint8_t>&)>& edit) {
  return edited(stream, [&](ContainerParts& parts) {
    auto [object, header] = read_headers<CpcaHeader>(parts);
    std::vector<uint8_t> bins, raw;
    edit(header, CpcaMap{cpca_cluster_map(parts), base_mesh_of(parts).faces}, bins, raw);
    header.map_bins_bytes = static_cast<uint32_t>(bins.size());
    header.map_bins = bins;
    header.map_raw_bytes = static_cast<uint32_t>(raw.size());
    header.map_raw = raw;
    BitWriter payload;
    syntax::WriteIO out(payload);
    syntax::describe(out, object);
    syntax::describe(out, header);
    parts.object_payload = payload.take_bytes();
  });
}

// The same stream with its cluster map coded by the differences (cluster_map_prediction 0).
std::vector<uint8_t> with_map_by_difference(const std::vector<uint8_t>& stream) {
  return with_cpca_header(stream, [](CpcaHeader& h, const CpcaMap& map, std::vector<uint8_t>& bins, std::vector<uint8_t>& raw) {
    h.map_prediction = kCpcaMapByDifference;
    write_cluster_map<false>(h, {}, map.cluster_of, bins, raw, syntax::SectionPlace{});
  });
}

// A cluster map by neighbours of `clusters` clusters whose first vertex
// (no neighbour before it: one candidate, cluster 0) is not cluster 0 and
// then, with more than one cluster, takes the raw rank `rank`.
std::vector<uint8_t> with_first_rank(const std::vector<uint8_t>& stream, uint32_t clusters, uint32_t rank) {
  return with_cpca_header(stream, [&](CpcaHeader& h, const CpcaMap&, std::vector<uint8_t>& bins, std::vector<uint8_t>& raw) {
    h.map_prediction = kCpcaMapByNeighbours;
    h.cluster_count = clusters;
    syntax::EntropyWriteIO<false> symbols(syntax::SectionPlace{});
    syntax::CpcaRankContexts contexts;
    bool not_first = true;
    symbols.bin("cluster_not_first", contexts.not_first[0], 0, not_first);
    if (clusters > 1) symbols.raw("cluster_rank", std::bit_width(clusters - 2), rank);
    bins = symbols.finish_bins();
    raw = symbols.finish_raw();
  });
}

// A clustered-PCA stream of 2 frames written symbol by symbol (no hash
// units) over a base mesh the encoder wrote: 255 clusters, F = 16, and
// - a cluster map of clusters 0 … 254 in turn, then per pattern of
//   for_each_prefix_pattern() up to e = 7 (cluster differences reach 254)
//   200 vertices of cluster 64 and steps up by the pattern's two values;
// - per pattern p (e up to 13), cluster p's start (shift 17) whose
//   translation on every axis is the pattern's first value in frame 0 and
//   moves by its second in frame 1;
// - cluster 64's component whose basis steps through prefix_schedule() on
//   every axis;
// - per pattern pair 2c, 2c + 1, two components of cluster c whose
//   coefficients step by the pattern's values.
std::vector<uint8_t> cpca_written_stream() {
  constexpr uint32_t kClusters = kCpcaMaxClusters, kQuietCluster = 64;
  std::vector<uint32_t> cluster_of;
  for (uint32_t c = 0; c < kClusters; ++c) cluster_of.push_back(c);
  for_each_prefix_pattern(7, [&](int32_t first, int32_t second) {
    cluster_of.insert(cluster_of.end(), 200, kQuietCluster);
    cluster_of.push_back(kQuietCluster + static_cast<uint32_t>(std::abs(first)));
    cluster_of.push_back(cluster_of.back() + static_cast<uint32_t>(std::abs(second)));
  });
  const int loose = static_cast<int>(cluster_of.size()) - 11;  // designed_loose()'s sheet and box hold 11
  ContainerWriter writer =
      cpca_written_start(cpca_one_cluster_parts(designed_loose(2, loose, [](int, int) { return 0; })), cluster_of, kClusters,
                         kCpcaMaxFractionBits);

  const std::vector<std::vector<NodeIndex>> members = cpca_members(cluster_of, kClusters);
  auto start = [&](uint32_t cluster, std::vector<int32_t> translation) {
    syntax::EntropyWriteIO<false> symbols(syntax::SectionPlace{});
    syntax::CpcaCoders coders;
    syntax::describe_start(symbols, coders.start, translation);
    writer.unit(refinement_bytes(cluster, kCpcaStart, kCpcaShiftBias + 1, symbols));
  };
  auto component = [&](uint32_t cluster, std::vector<int32_t> basis, std::vector<int32_t> coefficients) {
    basis.resize(3 * members[cluster].size());
    syntax::EntropyWriteIO<false> symbols(syntax::SectionPlace{});
    syntax::CpcaCoders coders;
    syntax::describe_operator(symbols, coders.component, basis, coefficients);
    writer.unit(refinement_bytes(cluster, kCpcaComponent, kCpcaShiftBias, symbols));
  };
  std::vector<std::pair<int32_t, int32_t>> patterns;
  for_each_prefix_pattern(13, [&](int32_t first, int32_t second) { patterns.emplace_back(first, second); });
  for (uint32_t c = 0; c < patterns.size(); ++c) {
    const auto [first, second] = patterns[c];
    start(c, {first, first, first, first + second, first + second, first + second});
  }
  start(kQuietCluster, std::vector<int32_t>(6));
  std::vector<int32_t> basis;
  int32_t value = 0;
  for (int32_t step : prefix_schedule()) {
    value += step;
    basis.insert(basis.end(), 3, value);
  }
  component(kQuietCluster, basis, {1, 1});
  for (uint32_t c = 0; 2 * c < patterns.size(); ++c)
    for (uint32_t k = 2 * c; k < std::min<size_t>(2 * c + 2, patterns.size()); ++k)
      component(c, {1, 1, 1}, {patterns[k].first, patterns[k].first + patterns[k].second});
  return writer.finish();
}

// A clustered-PCA stream of 2 frames written symbol by symbol (no hash
// units) with a component of unit_kind 2 (shapes over the mesh) and one of
// unit_kind 3 (trajectories) per cluster below, each carrying the same
// values, over the separate quads of parallelogram_quads() at one place
// and as many vertices in no face:
// - cluster 0, the quads: a component whose basis is 0 at a quad's first
//   three vertices and prefix_schedule()'s next value at its fourth, so
//   that the parallelogram channels carry the schedule;
// - cluster 1, the vertices in no face (each predicted by the one before):
//   a component whose basis steps through prefix_schedule();
// - clusters 2 … 43, one vertex each: per pattern of
//   for_each_prefix_pattern(), a component whose coefficients step by the
//   pattern's values on every lane.
std::vector<uint8_t> cpca_mesh_written_stream() {
  const std::vector<int32_t> schedule = prefix_schedule();
  std::vector<std::pair<int32_t, int32_t>> patterns;
  for_each_prefix_pattern(13, [&](int32_t first, int32_t second) { patterns.emplace_back(first, second); });
  MeshSequence s = parallelogram_quads(std::vector<int32_t>(schedule.size(), 0));
  const uint32_t quads_end = s.vertex_count;
  for (size_t i = 0; i < schedule.size() + patterns.size(); ++i) s.frames[0].push_back({40000.0 + static_cast<double>(i % 64), 40000, 40000});
  s.vertex_count = static_cast<uint32_t>(s.frames[0].size());
  s.frames = {s.frames[0], s.frames[0]};
  std::vector<uint32_t> cluster_of(s.vertex_count, 0);
  for (uint32_t v = quads_end; v < quads_end + schedule.size(); ++v) cluster_of[v] = 1;
  for (uint32_t p = 0; p < patterns.size(); ++p) cluster_of[quads_end + schedule.size() + p] = 2 + p;
  const uint32_t clusters = 2 + static_cast<uint32_t>(patterns.size());

  const ContainerParts start = cpca_one_cluster_parts(s);
  ContainerWriter writer = cpca_written_start(start, cluster_of, clusters, std::nullopt);

  const BaseMeshPlan plan = plan_base_mesh(s.faces, s.vertex_count, false);
  const CpcaMeshPrediction mesh(plan.faces, plan.input_of, cluster_of, clusters, base_mesh_of(start).positions);
  const std::vector<std::vector<NodeIndex>> members = cpca_members(cluster_of, clusters);
  // One value per member (every axis alike), one per frame (every lane alike).
  auto component = [&](uint32_t kind, uint32_t cluster, const std::vector<int32_t>& values, std::pair<int32_t, int32_t> frames) {
    const size_t per_member = kind == kCpcaTrajectory ? 1 : 3;
    std::vector<int32_t> basis, coefficients;
    for (int32_t v : values) basis.insert(basis.end(), per_member, v);
    coefficients.insert(coefficients.end(), 3 / per_member, frames.first);
    coefficients.insert(coefficients.end(), 3 / per_member, frames.second);
    syntax::EntropyWriteIO<false> symbols(syntax::SectionPlace{});
    syntax::CpcaCoders coders;
    if (kind == kCpcaTrajectory)
      mesh.describe_operator<1>(symbols, coders.trajectory, cluster, basis, coefficients);
    else
      mesh.describe_operator<3>(symbols, coders.mesh_component, cluster, basis, coefficients);
    writer.unit(refinement_bytes(cluster, kind, kCpcaShiftBias, symbols));
  };
  for (uint32_t c = 0; c < clusters; ++c) {
    syntax::EntropyWriteIO<false> symbols(syntax::SectionPlace{});
    syntax::CpcaCoders coders;
    std::vector<int32_t> translation(6);
    syntax::describe_start(symbols, coders.start, translation);
    writer.unit(refinement_bytes(c, kCpcaStart, kCpcaShiftBias, symbols));
  }
  std::vector<int32_t> quads(members[0].size(), 0);
  size_t next = 0;
  for (size_t i = 0; i < members[0].size(); ++i)
    if (members[0][i] >= 11 && (members[0][i] - 11) % 4 == 3) quads[i] = schedule[next++];  // a quad's fourth vertex
  std::vector<int32_t> chain;
  int32_t value = 0;
  for (int32_t step : schedule) chain.push_back(value += step);
  for (const uint32_t kind : {kCpcaMeshComponent, kCpcaTrajectory}) {
    component(kind, 0, quads, {1, 1});
    component(kind, 1, chain, {1, 1});
    for (uint32_t p = 0; p < patterns.size(); ++p)
      component(kind, 2 + p, {1}, {patterns[p].first, patterns[p].first + patterns[p].second});
  }
  return writer.finish();
}

// A clustered-PCA stream of 2 frames written symbol by symbol (no hash
// units) that tells the affine fit's binary64 order from each other
// reading of fit_readings.h: per reading, an octahedron whose corners are
// moved by −2 … 2 until values tell it apart at its last member, all in
// one cluster on a 4-bit grid (a grid unit per unit); a start and a
// component of unit_kind 2 and of unit_kind 3, whose values at the points
// of octahedron r's last member tell reading 1 + r apart on every lane;
// every other value is 0.
std::vector<uint8_t> cpca_fit_order_stream() {
  constexpr uint32_t kReadings = kFitReadings - 1, kTries = 20000;
  SplitMix64 random(46);
  MeshSequence s;
  const NodeIndex octahedron[8][3] = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  for (uint32_t r = 0; r < kReadings; ++r)
    for (const auto& f : octahedron) s.faces.push_back({{6 * r + f[0], 6 * r + f[1], 6 * r + f[2]}});
  s.vertex_count = 6 * kReadings + 2;
  std::vector<IntPoint3> positions(s.vertex_count);
  positions[s.vertex_count - 1] = {15, 15, 15};  // with the origin, the grid's box: 15 units on every axis
  const std::vector<uint32_t> cluster_of(s.vertex_count, 0);
  const BaseMeshPlan plan = plan_base_mesh(s.faces, s.vertex_count, false);
  std::vector<int32_t> shapes(3 * size_t{s.vertex_count}), trajectories(s.vertex_count);
  std::vector<uint32_t> points;
  for (uint32_t r = 0; r < kReadings; ++r) {
    const FitReading reading = static_cast<FitReading>(1 + r);
    std::vector<std::vector<int32_t>> lanes;  // unit_kind 2's three, then unit_kind 3's
    while (lanes.size() < 4) {
      const int corners[6][3] = {{2, 0, 0}, {-2, 0, 0}, {0, 2, 0}, {0, -2, 0}, {0, 0, 2}, {0, 0, -2}};
      const int32_t centre[3] = {4 + static_cast<int32_t>(r), 11 - static_cast<int32_t>(r), 4 + static_cast<int32_t>(5 * r % 8)};
      for (int i = 0; i < 6; ++i)
        for (int a = 0; a < 3; ++a) positions[6 * r + i][a] = centre[a] + corners[i][a] + random.uniform(-2, 2);
      const CpcaMeshPrediction mesh(plan.faces, plan.input_of, cluster_of, 1, positions);
      const std::span<const uint32_t> order = mesh.members_in_order(0);
      const uint32_t last = *std::find_if(order.rbegin(), order.rend(), [&](uint32_t v) { return v / 6 == r; });
      mesh.fit_support(last, points);
      std::vector<std::array<int32_t, 3>> q;
      for (const uint32_t u : points)
        q.push_back({positions[u][0] - positions[last][0], positions[u][1] - positions[last][1], positions[u][2] - positions[last][2]});
      lanes.clear();
      while (lanes.size() < 4) {
        std::optional<std::vector<int32_t>> values = values_telling_apart(q, reading, random, kTries);
        if (!values) break;
        lanes.push_back(std::move(*values));
      }
      if (lanes.size() < 4) continue;
      for (size_t i = 0; i < points.size(); ++i) {
        for (size_t a = 0; a < 3; ++a) shapes[3 * size_t{points[i]} + a] = lanes[a][i];
        trajectories[points[i]] = lanes[3][i];
      }
    }
  }
  for (const IntPoint3& p : positions) s.frames.resize(1), s.frames[0].push_back({double(p[0]), double(p[1]), double(p[2])});
  s.frames.push_back(s.frames[0]);

  Encode3dOptions o = cpca({{"clusters", "1"}, {"bits", "4"}});
  o.hashes = false;
  const ContainerParts start = split_container(encode_mesh3d(s, o).stream);
  if (base_mesh_of(start).positions != positions) throw std::logic_error("suite: the fit-order octahedra are not on their grid points");
  ContainerWriter writer = cpca_written_start(start, cluster_of, 1, std::nullopt);
  const CpcaMeshPrediction mesh(plan.faces, plan.input_of, cluster_of, 1, positions);
  syntax::EntropyWriteIO<false> start_symbols(syntax::SectionPlace{});
  syntax::CpcaCoders start_coders;
  std::vector<int32_t> translation(6);
  syntax::describe_start(start_symbols, start_coders.start, translation);
  writer.unit(refinement_bytes(0, kCpcaStart, kCpcaShiftBias, start_symbols));
  std::vector<int32_t> shape_coefficients{1, 1}, trajectory_coefficients(6, 1);
  syntax::EntropyWriteIO<false> shape_symbols(syntax::SectionPlace{});
  syntax::CpcaCoders shape_coders;
  mesh.describe_operator<3>(shape_symbols, shape_coders.mesh_component, 0, shapes, shape_coefficients);
  writer.unit(refinement_bytes(0, kCpcaMeshComponent, kCpcaShiftBias, shape_symbols));
  syntax::EntropyWriteIO<false> trajectory_symbols(syntax::SectionPlace{});
  syntax::CpcaCoders trajectory_coders;
  mesh.describe_operator<1>(trajectory_symbols, trajectory_coders.trajectory, 0, trajectories, trajectory_coefficients);
  writer.unit(refinement_bytes(0, kCpcaTrajectory, kCpcaShiftBias, trajectory_symbols));
  return writer.finish();
}

// One cluster with more components of both kinds than either limit: the
// units of a moving tetrahedron's shape components (3 over 3 frames, the
// limit), then those of its trajectory components (3: its 4 vertices less
// their mean), no hash units.
std::vector<uint8_t> cpca_mixed_kinds_stream() {
  auto units = [](const char* model) {
    Encode3dOptions o = cpca({{"clusters", "1"}, {"noise", "-4"}, {"model", model}});
    o.hashes = false;
    return split_container(encode_mesh3d(moving_tetrahedron(3), o).stream);
  };
  ContainerParts shapes = units("shape");
  const ContainerParts trajectories = units("trajectory");
  for (const ContainerUnit& unit : trajectories.units)
    if (is_refinement(unit) && unit_kind(unit) == kCpcaTrajectory) shapes.units.push_back(unit);
  ContainerWriter writer;
  writer.object(shapes.object_payload);
  for (const ContainerUnit& unit : shapes.units) writer.unit(unit.payload);
  return writer.finish();
}

// The start of a clustered-PCA stream of 2 frames written symbol by symbol
// over 255 vertices, one per cluster (the most clusters), and the
// prediction over its base mesh (which reads the plan's faces: not moved).
struct OneVertexClusters {
  OneVertexClusters() = default;
  OneVertexClusters(const OneVertexClusters&) = delete;
  OneVertexClusters& operator=(const OneVertexClusters&) = delete;

  MeshSequence sequence = designed_loose(2, static_cast<int>(kCpcaMaxClusters) - 11, [](int, int) { return 0; });  // its sheet and box hold 11
  std::vector<uint32_t> cluster_of = [this] {
    std::vector<uint32_t> each(sequence.vertex_count);
    for (uint32_t v = 0; v < sequence.vertex_count; ++v) each[v] = v;
    return each;
  }();
  BaseMeshPlan plan = plan_base_mesh(sequence.faces, sequence.vertex_count, false);
  ContainerParts start = cpca_one_cluster_parts(sequence);
  ContainerWriter writer = cpca_written_start(start, cluster_of, kCpcaMaxClusters, std::nullopt);
  CpcaMeshPrediction mesh{plan.faces, plan.input_of, cluster_of, kCpcaMaxClusters, base_mesh_of(start).positions};
};

// A clustered-PCA stream of 2 frames written symbol by symbol (no hash
// units) whose values meet their limits, over 255 vertices, one per
// cluster (the most clusters):
// - cluster 254's start at shift 0: translations 2^29, then −2^29;
// - cluster 0's component (unit_kind 1) at shift 63: basis ±2^15,
//   coefficients ±2^23;
// - cluster 1's component over the mesh (unit_kind 2) and cluster 2's
//   trajectory component (unit_kind 3), their values the same.
std::vector<uint8_t> cpca_limits_stream() {
  constexpr int32_t kBasis = kCpcaMaxBasis, kCoefficient = kCpcaMaxCoefficient, kTranslation = kCpcaMaxTranslation;
  OneVertexClusters stream;
  ContainerWriter& writer = stream.writer;
  const CpcaMeshPrediction& mesh = stream.mesh;
  auto start = [&](uint32_t cluster, uint32_t shift, std::vector<int32_t> translation) {
    syntax::EntropyWriteIO<false> symbols(syntax::SectionPlace{});
    syntax::CpcaCoders coders;
    syntax::describe_start(symbols, coders.start, translation);
    writer.unit(refinement_bytes(cluster, kCpcaStart, shift, symbols));
  };
  start(kCpcaMaxClusters - 1, 0, {kTranslation, kTranslation, kTranslation, -kTranslation, -kTranslation, -kTranslation});
  for (uint32_t cluster : {0u, 1u, 2u}) start(cluster, kCpcaShiftBias, std::vector<int32_t>(6));
  {
    std::vector<int32_t> basis{kBasis, -kBasis, kBasis}, coefficients{kCoefficient, -kCoefficient};
    syntax::EntropyWriteIO<false> symbols(syntax::SectionPlace{});
    syntax::CpcaCoders coders;
    syntax::describe_operator(symbols, coders.component, basis, coefficients);
    writer.unit(refinement_bytes(0, kCpcaComponent, kCpcaMaxShift, symbols));
  }
  {
    std::vector<int32_t> basis{-kBasis, kBasis, -kBasis}, coefficients{-kCoefficient, kCoefficient};
    syntax::EntropyWriteIO<false> symbols(syntax::SectionPlace{});
    syntax::CpcaCoders coders;
    mesh.describe_operator<3>(symbols, coders.mesh_component, 1, basis, coefficients);
    writer.unit(refinement_bytes(1, kCpcaMeshComponent, kCpcaShiftBias + 24, symbols));
  }
  {
    std::vector<int32_t> basis{-kBasis}, coefficients{kCoefficient, -kCoefficient, kCoefficient, -kCoefficient, kCoefficient, -kCoefficient};
    syntax::EntropyWriteIO<false> symbols(syntax::SectionPlace{});
    syntax::CpcaCoders coders;
    mesh.describe_operator<1>(symbols, coders.trajectory, 2, basis, coefficients);
    writer.unit(refinement_bytes(2, kCpcaTrajectory, kCpcaShiftBias + 24, symbols));
  }
  return writer.finish();
}

// A clustered-PCA stream of 2 frames written symbol by symbol
// (no hash units), of groups at their limits, over 255 vertices, one per
// cluster:
// - a group of 255: every cluster's start in cluster order, cluster 0's at
//   group_shift 0 and cluster 254's at 63, translations −2 … 2 (one start
//   coder through all 255);
// - a group of 1: cluster 0's component (unit_kind 1);
// - a group of 3: cluster 1's components of unit_kind 1 and 2 (its limit,
//   min(3M, N) = 2), then cluster 254's trajectory component (unit_kind 3)
//   at group_shift 63: a coder of each kind in one unit.
// Writes a group unit of these refinements over OneVertexClusters, the
// i-th value of each −2 … 2; `started` as group_bytes's.
void write_one_vertex_group(OneVertexClusters& stream, std::vector<uint8_t>& started, const std::vector<CpcaRefinementHeader>& refinements) {
  stream.writer.unit(group_bytes(refinements, started, [&](syntax::EntropyWriteIO<false>& symbols) {
    syntax::CpcaCoders coders;
    for (const CpcaRefinementHeader& h : refinements) {
      const size_t per_member = h.kind == kCpcaTrajectory ? 1 : 3;
      std::vector<int32_t> translation(h.kind == kCpcaStart ? 6 : 0), basis(h.kind == kCpcaStart ? 0 : per_member),
          coefficients(h.kind == kCpcaStart ? 0 : 6 / per_member);
      for (std::vector<int32_t>* values : {&translation, &basis, &coefficients})
        for (size_t i = 0; i < values->size(); ++i) (*values)[i] = static_cast<int32_t>((h.cluster + 3 * i) % 5) - 2;
      describe_refinement(symbols, coders, stream.mesh, h, h.kind == kCpcaTrajectory, {}, translation, basis, coefficients);
    }
  }));
}

std::vector<uint8_t> cpca_group_limits_stream() {
  OneVertexClusters stream;
  std::vector<uint8_t> started(kCpcaMaxClusters, 0);
  auto group = [&](const std::vector<CpcaRefinementHeader>& refinements) { write_one_vertex_group(stream, started, refinements); };
  std::vector<CpcaRefinementHeader> starts;
  for (uint32_t c = 0; c < kCpcaMaxClusters; ++c)
    starts.push_back({c, kCpcaStart, c == 0 ? 0 : c == kCpcaMaxClusters - 1 ? kCpcaMaxShift : kCpcaShiftBias});
  group(starts);
  group({{0, kCpcaComponent, kCpcaShiftBias}});
  group({{1, kCpcaComponent, kCpcaShiftBias}, {1, kCpcaMeshComponent, kCpcaShiftBias}, {kCpcaMaxClusters - 1, kCpcaTrajectory, kCpcaMaxShift}});
  return stream.writer.finish();
}

// A clustered-PCA stream over OneVertexClusters whose group
// lists' shifts walk 0 … 63 at random (a fixed seed; a third of the time
// the same shift, a third one up or down, a third anywhere), then climb a
// ladder to the longest prefixes, so that the shift differences of starts
// and of components reach every context: a group of the 255 starts, then
// every cluster's components of unit_kind 1, 2 and 3 in three groups.
std::vector<uint8_t> cpca_group_shifts_stream() {
  OneVertexClusters stream;
  std::vector<uint8_t> started(kCpcaMaxClusters, 0);
  uint32_t state = 12345, shift = kCpcaShiftBias;
  auto next_shift = [&] {
    state = state * 1103515245u + 12345u;
    const uint32_t step = (state >> 16) % 3;
    if (step == 1) shift = (state >> 20) % 2 == 0 ? std::max(shift, 1u) - 1 : std::min(shift + 1, kCpcaMaxShift);
    if (step == 2) shift = (state >> 20) % (kCpcaMaxShift + 1);
    return shift;
  };
  // The list's last 104 shifts: from 0 up and from 63 down, 24 times the
  // same (the order k falls to 0), a step of 1 or 2 (class 1 or 2), then a
  // jump of 40 (prefix length 5).
  std::vector<uint32_t> ladder;
  for (const uint32_t step : {1u, 2u})
    for (const bool up : {true, false}) {
      const uint32_t from = up ? 0 : kCpcaMaxShift;
      ladder.insert(ladder.end(), 24, from);
      ladder.push_back(up ? from + step : from - step);
      ladder.push_back(up ? from + step + 40 : from - step - 40);
    }
  for (const uint32_t kind : {kCpcaStart, kCpcaComponent, kCpcaMeshComponent, kCpcaTrajectory}) {
    std::vector<CpcaRefinementHeader> group;
    for (uint32_t c = 0; c < kCpcaMaxClusters; ++c) {
      const bool on_ladder = c + ladder.size() >= kCpcaMaxClusters;
      group.push_back({c, kind, on_ladder ? ladder[c + ladder.size() - kCpcaMaxClusters] : next_shift()});
    }
    write_one_vertex_group(stream, started, group);
  }
  return stream.writer.finish();
}

}  // namespace

std::vector<uint8_t> cpca_over_mesh_stream(const MeshSequence& s, uint32_t kind, std::span<const uint32_t> untraversed) {
  std::vector<uint32_t> cluster_of(s.vertex_count);
  for (uint32_t v = 0; v < s.vertex_count; ++v) cluster_of[v] = v < s.vertex_count / 2 ? 0 : 1;
  const ContainerParts start = cpca_one_cluster_parts(s);
  ContainerWriter writer = cpca_written_start(start, cluster_of, 2, std::nullopt);
  const BaseMeshPlan plan = plan_base_mesh(s.faces, s.vertex_count, false, untraversed);
  const CpcaMeshPrediction mesh(plan.faces, plan.input_of, cluster_of, 2, base_mesh_of(start).positions);
  const std::vector<std::vector<NodeIndex>> members = cpca_members(cluster_of, 2);
  const size_t per_member = kind == kCpcaTrajectory ? 1 : 3, frames = s.frames.size();
  for (uint32_t c = 0; c < 2; ++c) {
    syntax::EntropyWriteIO<false> symbols(syntax::SectionPlace{});
    syntax::CpcaCoders coders;
    std::vector<int32_t> translation(3 * frames);
    for (size_t i = 0; i < translation.size(); ++i) translation[i] = static_cast<int32_t>(i % 5) - 2;
    syntax::describe_start(symbols, coders.start, translation);
    writer.unit(refinement_bytes(c, kCpcaStart, kCpcaShiftBias, symbols));
  }
  for (uint32_t c = 0; c < 2; ++c) {
    std::vector<int32_t> basis(per_member * members[c].size()), coefficients(3 / per_member * frames);
    for (size_t i = 0; i < basis.size(); ++i) basis[i] = static_cast<int32_t>((7 * i + c) % 23) - 11;
    for (size_t i = 0; i < coefficients.size(); ++i) coefficients[i] = static_cast<int32_t>((3 * i) % 7) - 3;
    syntax::EntropyWriteIO<false> symbols(syntax::SectionPlace{});
    syntax::CpcaCoders coders;
    if (kind == kCpcaTrajectory)
      mesh.describe_operator<1>(symbols, coders.trajectory, c, basis, coefficients);
    else
      mesh.describe_operator<3>(symbols, coders.mesh_component, c, basis, coefficients);
    writer.unit(refinement_bytes(c, kind, kCpcaShiftBias, symbols));
  }
  return untraversed.empty() ? writer.finish() : with_untraversed_order(writer.finish(), untraversed);
}

// The clustered-PCA codec's streams: both orders, a prefix cut at a unit
// boundary, the finest and coarsest quantization, one cluster, F = 0.
std::vector<SuiteCase> cpca_cases(bool traced) {
  const MeshSequence flag = waving_flag(9, 8, false);
  std::vector<SuiteCase> suite;
  suite.push_back(valid("cpca-01-wpt", "cpca-wpt, 4 clusters, weighted progressive order", {"cpca", "container-units"}, flag,
                        cpca({{"clusters", "4"}}), traced));
  suite.push_back(valid("cpca-02-rpt", "cpca-wpt, round robin over the clusters", {"cpca"}, flag, cpca({{"clusters", "4"}, {"order", "rpt"}}),
                        traced));
  {
    // The prefix of cpca-01 through its twelfth unit (no hash units, no
    // end code), traced as the encoder traced those units.
    const SuiteCase& full = suite.front();
    const ContainerParts parts = split_container(full.stream);
    SuiteCase prefix = decode_case(
        "cpca-03-prefix", "the first 12 units of cpca-01: a prefix cut at a unit boundary decodes", {"cpca", "cpca-prefix"},
        std::vector<uint8_t>(full.stream.begin(), full.stream.begin() + static_cast<std::ptrdiff_t>(parts.units[12].byte_offset)));
    if (traced) prefix.encoder_trace = full.encoder_trace.substr(0, full.encoder_trace.find("\nunit 12 ") + 1);
    suite.push_back(std::move(prefix));
  }
  suite.push_back(valid("cpca-04-fine", "every component at the finest noise step, a 16-bit grid", {"cpca"}, flag,
                        cpca({{"clusters", "3"}, {"components", "4096"}, {"noise", "-4"}, {"bits", "16"}}), traced));
  suite.push_back(valid("cpca-05-coarse", "the coarsest noise step on a 4-bit grid", {"cpca"}, flag,
                        cpca({{"clusters", "3"}, {"noise", "12"}, {"bits", "4"}}), traced));
  suite.push_back(valid("cpca-06-one-cluster", "one cluster", {"cpca"}, flag, cpca({{"clusters", "1"}}), traced));
  suite.push_back(valid("cpca-08-spikes", "vertices that jump by 2^−2 … 2^−23 of the box on a 24-bit grid", {"cpca"},
                        spiky_sheet(8, 16, 0, 43, 30), cpca({{"clusters", "3"}, {"bits", "24"}, {"noise", "-4"}, {"components", "4096"}}), traced));
  suite.push_back(valid("cpca-09-many-clusters", "200 clusters over 389 vertices: cluster numbers far apart", {"cpca"},
                        spiky_sheet(4, 16, 100, 47, 3), cpca({{"clusters", "200"}, {"bits", "24"}}), traced));
  suite.push_back(written_case("cpca-10-written", "a stream written symbol by symbol: every prefix length 0 … 13 after each class in "
                              "translations, basis values and coefficients, cluster differences up to 254, F = 16, start shifts above 16",
                              {"cpca"}, cpca_written_stream()));
  suite.push_back(valid("cpca-11-mesh-basis", "shape components whose basis is predicted over the base mesh (unit_kind 2)", {"cpca"}, flag,
                        cpca({{"clusters", "4"}, {"basis", "mesh"}}), traced));
  suite.push_back(valid("cpca-27-mesh-basis-spikes", "cpca-08's spikes, the basis predicted over the base mesh (unit_kind 2)", {"cpca"},
                        spiky_sheet(8, 16, 0, 43, 30), cpca({{"clusters", "3"}, {"bits", "24"}, {"basis", "mesh"}}), traced));
  suite.push_back(valid("cpca-12-trajectories", "trajectory components (unit_kind 3)", {"cpca"}, flag,
                        cpca({{"clusters", "4"}, {"model", "trajectory"}}), traced));
  suite.push_back(valid("cpca-13-trajectories-scattered", "trajectory components of 200 clusters over a sheet: members without neighbours",
                        {"cpca"}, spiky_sheet(4, 16, 100, 47, 3), cpca({{"clusters", "200"}, {"bits", "24"}, {"model", "trajectory"}}), traced));
  suite.push_back(written_case("cpca-14-mesh-written", "unit_kind 2 and 3 written symbol by symbol: every prefix length 0 … 13 after "
                              "each class on the parallelogram, neighbour and coefficient channels", {"cpca"}, cpca_mesh_written_stream()));
  suite.push_back(written_case("cpca-46-fit-order", "unit_kind 2 and 3 written symbol by symbol over octahedra: fits whose exact "
                               "value is an integer that the affine fit's binary64 steps taken in another order floor otherwise",
                               {"cpca"}, cpca_fit_order_stream()));
  suite.push_back(written_case("cpca-16-mixed-kinds", "one cluster of 4 vertices over 3 frames: 3 shape components (its limit, "
                              "min(3M, N) = 3) and 3 trajectory components (of min(M, 3N) = 4), counted apart", {"cpca"}, cpca_mixed_kinds_stream()));
  suite.push_back(valid("cpca-07-no-fraction", "a 24-bit grid: fraction_bits 0", {"cpca"}, flag, cpca({{"clusters", "2"}, {"bits", "24"}}),
                        traced));
  suite.push_back(written_case("cpca-17-limits", "values at their limits, written symbol by symbol: translations ±2^29, basis values ±2^15 and "
                               "coefficients ±2^23 of all three component kinds, shifts 0 and 63, cluster 254 of 255", {"cpca"}, cpca_limits_stream()));
  suite.push_back(valid("cpca-18-groups", "refinements in groups (unit_kind 4) of about 150 bytes: starts and components (unit_kind 1) "
                        "together", {"cpca"}, flag, cpca({{"clusters", "4"}, {"group-bytes", "150"}, {"group-growth", "1"}}), traced));
  suite.push_back(valid("cpca-19-groups-over-mesh", "groups of starts and components over the mesh (unit_kind 2)", {"cpca"}, flag,
                        cpca({{"clusters", "4"}, {"basis", "mesh"}, {"group-bytes", "150"}, {"group-growth", "1"}}), traced));
  suite.push_back(valid("cpca-20-groups-of-trajectories", "groups of starts and trajectory components (unit_kind 3)", {"cpca"}, flag,
                        cpca({{"clusters", "4"}, {"model", "trajectory"}, {"group-bytes", "150"}, {"group-growth", "1"}}), traced));
  suite.push_back(written_case("cpca-21-group-limits", "groups at their limits, written symbol by symbol: 255 starts in one group "
                               "(group_cluster 0 … 254, group_shift 0 and 63), a group of 1, a group of all three component kinds",
                               {"cpca"}, cpca_group_limits_stream()));
  const auto by_neighbours = [](const std::vector<uint8_t>& stream) {
    return with_cpca_header(stream, [](CpcaHeader& h, const CpcaMap& map, std::vector<uint8_t>& bins, std::vector<uint8_t>& raw) {
      h.map_prediction = kCpcaMapByNeighbours;
      write_cluster_map<false>(h, map.faces, map.cluster_of, bins, raw, syntax::SectionPlace{});
    });
  };
  suite.push_back(written_case("cpca-22-map-by-neighbours", "cpca-09's 200 scattered clusters, its map by neighbours: one, two and more "
                               "candidates, second candidates and raw ranks", {"cpca"}, by_neighbours(stream_of(suite, "cpca-09-many-clusters"))));
  suite.push_back(written_case("cpca-23-map-limits-by-neighbours", "cpca-17's 255 clusters, its map by neighbours: raw ranks up to 253 of "
                               "8 bits", {"cpca"}, by_neighbours(stream_of(suite, "cpca-17-limits"))));
  suite.push_back(written_case("cpca-30-group-shifts", "group lists whose shifts walk 0 … 63 at random: 255 starts, then the "
                               "components of unit_kind 1, 2 and 3 of every cluster, a group each", {"cpca"}, cpca_group_shifts_stream()));
  {
    // Frame 1 the flag's frame 0, its first half through the origin: the
    // mean shape holds that half at the origin.
    MeshSequence collapsed = flag;
    collapsed.frames = {flag.frames[0], flag.frames[0]};
    for (size_t v = 0; v < collapsed.vertex_count / 2; ++v) {
      const Vec3 p = collapsed.frames[1][v];
      collapsed.frames[1][v] = {-p.x, -p.y, -p.z};
    }
    suite.push_back(valid("cpca-35-trajectories-collapsed", "trajectory components over a mean shape half collapsed to one point: fits "
                          "without spread, the mean of the known values", {"cpca"}, collapsed,
                          cpca({{"clusters", "2"}, {"model", "trajectory"}, {"noise", "-4"}}), traced));
  }
  {
    // base-25's spiky sheet with a loose face (v, v, u): u counts once per
    // corner of v, in the member order of kinds 2 and 3 and in the map by
    // neighbours.
    MeshSequence repeated_corner = spiky_sheet(2, 32, 200, 46, 4);
    repeated_corner.faces.push_back({{544, 544, repeated_corner.faces.front().v[0]}});
    suite.push_back(valid("cpca-43-repeated-corner-mesh-basis", "components over the mesh (unit_kind 2) of one cluster over base-25's sheet "
                          "and its loose face (v, v, u)", {"cpca"}, repeated_corner, cpca({{"clusters", "1"}, {"basis", "mesh"}, {"noise", "-4"}}),
                          traced));
    suite.push_back(valid("cpca-44-repeated-corner-trajectories", "trajectory components (unit_kind 3) of one cluster over base-25's sheet "
                          "and its loose face (v, v, u)", {"cpca"}, repeated_corner,
                          cpca({{"clusters", "1"}, {"model", "trajectory"}, {"noise", "-4"}}), traced));
    Encode3dOptions clusters = cpca({{"clusters", "20"}});
    clusters.hashes = false;
    suite.push_back(written_case("cpca-45-repeated-corner-map", "20 clusters over base-25's sheet and its loose face (v, v, u), the map "
                                 "by neighbours", {"cpca"}, by_neighbours(encode_mesh3d(repeated_corner, clusters).stream)));
  }
  return suite;
}

// The clustered-PCA codec's streams to reject: header ranges, and the unit
// rules (cluster, start, component count).
std::vector<SuiteCase> cpca_rejected(const std::vector<SuiteCase>& valid) {
  std::vector<SuiteCase> suite;
  const std::vector<uint8_t> base = stream_of(valid, "cpca-01-wpt");
  auto field = [&base](const char* name) { return object_field<CpcaHeader>(base, name); };
  const struct {
    const char* id;
    const char* purpose;
    const char* field;
    uint8_t value;
    ErrorKind kind;
    const char* element;
  } header_cases[] = {
      {"x-26-cpca-no-cluster", "cluster_count 0", "cluster_count", 0, ErrorKind::kOutOfRange, "cluster_count"},
      {"x-27-cpca-fraction-bits", "fraction_bits 17", "fraction_bits", 17, ErrorKind::kOutOfRange, "fraction_bits"},
      {"x-28-cpca-map-beyond", "cluster_count 3 while the map names cluster 3", "cluster_count", 3, ErrorKind::kOutOfRange, "cluster_of_vertex"},
      {"x-29-cpca-empty-cluster", "cluster_count 5 while the map names clusters 0 … 3", "cluster_count", 5, ErrorKind::kStructure, "cluster_count"},
      {"x-37-cpca-quantization-bits", "quantization_bits 3", "quantization_bits", 3, ErrorKind::kOutOfRange, "quantization_bits"},
  };
  // The map's own cases on the same stream with its map by differences.
  const std::vector<uint8_t> by_difference = with_map_by_difference(base);
  for (const auto& c : header_cases)
    suite.push_back(invalid(c.id, c.purpose, {"cpca"},
                            edited(by_difference, [&](ContainerParts& p) { put_field(p.object_payload, object_field<CpcaHeader>(by_difference, c.field), c.value); }),
                            c.kind, c.element, kNoPlane));
  suite.push_back(invalid("x-147-cpca-map-prediction", "cluster_map_prediction 2", {"cpca"},
                          edited(base, [&](ContainerParts& p) { put_field(p.object_payload, field("cluster_map_prediction"), 2); }),
                          ErrorKind::kOutOfRange, "cluster_map_prediction", kNoPlane));
  suite.push_back(invalid("x-148-cpca-rank-beyond", "a cluster map by neighbours of 4 clusters whose first vertex takes rank 3 of the 3 left",
                          {"cpca"}, with_first_rank(base, 4, 3), ErrorKind::kOutOfRange, "cluster_rank", kNoPlane));
  suite.push_back(invalid("x-149-cpca-rank-none-left", "a cluster map by neighbours of 1 cluster whose first vertex is not in it",
                          {"cpca"}, with_first_rank(base, 1, 0), ErrorKind::kOutOfRange, "cluster_rank", kNoPlane));
  suite.push_back(invalid("x-150-cpca-empty-cluster-by-neighbours", "a cluster map by neighbours naming clusters 0 … 3 of 5", {"cpca"},
                          with_cpca_header(base,
                                           [](CpcaHeader& h, const CpcaMap& map, std::vector<uint8_t>& bins, std::vector<uint8_t>& raw) {
                                             h.map_prediction = kCpcaMapByNeighbours;
                                             h.cluster_count = 5;
                                             write_cluster_map<false>(h, map.faces, map.cluster_of, bins, raw, syntax::SectionPlace{});
                                           }),
                          ErrorKind::kStructure, "cluster_count", kNoPlane));
  suite.push_back(invalid("x-30-cpca-no-frame-count", "frame_count 0 (unknown)", {"cpca"},
                          edited(base,
                                 [&](ContainerParts& p) { put_field(p.object_payload, field("frame_count"), 0); }),
                          ErrorKind::kStructure, "frame_count", kNoPlane));
  suite.push_back(invalid("x-31-cpca-cluster-beyond", "a refinement unit for cluster 4 of 4", {"cpca"},
                          edited(base, [](ContainerParts& p) { put_field(p.units[refinement_unit(p, 0)].payload, refinement_field("cluster"), 4); }),
                          ErrorKind::kOutOfRange, "cluster", kNoPlane));
  suite.push_back(invalid("x-95-cpca-cluster-255", "a refinement unit for cluster 255, one past the most clusters", {"cpca"},
                          edited(stream_of(valid, "cpca-17-limits"),
                                 [](ContainerParts& p) { put_field(p.units[refinement_unit(p, 0)].payload, refinement_field("cluster"), 255); }),
                          ErrorKind::kOutOfRange, "cluster", kNoPlane));
  {
    // cpca-17's clusters are one vertex each over 2 frames (at most 2
    // components of kinds 1 and 2, 1 of kind 3); cluster 254 has none, 0 one.
    const std::vector<uint8_t> limits = stream_of(valid, "cpca-17-limits");
    constexpr int32_t kBeyond = kCpcaMaxCoefficient + 1;
    auto appended = [&](std::vector<uint8_t> unit) {
      return edited(limits, [&](ContainerParts& p) { p.units.push_back(ContainerUnit{0, 0, unit}); });
    };
    suite.push_back(invalid("x-121-cpca-trajectory-coefficient-range", "a trajectory component whose first coefficient is 2^23 + 1", {"cpca"},
                            appended(crafted_refinement(kCpcaMaxClusters - 1, kCpcaTrajectory, {{1, 0}, {2, kBeyond}})), ErrorKind::kOutOfRange,
                            "trajectory_coefficient", kNoPlane));
    suite.push_back(invalid("x-122-cpca-mesh-coefficient-range", "a unit_kind 2 component whose first coefficient is 2^23 + 1", {"cpca"},
                            appended(crafted_refinement(0, kCpcaMeshComponent, {{3, 0}, {4, 0}, {5, 0}, {6, kBeyond}})),
                            ErrorKind::kOutOfRange, "coefficient", kNoPlane));
    const FieldBytes length = refinement_field("arithmetic_bytes");
    suite.push_back(invalid("x-120-cpca-arithmetic-bytes", "arithmetic_bytes longer than the unit", {"cpca"},
                            edited(limits, [&](ContainerParts& p) { put_field(p.units[refinement_unit(p, 0)].payload, length, 0x7F000000); }),
                            ErrorKind::kOutOfRange, "arithmetic_bytes", kNoPlane));
    suite.push_back(invalid("x-123-cpca-start-left-over", "a byte after a start's last bin, counted by arithmetic_bytes", {"cpca"},
                            edited(limits, [&](ContainerParts& p) { add_bins_byte(p.units[refinement_unit(p, 0)].payload, length); }),
                            ErrorKind::kStructure, "translation", kNoPlane));
    // cpca-17's units: 4 starts, then kinds 1, 2 and 3.
    const struct {
      const char* id;
      const char* purpose;
      size_t unit;
      const char* element;
    } raw_left_over[] = {{"x-124-cpca-component-left-over", "a byte after a component's raw bits", 4, "coefficient"},
                         {"x-125-cpca-mesh-left-over", "a byte after a unit_kind 2 component's raw bits", 5, "coefficient"},
                         {"x-126-cpca-trajectory-left-over", "a byte after a trajectory component's raw bits", 6, "trajectory_coefficient"}};
    for (const auto& c : raw_left_over)
      suite.push_back(invalid(c.id, c.purpose, {"cpca"},
                              edited(limits, [&](ContainerParts& p) { p.units[refinement_unit(p, c.unit)].payload.push_back(0x00); }),
                              ErrorKind::kStructure, c.element, kNoPlane));
  }
  suite.push_back(invalid("x-32-cpca-unit-kind", "unit_kind 6", {"cpca"},
                          edited(base, [](ContainerParts& p) { put_field(p.units[refinement_unit(p, 0)].payload, refinement_field("unit_kind"), 6); }),
                          ErrorKind::kOutOfRange, "unit_kind", kNoPlane));
  // The first component unit of a kind moves before every refinement unit (they follow the base mesh).
  auto component_first = [](uint32_t kind) {
    return [kind](ContainerParts& p) {
      size_t k = refinement_unit(p, 0);
      while (unit_kind(p.units[k]) != kind) ++k;
      ContainerUnit component = p.units[k];
      p.units.erase(p.units.begin() + static_cast<std::ptrdiff_t>(k));
      p.units.insert(p.units.begin() + static_cast<std::ptrdiff_t>(refinement_unit(p, 0)), component);
    };
  };
  suite.push_back(invalid("x-33-cpca-not-started", "a component of a cluster before the cluster's start", {"cpca"},
                          edited(base, component_first(kCpcaComponent)), ErrorKind::kStructure, "unit_kind", kNoPlane));
  suite.push_back(invalid("x-65-cpca-mesh-not-started", "a unit_kind 2 component of a cluster before the cluster's start", {"cpca"},
                          edited(stream_of(valid, "cpca-11-mesh-basis"), component_first(kCpcaMeshComponent)), ErrorKind::kStructure, "unit_kind", kNoPlane));
  suite.push_back(invalid("x-66-cpca-trajectory-not-started", "a trajectory component of a cluster before the cluster's start", {"cpca"},
                          edited(stream_of(valid, "cpca-12-trajectories"), component_first(kCpcaTrajectory)), ErrorKind::kStructure, "unit_kind",
                          kNoPlane));
  suite.push_back(invalid("x-34-cpca-second-start", "a cluster's start sent twice", {"cpca"},
                          edited(base,
                                 [](ContainerParts& p) {
                                   const size_t first = refinement_unit(p, 0);
                                   p.units.insert(p.units.begin() + static_cast<std::ptrdiff_t>(first) + 1, p.units[first]);
                                 }),
                          ErrorKind::kStructure, "unit_kind", kNoPlane));
  // Two rules broken at once: a refinement's rules come after its fields' ranges.
  suite.push_back(invalid("x-182-cpca-second-start-shift-64", "x-34's second start with shift 64: shift's range before the start rule", {"cpca"},
                          edited(base,
                                 [](ContainerParts& p) {
                                   const size_t first = refinement_unit(p, 0);
                                   p.units.insert(p.units.begin() + static_cast<std::ptrdiff_t>(first) + 1, p.units[first]);
                                   put_field(p.units[first + 1].payload, refinement_field("shift"), 64);
                                 }),
                          ErrorKind::kOutOfRange, "shift", kNoPlane));
  suite.push_back(invalid("x-35-cpca-refinement-frame", "a refinement unit naming frame 1", {"cpca"},
                          edited(base, [](ContainerParts& p) { put_field(p.units[refinement_unit(p, 0)].payload, unit_header_field("frame_index"), 1); }),
                          ErrorKind::kStructure, "frame_index", kNoPlane));
  suite.push_back(invalid("x-38-cpca-shift", "shift 64", {"cpca"},
                          edited(base, [](ContainerParts& p) { put_field(p.units[refinement_unit(p, 0)].payload, refinement_field("shift"), 64); }),
                          ErrorKind::kOutOfRange, "shift", kNoPlane));
  {
    // Values beyond their ranges, in the first refinement units: cluster
    // 0's start, then one of its components.
    const ContainerParts parts = split_container(base);
    const size_t start = refinement_unit(parts, 0);
    const uint32_t cluster = static_cast<uint32_t>(field_value(parts.units[start].payload, refinement_field("cluster")));
    // The cluster's size, from the header's cluster map.
    const std::vector<uint32_t> cluster_of = cpca_cluster_map(parts);
    std::vector<std::pair<int, int32_t>> coefficient_beyond(3 * static_cast<size_t>(std::count(cluster_of.begin(), cluster_of.end(), cluster)));
    for (size_t j = 0; j < coefficient_beyond.size(); ++j) coefficient_beyond[j] = {static_cast<int>(j % 3), 0};
    coefficient_beyond.emplace_back(syntax::kCpcaCoefficientChannel, (1 << 23) + 1);
    const struct {
      const char* id;
      const char* purpose;
      uint32_t kind;
      std::vector<std::pair<int, int32_t>> residuals;
      const char* element;
    } ranges[] = {
        {"x-39-cpca-translation-range", "a start whose first translation is 2^29 + 1", kCpcaStart, {{0, (1 << 29) + 1}}, "translation"},
        {"x-40-cpca-basis-range", "a component whose first basis value is 2^15 + 1", kCpcaComponent, {{0, (1 << 15) + 1}}, "basis"},
        {"x-41-cpca-coefficient-range", "a component whose first coefficient is 2^23 + 1", kCpcaComponent, coefficient_beyond, "coefficient"},
        // The first member in coding order has no member before it: channel D, from 0.
        {"x-63-cpca-mesh-basis-range", "a unit_kind 2 component whose first basis value is 2^15 + 1", kCpcaMeshComponent,
         {{3, (1 << 15) + 1}}, "mesh_basis"},
        {"x-64-cpca-trajectory-basis-range", "a trajectory component whose first basis value is 2^15 + 1", kCpcaTrajectory,
         {{1, (1 << 15) + 1}}, "trajectory_basis"},
    };
    for (const auto& c : ranges)
      suite.push_back(invalid(c.id, c.purpose, {"cpca"},
                              edited(base,
                                     [&](ContainerParts& p) {
                                       const std::vector<uint8_t> unit = crafted_refinement(cluster, c.kind, c.residuals);
                                       // A start replaces cluster's start; a component follows it.
                                       if (c.kind == kCpcaStart)
                                         p.units[start].payload = unit;
                                       else
                                         p.units.insert(p.units.begin() + static_cast<std::ptrdiff_t>(start) + 1, ContainerUnit{0, 0, unit});
                                     }),
                              ErrorKind::kOutOfRange, c.element, kNoPlane));
  }
  {
    // One cluster over 3 frames has 3 components: its fourth is one too many.
    const std::vector<uint8_t> short_stream = encode_mesh3d(moving_tetrahedron(3), cpca({{"clusters", "1"}, {"noise", "-4"}})).stream;
    suite.push_back(invalid("x-36-cpca-beyond-components", "a fourth component of a cluster over 3 frames", {"cpca"},
                            edited(short_stream,
                                   [](ContainerParts& p) {
                                     size_t last = refinement_unit(p, 0), components = 0;
                                     for (size_t k = 0; k < p.units.size(); ++k)
                                       if (is_refinement(p.units[k])) {
                                         last = k;
                                         components += unit_kind(p.units[k]) == kCpcaComponent;
                                       }
                                     const ContainerUnit copy = p.units[last];
                                     for (size_t extra = components; extra < 4; ++extra)
                                       p.units.insert(p.units.begin() + static_cast<std::ptrdiff_t>(last) + 1, copy);
                                   }),
                            ErrorKind::kStructure, "cluster", kNoPlane));
  }
  {
    // One cluster of 4 vertices has at most 4 trajectory components: a fifth is one too many.
    const std::vector<uint8_t> short_stream =
        encode_mesh3d(moving_tetrahedron(3), cpca({{"clusters", "1"}, {"noise", "-4"}, {"model", "trajectory"}})).stream;
    suite.push_back(invalid("x-62-cpca-beyond-trajectories", "a fifth trajectory component of a cluster of 4 vertices", {"cpca"},
                            edited(short_stream,
                                   [](ContainerParts& p) {
                                     size_t last = 0, components = 0;
                                     for (size_t k = 0; k < p.units.size(); ++k)
                                       if (is_refinement(p.units[k]) && unit_kind(p.units[k]) == kCpcaTrajectory) {
                                         last = k;
                                         ++components;
                                       }
                                     if (components == 0) throw Error(ErrorKind::kStructure, "", kNoPlane, kNoOffset, "suite: no trajectory unit");
                                     const ContainerUnit copy = p.units[last];
                                     for (size_t extra = components; extra < 5; ++extra)
                                       p.units.insert(p.units.begin() + static_cast<std::ptrdiff_t>(last) + 1, copy);
                                   }),
                            ErrorKind::kStructure, "cluster", kNoPlane));
  }
  {
    // cpca-18's first refinement unit is a group: its fields and its list.
    const std::vector<uint8_t> groups = stream_of(valid, "cpca-18-groups");
    auto first_group = [](ContainerParts& p) -> ContainerUnit& {
      ContainerUnit& unit = p.units[refinement_unit(p, 0)];
      if (unit_kind(unit) != kCpcaGroup) throw Error(ErrorKind::kStructure, "", kNoPlane, kNoOffset, "suite: the stream starts without a group");
      return unit;
    };
    auto put = [&](FieldBytes at, uint64_t value) {
      return edited(groups, [&, at, value](ContainerParts& p) { put_field(first_group(p).payload, at, value); });
    };
    suite.push_back(invalid("x-134-cpca-group-cluster", "a group whose cluster field is 1", {"cpca"}, put(refinement_field("cluster"), 1),
                            ErrorKind::kStructure, "cluster", kNoPlane));
    suite.push_back(invalid("x-135-cpca-group-shift", "a group whose shift field is 16", {"cpca"}, put(refinement_field("shift"), 16),
                            ErrorKind::kStructure, "shift", kNoPlane));
    suite.push_back(invalid("x-136-cpca-group-empty", "group_size 0", {"cpca"}, put(group_field("group_size"), 0), ErrorKind::kOutOfRange,
                            "group_size", kNoPlane));
    // Two rules broken at once: the fields' ranges come before a group's rules.
    suite.push_back(invalid("x-183-cpca-group-cluster-and-shift-64", "a group whose cluster field is 1 and shift 64: shift's range first",
                            {"cpca"},
                            edited(groups,
                                   [&](ContainerParts& p) {
                                     put_field(first_group(p).payload, refinement_field("cluster"), 1);
                                     put_field(first_group(p).payload, refinement_field("shift"), 64);
                                   }),
                            ErrorKind::kOutOfRange, "shift", kNoPlane));
  }
  {
    // cpca-21: one vertex per cluster over 2 frames (at most 2 components of
    // kinds 1 and 2); cluster 0 has one after its second group.
    const std::vector<uint8_t> limits = stream_of(valid, "cpca-21-group-limits");
    suite.push_back(invalid("x-142-cpca-group-beyond-components", "a group of two more components of cluster 0, which has room for one",
                            {"cpca"}, edited(limits,
                                             [](ContainerParts& p) {
                                               std::vector<uint8_t> started(kCpcaMaxClusters, 1);
                                               const std::vector<uint8_t> unit = group_bytes(
                                                   {{0, kCpcaComponent, kCpcaShiftBias}, {0, kCpcaComponent, kCpcaShiftBias}}, started,
                                                   [](syntax::EntropyWriteIO<false>& symbols) {
                                                     syntax::CpcaCoders coders;
                                                     for (int k = 0; k < 2; ++k) {
                                                       std::vector<int32_t> basis{1, 1, 1}, coefficients{1, 1};
                                                       syntax::describe_operator(symbols, coders.component, basis, coefficients);
                                                     }
                                                   });
                                               p.units.push_back(ContainerUnit{0, 0, unit});
                                             }),
                            ErrorKind::kStructure, "group_cluster", kNoPlane));
    suite.push_back(invalid("x-143-cpca-group-left-over", "a byte after the raw bits of a group whose last refinement is a trajectory component",
                            {"cpca"},
                            edited(limits, [](ContainerParts& p) { p.units[refinement_unit(p, 2)].payload.push_back(0x00); }),
                            ErrorKind::kStructure, "trajectory_coefficient", kNoPlane));
    // The list in bins: the first group of cpca-21 replaced by one
    // whose first refinement is written symbol by symbol.
    auto first_list = [&](const std::function<void(syntax::EntropyWriteIO<false>&)>& symbols_of) {
      return edited(limits, [&](ContainerParts& p) {
        syntax::EntropyWriteIO<false> symbols(syntax::SectionPlace{});
        symbols_of(symbols);
        p.units[refinement_unit(p, 0)].payload = refinement_unit_bytes(CpcaRefinement{0, kCpcaGroup, 0, {CpcaRefinementHeader{}}, 0, {}, {}}, symbols);
      });
    };
    suite.push_back(invalid("x-154-cpca-group-list-cluster-255", "a group's first group_cluster 255 (8 raw bits of 255 clusters)",
                            {"cpca"}, first_list([](syntax::EntropyWriteIO<false>& symbols) {
                              uint32_t cluster = kCpcaMaxClusters;
                              symbols.raw("group_cluster", 8, cluster);
                            }),
                            ErrorKind::kOutOfRange, "group_cluster", kNoPlane));
    // The same with 40 bytes of bins behind the raw field: the error is
    // placed where the arithmetic decoder is (5 bytes in), not at the raw
    // bits (after the bins), which x-154's 5-byte bin section puts at one place.
    suite.push_back(invalid("x-177-cpca-group-list-cluster-behind-bins", "x-154's group_cluster 255, its unit's bin section 40 bytes long",
                            {"cpca"}, first_list([](syntax::EntropyWriteIO<false>& symbols) {
                              uint32_t cluster = kCpcaMaxClusters;
                              symbols.raw("group_cluster", 8, cluster);
                              BinContext context;
                              for (int i = 0; i < 320; ++i) {
                                bool bin = i % 2 == 0;
                                symbols.bin("group_trajectory", context, 0, bin);
                              }
                            }),
                            ErrorKind::kOutOfRange, "group_cluster", kNoPlane));
    suite.push_back(invalid("x-155-cpca-group-list-shift", "a group's first start at group_shift 16 − 17", {"cpca"},
                            first_list([](syntax::EntropyWriteIO<false>& symbols) {
                              uint32_t cluster = 0;
                              symbols.raw("group_cluster", 8, cluster);
                              syntax::CpcaGroupContexts contexts;
                              int32_t difference = -static_cast<int32_t>(kCpcaShiftBias) - 1;
                              contexts.shift.describe(symbols, 0, difference, syntax::kCpcaGroupShift);
                            }),
                            ErrorKind::kOutOfRange, "group_shift", kNoPlane));
  }
  return suite;
}

}  // namespace m4mesh::suite3d
