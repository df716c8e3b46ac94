// The clustered-PCA codec (codec_id 4): the reconstruction's arithmetic,
// every prefix decodes and improves on the one before, full
// reconstruction, WPT against RPT, determinism, budgets and targets,
// damaged streams.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <numeric>
#include <set>

#include "common/bit_cast.h"
#include "common/random.h"
#include "decoder/mesh3d/container_decoder.h"
#include "encoder/mesh3d/container_encoder.h"
#include "mesh3d/cpca_wpt.h"
#include "mesh3d/metrics.h"
#include "mesh3d/quantization.h"
#include "syntax/mesh3d/cpca_wpt.h"
#include "syntax/mesh3d/container.h"
#include "tests/test_util.h"

namespace m4mesh {
namespace {

namespace fs = std::filesystem;

const fs::path kData = fs::path(M4MESH_SOURCE_DIR) / ".." / "shared" / "data";

Encode3dOptions cpca(CodecOptionValues values = {}) {
  Encode3dOptions options;
  options.codec = "cpca-wpt";
  options.codec_options = std::move(values);
  return options;
}

// (bytes received, KG error) after every unit but hash units.
std::vector<std::pair<uint64_t, double>> curve(const std::vector<uint8_t>& stream, const MeshSequence& original) {
  std::vector<std::pair<uint64_t, double>> points;
  for_each_prefix(stream, [&](size_t, uint64_t bytes, const MeshSequence& decoded) { points.emplace_back(bytes, kg_error(original, decoded)); });
  return points;
}

// The bytes a curve needs to reach a KG error, the curve read as a
// rate–distortion curve, linear between unit boundaries (INFINITY: never).
double bytes_to_reach(const std::vector<std::pair<uint64_t, double>>& points, double kg) {
  for (size_t k = 0; k < points.size(); ++k) {
    if (points[k].second > kg) continue;
    if (k == 0 || points[k].second == points[k - 1].second) return static_cast<double>(points[k].first);
    const double t = (points[k - 1].second - kg) / (points[k - 1].second - points[k].second);
    return static_cast<double>(points[k - 1].first) + t * static_cast<double>(points[k].first - points[k - 1].first);
  }
  return INFINITY;
}

// Every prefix of `stream` cut at a unit boundary decodes every frame, each
// no worse than the one before.
void expect_prefixes_decode_and_improve(const MeshSequence& s, const std::vector<uint8_t>& stream, const ContainerParts& parts) {
  double previous = INFINITY;
  for (size_t k = 1; k < parts.units.size(); ++k) {
    if (parts.units[k].payload[0] == static_cast<uint8_t>(UnitType::kFrameHash)) continue;
    const ContainerPrefix prefix = container_prefix(parts, stream.size(), parts.units[k].byte_offset);
    ASSERT_EQ(prefix.units, k);
    const MeshSequence decoded = decode_mesh3d(std::span(stream).first(prefix.bytes));
    ASSERT_EQ(decoded.frames.size(), s.frames.size());
    const double kg = kg_error(s, decoded);
    EXPECT_LE(kg, previous) << "after " << k << " units";
    previous = kg;
  }
  EXPECT_EQ(container_prefix(parts, stream.size(), 3).units, 0u);
}

// With a unit per refinement, with groups of one size and with growing groups.
// docs/codec_cpca_wpt.md, "Reconstruction", step 2: scale(p) of every
// term, in scalar 64-bit arithmetic.
int64_t document_scale(int64_t p, uint32_t shift) {
  const int u = static_cast<int>(shift) - 16;
  return u > 0 ? (p + (int64_t{1} << (u - 1))) >> u : p * (int64_t{1} << -u);
}

// A value within ±limit, the limits themselves one time in four.
int32_t value_to_limit(SplitMix64& random, int32_t limit) {
  return random.next() % 4 == 0 ? (random.next() % 2 ? limit : -limit) : random.uniform(-limit, limit);
}

// The SIMD loop and its scalar tail give the document's integers: every shift, both kinds and directions, runs of
// 1 to 12 members.
TEST(CpcaReconstruction, TermsAreTheDocumentsIntegers) {
  SplitMix64 random(72);
  for (uint32_t shift = 0; shift <= 63; ++shift)
    for (const bool trajectory : {false, true})
      for (const bool subtract : {false, true})
        for (size_t members = 1; members <= 12; ++members) {
          std::vector<uint64_t> run(3 * members);
          for (uint64_t& x : run) x = random.next();
          std::vector<int32_t> basis(trajectory ? members : 3 * members);
          for (int32_t& b : basis) b = value_to_limit(random, kCpcaMaxBasis);
          std::array<int64_t, 3> lanes{};
          for (int64_t& w : lanes) w = value_to_limit(random, kCpcaMaxCoefficient);
          if (!trajectory) lanes[1] = lanes[2] = lanes[0];
          std::vector<uint64_t> expected = run;
          for (size_t j = 0; j < run.size(); ++j) {
            const auto term = static_cast<uint64_t>(document_scale(int64_t{basis[trajectory ? j / 3 : j]} * lanes[j % 3], shift));
            expected[j] = subtract ? expected[j] - term : expected[j] + term;
          }
          cpca_add_terms(run, basis, lanes, shift, trajectory, subtract);
          ASSERT_EQ(run, expected) << "shift " << shift << (trajectory ? ", trajectory" : "") << (subtract ? ", subtracted" : "") << ", "
                                   << members << " members";
        }
}

// Bounds of a reconstruction test's values: the basis's, and the coefficients' on every frame but the last
// (on which they reach kCpcaMaxCoefficient).
struct ValueLimits {
  int32_t basis = kCpcaMaxBasis, coefficient = kCpcaMaxCoefficient;
};

// The whole reconstruction, step by step as the document gives it, to
// binary32: CpcaAnimation and CpcaSegment (SIMD sums and conversion
// included, one frame or a batch) give the same positions.
void expect_frames_are_the_documents(SplitMix64& random, ValueLimits limits, std::initializer_list<uint32_t> shifts) {
  CpcaHeader header;
  header.fraction_bits = kCpcaMaxFractionBits;
  for (int axis = 0; axis < 3; ++axis) {
    header.origin[axis] = bit_cast<uint32_t>(-1.5f + static_cast<float>(axis));
    header.step[axis] = bit_cast<uint32_t>(0.001f * static_cast<float>(axis + 1));
  }
  const uint32_t vertices = 67, frames = 5;
  // Sizes odd and even, whole blocks of 4 only (24), none (3).
  std::vector<uint32_t> cluster_of(vertices);
  for (uint32_t v = 0; v < vertices; ++v) cluster_of[v] = v < 40 ? static_cast<uint32_t>(random.uniform(0, 2)) : v < 64 ? 3 : 4;
  const std::vector<std::vector<NodeIndex>> members = cpca_members(cluster_of, 5);
  std::vector<IntPoint3> mean(vertices);
  for (IntPoint3& p : mean)
    for (int axis = 0; axis < 3; ++axis) p[axis] = random.uniform(-(1 << 20), 1 << 20);
  // P per frame, vertex and axis, as the document defines it.
  std::vector<uint64_t> expected(size_t{frames} * vertices * 3);
  for (uint32_t f = 0; f < frames; ++f)
    for (uint32_t v = 0; v < vertices; ++v)
      for (int axis = 0; axis < 3; ++axis)
        expected[(size_t{f} * vertices + v) * 3 + static_cast<size_t>(axis)] = static_cast<uint64_t>(int64_t{mean[v][axis]}) << header.fraction_bits;
  CpcaAnimation animation(header, mean, members, frames);
  CpcaSegment segment(header, mean, members, frames);
  for (uint32_t shift : shifts)
    for (uint32_t c = 0; c < members.size(); ++c)
      for (const uint32_t kind : {kCpcaStart, kCpcaComponent, kCpcaTrajectory}) {
        const size_t count = members[c].size(), lanes = kind == kCpcaComponent ? 1 : 3;
        std::vector<int32_t> values(lanes * frames), basis(kind == kCpcaComponent ? 3 * count : count);
        for (size_t k = 0; k < values.size(); ++k)
          values[k] = value_to_limit(random, kind == kCpcaStart           ? kCpcaMaxTranslation
                                             : k / lanes + 1 == frames ? kCpcaMaxCoefficient
                                                                       : limits.coefficient);
        for (int32_t& x : basis) x = value_to_limit(random, limits.basis);
        for (uint32_t f = 0; f < frames; ++f)
          for (size_t i = 0; i < count; ++i)
            for (size_t axis = 0; axis < 3; ++axis) {
              const int64_t term = kind == kCpcaStart       ? document_scale(values[3 * f + axis], shift)
                                   : kind == kCpcaComponent ? document_scale(int64_t{basis[3 * i + axis]} * values[f], shift)
                                                            : document_scale(int64_t{basis[i]} * values[3 * f + axis], shift);
              expected[(size_t{f} * vertices + members[c][i]) * 3 + axis] += static_cast<uint64_t>(term);
            }
        if (kind == kCpcaStart) {
          animation.translate(c, values, shift);
          segment.translate(c, values, shift);
        } else {
          // Undone once, exactly, before it is added for good.
          animation.refine(c, basis, values, shift, kind == kCpcaTrajectory);
          animation.refine(c, basis, values, shift, kind == kCpcaTrajectory, true);
          animation.refine(c, basis, values, shift, kind == kCpcaTrajectory);
          segment.refine(c, std::make_shared<const std::vector<int32_t>>(basis), values, shift, kind == kCpcaTrajectory);
        }
      }
  std::vector<Float3> eager(vertices), lazy(vertices);
  // Also every frame from frame 1 on at once.
  std::vector<std::vector<Float3>> batch(frames - 1, std::vector<Float3>(vertices));
  segment.frames(1, std::vector<std::span<Float3>>(batch.begin(), batch.end()));
  for (uint32_t f = 0; f < frames; ++f) {
    animation.frame(f, eager);
    segment.frame(f, lazy);
    if (f > 0) {
      ASSERT_EQ(batch[f - 1], lazy) << "frame " << f << " in a batch";
    }
    for (uint32_t v = 0; v < vertices; ++v)
      for (int axis = 0; axis < 3; ++axis) {
        const auto P = static_cast<int64_t>(expected[(size_t{f} * vertices + v) * 3 + static_cast<size_t>(axis)]);
        const double unit = static_cast<double>(header.step_value(axis)) / static_cast<double>(uint64_t{1} << header.fraction_bits);
        const float position = static_cast<float>(static_cast<double>(header.origin_value(axis)) + static_cast<double>(P) * unit);
        ASSERT_EQ(bit_cast<uint32_t>(eager[v][axis]), bit_cast<uint32_t>(position)) << "frame " << f << ", vertex " << v << ", axis " << axis;
        ASSERT_EQ(bit_cast<uint32_t>(lazy[v][axis]), bit_cast<uint32_t>(position)) << "frame " << f << ", vertex " << v << ", axis " << axis;
        ASSERT_EQ(bit_cast<uint32_t>(animation.position(f, v)[axis]), bit_cast<uint32_t>(position));
      }
  }
}

// At the value limits and over every kind of shift.
TEST(CpcaReconstruction, FramesAreTheDocumentsPositions) {
  SplitMix64 random(71);
  expect_frames_are_the_documents(random, {}, {0u, 1u, 15u, 16u, 17u, 30u, 47u, 63u});
}

// Values whose terms and sums fit in int32 on every frame but the last (the narrow loops' with SIMD), at
// shifts of either sign.
TEST(CpcaReconstruction, SmallTermsAreTheDocumentsPositions) {
  SplitMix64 random(73);
  expect_frames_are_the_documents(random, {1 << 9, 1 << 10}, {10u, 16u, 17u, 20u, 24u});
}

// Beyond int32: products that reach 2^31 with their rounding half, products under 2^31 whose terms (shifted
// left) do not fit, and terms under 2^31 whose sums do not.
TEST(CpcaReconstruction, TermsAndSumsBeyondInt32AreTheDocumentsPositions) {
  SplitMix64 random(74);
  expect_frames_are_the_documents(random, {1 << 13, 1 << 18}, {17u});
  expect_frames_are_the_documents(random, {1 << 12, 1 << 16}, {12u});
  expect_frames_are_the_documents(random, {1 << 12, 1 << 18}, {16u, 16u, 16u});
}

// Terms with u ≤ 0 in pairs, with a term left over and rounded ones beside them: coefficients that fit int16
// once shifted left (a multiply-add of int16 halves a pair with SIMD); then ones that do not while the terms
// and their sums still fit int32; then basis values of 2^15, which no int16 half holds.
TEST(CpcaReconstruction, PairedTermsAreTheDocumentsPositions) {
  SplitMix64 random(75);
  expect_frames_are_the_documents(random, {1 << 9, 1 << 6}, {12u, 14u, 17u, 16u, 13u, 15u});
  expect_frames_are_the_documents(random, {1 << 9, 1 << 12}, {12u, 12u, 13u});
  expect_frames_are_the_documents(random, {1 << 15, 1 << 3}, {16u, 15u});
}

TEST(CpcaWpt, EveryPrefixDecodesAndTheErrorNeverGrows) {
  const MeshSequence s = test::test_sequence(12, 7);
  struct Case {
    const char *group_bytes, *growth;
    size_t least_units;
  };
  for (const Case& c : {Case{"0", "1", 10}, Case{"60", "1", 5}, Case{"60", "2", 3}}) {
    const std::vector<uint8_t> stream =
        encode_mesh3d(s, cpca({{"clusters", "4"}, {"group-bytes", c.group_bytes}, {"group-growth", c.growth}})).stream;
    const ContainerParts parts = split_container(stream);
    ASSERT_GT(parts.units.size(), c.least_units);
    expect_prefixes_decode_and_improve(s, stream, parts);
  }
}

TEST(CpcaWpt, AllComponentsAtFineQuantizationReconstructTheOriginal) {
  const MeshSequence s = test::test_sequence(10, 3);
  const Encode3dResult r = encode_mesh3d(s, cpca({{"clusters", "3"}, {"components", "4096"}, {"noise", "-4"}, {"bits", "16"}}));
  EXPECT_LT(kg_error(s, decode_mesh3d(r.stream)), 0.001);
}

TEST(CpcaWpt, EncodingIsDeterministic) {
  const MeshSequence s = test::test_sequence(9, 11);
  EXPECT_EQ(encode_mesh3d(s, cpca()).stream, encode_mesh3d(s, cpca()).stream);
  EXPECT_EQ(encode_mesh3d(s, cpca({{"order", "rpt"}})).stream, encode_mesh3d(s, cpca({{"order", "rpt"}})).stream);
}

TEST(CpcaWpt, BudgetAndTargetAreMet) {
  const MeshSequence s = test::test_sequence(12, 5);
  Encode3dOptions options = cpca();
  options.hashes = false;
  const Encode3dResult full = encode_mesh3d(s, options);
  const uint64_t budget = full.stream.size() - full.unit_bytes[static_cast<size_t>(UnitType::kRefinement)] / 2;
  options.codec_options = {{"max-bytes", std::to_string(budget)}};
  const Encode3dResult half = encode_mesh3d(s, options);
  EXPECT_LE(half.stream.size() - 4, budget);  // through the last refinement
  EXPECT_GT(half.stream.size() - 4, budget - full.unit_bytes[static_cast<size_t>(UnitType::kRefinement)] / 4);
  for (double target : {5.0, 1.0}) {
    const Encode3dResult r = encode_mesh3d(s, cpca({{"target-kg", std::to_string(target)}}));
    const double kg = kg_error(s, decode_mesh3d(r.stream));
    EXPECT_LE(kg, target);
    // The prefix one refinement shorter misses the target: the first that reaches it.
    const ContainerParts parts = split_container(r.stream);
    size_t last_refinement = 0;
    for (size_t k = 0; k < parts.units.size(); ++k)
      if (parts.units[k].payload[0] == static_cast<uint8_t>(UnitType::kRefinement)) last_refinement = k;
    ASSERT_GT(last_refinement, 0u);
    EXPECT_GT(kg_error(s, decode_mesh3d(std::span(r.stream).first(parts.units[last_refinement].byte_offset))), target);
  }
  EXPECT_THROW(encode_mesh3d(s, cpca({{"target-kg", "0.000001"}, {"components", "1"}})), Error);
  EXPECT_THROW(encode_mesh3d(s, cpca({{"order", "fast"}})), Error);
  EXPECT_THROW(encode_mesh3d(s, cpca({{"noise", "13"}})), Error);
}

// With a KG target, clusters and components left to auto: of 5, 10, 20 and
// 40 clusters the one whose stream is smallest, then counts 0.7 and 1.4, a
// quarter and an eighth of an octave either side; with every component and
// the model it chose, the same stream as that count given, and no larger
// than other counts. Here 5, then 3 (0.7 times), 2 (2^(−1/4) times) and 1
// (2^(−1/8) times 2): each step of the search shows.
TEST(CpcaWpt, ATargetChoosesTheClusterCount) {
  const MeshSequence s = test::test_sequence(12, 6);
  const Encode3dResult chosen = encode_mesh3d(s, cpca({{"target-kg", "1"}, {"bits", "8"}}));
  auto statistic = [&](const char* name) {
    const auto found = std::find_if(chosen.statistics.begin(), chosen.statistics.end(), [&](const CodecStatistic& c) { return c.first == name; });
    EXPECT_NE(found, chosen.statistics.end()) << name;
    return found == chosen.statistics.end() ? -1.0 : found->second;
  };
  EXPECT_EQ(statistic("clusters"), 1);
  const char* model = statistic("trajectory model") == 1 ? "trajectory" : "shape";
  auto with = [&](const char* count) {
    return encode_mesh3d(s, cpca({{"target-kg", "1"}, {"bits", "8"}, {"model", model}, {"clusters", count}, {"components", "4096"}})).stream;
  };
  EXPECT_EQ(with("1"), chosen.stream);
  for (const char* other : {"2", "3", "5", "10", "20", "40"}) EXPECT_LE(chosen.stream.size(), with(other).size()) << other << " clusters";
  EXPECT_THROW(encode_mesh3d(s, cpca({{"clusters", "0"}})), Error);
  EXPECT_THROW(encode_mesh3d(s, cpca({{"components", "many"}})), Error);
}

// A target's search tries the mean shape's grid half a bit either side of
// the whole bits it settles on (2^(b ± 1/2) − 1 steps), and takes one here
// (5 clusters): its stream is no larger than those of the whole bits around
// its choice.
TEST(CpcaWpt, ATargetsMeanShapeGridMayLieHalfABitBetween) {
  const MeshSequence s = test::test_sequence(12, 6);
  const Encode3dResult chosen = encode_mesh3d(s, cpca({{"target-kg", "0.7"}, {"clusters", "5"}}));
  const auto bits = std::find_if(chosen.statistics.begin(), chosen.statistics.end(), [](const CodecStatistic& c) { return c.first == "mean shape bits"; });
  ASSERT_NE(bits, chosen.statistics.end());
  EXPECT_EQ(bits->second, 8.5);  // this sequence's, between 8 and 9
  for (const double whole : {std::floor(bits->second), std::ceil(bits->second)}) {
    const uint64_t bytes =
        encode_mesh3d(s, cpca({{"target-kg", "0.7"}, {"clusters", "5"}, {"bits", std::to_string(static_cast<int>(whole))}})).stream.size();
    EXPECT_LE(chosen.stream.size(), bytes) << whole << " bits";
  }
  const Grid whole = Grid::over(s.frames[0], 10, true), same = Grid::over_half_bits(s.frames[0], 20, true),
             half = Grid::over_half_bits(s.frames[0], 21, true);
  EXPECT_EQ(same.step, whole.step);
  EXPECT_NEAR(whole.step[0] / half.step[0], (std::sqrt(2.0) * 1024 - 1) / 1023, 1e-6);
}

// Calls visit(unit, io) for each refinement unit of a stream, io just after its unit header.
template <class Visit>
void for_each_refinement_unit(const std::vector<uint8_t>& stream, Visit visit) {
  for (const ContainerUnit& unit : split_container(stream).units) {
    BitReader reader(unit.payload.data(), unit.payload.size());
    syntax::ReadIO io(reader);
    UnitHeader header;
    syntax::describe(io, header);
    if (header.type() == UnitType::kRefinement) visit(unit, io);
  }
}

// The refinements of a stream's refinement units, in order (a group's
// list read from its bins).
std::vector<CpcaRefinementHeader> refinements(const std::vector<uint8_t>& stream) {
  const CpcaHeader header = read_headers<CpcaHeader>(split_container(stream)).second;
  std::vector<uint8_t> started(header.cluster_count, 0);
  std::vector<CpcaRefinementHeader> all;
  for_each_refinement_unit(stream, [&](const ContainerUnit&, syntax::ReadIO& io) {
    CpcaRefinement r;
    syntax::describe(io, r);
    if (r.kind == kCpcaGroup) {
      syntax::EntropyReadIO<false> symbols(r.bins, r.raw, syntax::SectionPlace{});
      syntax::CpcaGroupContexts contexts;
      syntax::describe_group_list(symbols, contexts, std::span(r.group), header.cluster_count, [&](uint32_t c) { return started[c] != 0; },
                                  [](uint32_t) { return 0u; }, [&](const CpcaRefinementHeader& h, bool) { started[h.cluster] |= h.kind == kCpcaStart; });
    }
    const std::vector<CpcaRefinementHeader> listed = r.refinements();
    all.insert(all.end(), listed.begin(), listed.end());
    for (const CpcaRefinementHeader& h : listed)
      if (h.kind == kCpcaStart) started[h.cluster] = 1;
  });
  return all;
}

// The unit_kind of every refinement but starts, counted.
std::map<uint32_t, size_t> component_kinds(const std::vector<uint8_t>& stream) {
  std::map<uint32_t, size_t> kinds;
  for (const CpcaRefinementHeader& h : refinements(stream))
    if (h.kind != kCpcaStart) ++kinds[h.kind];
  return kinds;
}

// Every component kind decodes to what the encoder reconstructed (a hash
// unit per frame checks it), each option sending the kinds it names.
TEST(CpcaWpt, EveryComponentKindDecodesAsTheEncoderReconstructs) {
  const MeshSequence s = test::test_sequence(12, 8);
  const struct {
    CodecOptionValues values;
    std::set<uint32_t> kinds;
  } cases[] = {
      {{{"model", "shape"}, {"basis", "index"}}, {kCpcaComponent}},
      {{{"model", "shape"}, {"basis", "mesh"}}, {kCpcaMeshComponent}},
      {{{"model", "trajectory"}}, {kCpcaTrajectory}},
  };
  for (const auto& c : cases) {
    Encode3dOptions options = cpca(c.values);
    options.codec_options["clusters"] = "3";
    options.hash_group = 1;
    const std::vector<uint8_t> stream = encode_mesh3d(s, options).stream;
    std::set<uint32_t> kinds;
    for (const auto& [kind, count] : component_kinds(stream)) kinds.insert(kind);
    EXPECT_EQ(kinds, c.kinds) << c.values.at("model");
    const MeshSequence decoded = decode_mesh3d(stream);  // throws on a hash mismatch
    EXPECT_LT(kg_error(s, decoded), 5.0);
  }
}

// Groups (unit_kind 4) carry the refinements that units of their own
// carry: the same ones, decoding to the same animation bit for bit (the
// decoder's sums do not depend on their order), in fewer bytes, for every
// component kind.
TEST(CpcaWpt, GroupsDecodeAsTheirRefinementsAloneInFewerBytes) {
  const MeshSequence s = test::test_sequence(12, 8);
  for (const CodecOptionValues& model : {CodecOptionValues{{"model", "shape"}, {"basis", "index"}},
                                         CodecOptionValues{{"model", "shape"}, {"basis", "mesh"}}, CodecOptionValues{{"model", "trajectory"}}}) {
    auto encoded = [&](const char* group_bytes) {
      CodecOptionValues values = model;
      values["clusters"] = "3";
      values["group-bytes"] = group_bytes;
      return encode_mesh3d(s, cpca(values)).stream;
    };
    const std::vector<uint8_t> alone = encoded("0"), grouped = encoded("1000000");
    EXPECT_EQ(split_container(grouped).units.size(), 3u) << "the base mesh, one group, a group hash";
    EXPECT_EQ(component_kinds(grouped), component_kinds(alone));
    EXPECT_EQ(refinements(grouped).size(), refinements(alone).size());
    EXPECT_LT(grouped.size(), alone.size());
    EXPECT_EQ(decode_mesh3d(grouped).frames, decode_mesh3d(alone).frames) << model.at("model");
  }
}

// The refinement units' payload bytes, in order.
std::vector<size_t> refinement_unit_bytes(const std::vector<uint8_t>& stream) {
  std::vector<size_t> bytes;
  for_each_refinement_unit(stream, [&](const ContainerUnit& unit, syntax::ReadIO&) { bytes.push_back(unit.payload.size()); });
  return bytes;
}

// A 24 × 24 sheet, its vertices numbered in a scrambled order, waving in
// two travelling waves: smooth over the surface, not along the numbers.
MeshSequence scrambled_waving_sheet(int frames) {
  constexpr int n = 24;
  std::vector<NodeIndex> number((n + 1) * (n + 1));
  for (size_t i = 0; i < number.size(); ++i) number[i] = static_cast<NodeIndex>((i * 331) % number.size());
  MeshSequence s;
  s.vertex_count = static_cast<uint32_t>(number.size());
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const NodeIndex a = number[y * (n + 1) + x], b = number[y * (n + 1) + x + 1], c = number[(y + 1) * (n + 1) + x],
                      d = number[(y + 1) * (n + 1) + x + 1];
      s.faces.push_back({{a, b, d}});
      s.faces.push_back({{a, d, c}});
    }
  for (int f = 0; f < frames; ++f) {
    std::vector<Vec3> frame(number.size());
    for (int y = 0; y <= n; ++y)
      for (int x = 0; x <= n; ++x)
        frame[number[y * (n + 1) + x]] = {x / double{n}, y / double{n}, 0.2 * std::sin(0.3 * x + 0.4 * f) + 0.1 * std::cos(0.25 * y - 0.3 * f)};
    s.frames.push_back(std::move(frame));
  }
  return s;
}

// --group-growth F: group k fills to about B · F^k bytes, at most 4 B,
// where B is --group-bytes; the same refinements in fewer units and bytes.
TEST(CpcaWpt, GroupsGrowByTheirFactorUpToFourTimesTheFirst) {
  const MeshSequence s = scrambled_waving_sheet(24);
  auto encoded = [&](const char* group_bytes, const char* growth) {
    const CodecOptionValues values{{"clusters", "4"}, {"components", "4096"}, {"noise", "-4"}, {"group-bytes", group_bytes}, {"group-growth", growth}};
    return encode_mesh3d(s, cpca(values)).stream;
  };
  const std::vector<uint8_t> fixed = encoded("50", "1"), doubling = encoded("50", "2"), capped = encoded("50", "16");
  const std::vector<size_t> fixed_units = refinement_unit_bytes(fixed), doubling_units = refinement_unit_bytes(doubling),
                            capped_units = refinement_unit_bytes(capped), single_units = refinement_unit_bytes(encoded("0", "1"));
  ASSERT_GE(fixed_units.size(), 30u) << "the test needs a long run of refinements";
  EXPECT_LT(doubling_units.size(), fixed_units.size());
  EXPECT_LT(doubling.size(), fixed.size());
  EXPECT_EQ(refinements(doubling).size(), refinements(fixed).size());
  EXPECT_EQ(decode_mesh3d(doubling).frames, decode_mesh3d(fixed).frames);
  // A group closes once its refinements' planned bytes reach its limit: each but the last holds at least half of it.
  for (size_t k = 0; k + 1 < doubling_units.size(); ++k) {
    const double limit = std::min(50.0 * std::pow(2.0, static_cast<double>(k)), 200.0);
    EXPECT_GT(static_cast<double>(doubling_units[k]), 0.5 * limit) << "group " << k;
  }
  // Growth 16 reaches the cap at the second group: from there on, groups
  // of about 200 bytes, each below 200 and one refinement (its own unit's bytes).
  const size_t largest = *std::max_element(single_units.begin(), single_units.end());
  const size_t total = std::accumulate(capped_units.begin(), capped_units.end(), size_t{0});
  EXPECT_GE(capped_units.size(), total / (200 + largest)) << total << " bytes";
  for (size_t k = 1; k + 1 < capped_units.size(); ++k) EXPECT_LT(capped_units[k], 200 + largest) << "group " << k;
}

// Per shape component, --basis auto sends the smaller of unit_kind 1 and 2:
// never more bytes than either alone; on a smooth surface numbered out of
// order the mesh prediction wins.
TEST(CpcaWpt, TheBasisPredictionChosenPerComponentIsNeverLarger) {
  const MeshSequence s = scrambled_waving_sheet(16);
  auto bytes = [&](const char* basis) {
    return encode_mesh3d(s, cpca({{"model", "shape"}, {"basis", basis}, {"clusters", "2"}, {"noise", "-2"}})).stream.size();
  };
  const size_t index = bytes("index"), mesh = bytes("mesh"), either = bytes("auto");
  EXPECT_LE(either, index);
  EXPECT_LE(either, mesh);
  EXPECT_LT(either, index);
}

// A tumbling rigid body: each vertex's trajectory is R(t) p, a combination
// of its 3 rest coordinates (rank 3 over the trajectories), while the
// shapes over time mix the 9 functions of R(t) (rank up to 9): the
// trajectory components take fewer units and fewer bytes.
TEST(CpcaWpt, TrajectoriesCodeATumblingBodyInFewerComponents) {
  MeshSequence s = test::test_sequence(1, 1);
  const std::vector<Vec3> rest = s.frames[0];
  s.frames.clear();
  for (int f = 0; f < 40; ++f) {
    const double a = 0.11 * f, b = 0.07 * f + 0.3 * std::sin(0.2 * f);
    std::vector<Vec3> frame;
    for (const Vec3& p : rest) {
      const double x = std::cos(a) * p.x - std::sin(a) * p.y, y = std::sin(a) * p.x + std::cos(a) * p.y;  // about z
      frame.push_back({x, std::cos(b) * y - std::sin(b) * p.z, std::sin(b) * y + std::cos(b) * p.z});    // then about x
    }
    s.frames.push_back(std::move(frame));
  }
  auto encoded = [&](const char* model) {
    return encode_mesh3d(s, cpca({{"model", model}, {"basis", "index"}, {"clusters", "1"}, {"noise", "2"}})).stream;
  };
  const std::vector<uint8_t> trajectories = encoded("trajectory"), shapes = encoded("shape");
  EXPECT_LE(component_kinds(trajectories)[kCpcaTrajectory], 3u);
  EXPECT_GE(component_kinds(shapes)[kCpcaComponent], 5u);
  EXPECT_LT(trajectories.size(), shapes.size());
  EXPECT_LT(kg_error(s, decode_mesh3d(trajectories)), kg_error(s, decode_mesh3d(shapes)) + 0.05);
}

TEST(CpcaWpt, UnknownModelOrBasisIsAUsageError) {
  const MeshSequence s = test::test_sequence(4, 1);
  for (const CodecOptionValues& values : {CodecOptionValues{{"model", "trajectories"}}, CodecOptionValues{{"basis", "parallelogram"}}}) {
    try {
      encode_mesh3d(s, cpca(values));
      ADD_FAILURE() << values.begin()->first;
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::kUsage);
      EXPECT_NE(e.message().find("--" + values.begin()->first), std::string::npos) << e.message();
    }
  }
}

// A target's search (models, cluster counts, the mean shape's bits) runs
// its candidates side by side and keeps the same stream on any number of
// threads.
TEST(CpcaWpt, TheSearchKeepsTheSameStreamOnOneThreadAndOnSeveral) {
  const MeshSequence s = test::test_sequence(12, 4);
  Encode3dOptions one = cpca({{"target-kg", "1"}, {"model", "auto"}, {"basis", "auto"}}), several = one;
  one.threads = 1;
  several.threads = 4;
  EXPECT_EQ(encode_mesh3d(s, one).stream, encode_mesh3d(s, several).stream);
}

TEST(CpcaWpt, CorruptAndTruncatedStreamsFailCleanly) {
  EXPECT_GT(test::decode_damaged_mesh3d(encode_mesh3d(test::test_sequence(6, 2), cpca({{"clusters", "3"}})).stream, 41, 5), 0);
}

// The report's claim on real sequences: weighted progressive transmission
// reaches every quality with no more bytes than round robin (compared as
// rate–distortion curves at the KG errors RPT reaches after a tenth, two
// tenths, … of its units), and the error never grows from one unit to the
// next.
TEST(CpcaWptRealData, WptNeverNeedsMoreBytesThanRpt) {
  for (const char* name : {"pcow", "horse-gallop"}) {
    if (!fs::exists(kData / name)) GTEST_SKIP() << "../shared/data/" << name << " is absent";
    const MeshSequence s = load_sequence((kData / name).string());
    // The report's operators (shape components, basis in index order), a unit each.
    const auto wpt = curve(encode_mesh3d(s, cpca({{"model", "shape"}, {"basis", "index"}, {"group-bytes", "0"}})).stream, s);
    const auto rpt = curve(encode_mesh3d(s, cpca({{"model", "shape"}, {"basis", "index"}, {"group-bytes", "0"}, {"order", "rpt"}})).stream, s);
    for (size_t k = 1; k < wpt.size(); ++k) EXPECT_LE(wpt[k].second, wpt[k - 1].second) << name << " unit " << k;
    for (int checkpoint = 1; checkpoint <= 10; ++checkpoint) {
      const double kg = rpt[(rpt.size() - 1) * static_cast<size_t>(checkpoint) / 10].second;
      EXPECT_LE(bytes_to_reach(wpt, kg), bytes_to_reach(rpt, kg)) << name << " at KG " << kg;
    }
  }
}

}  // namespace
}  // namespace m4mesh
