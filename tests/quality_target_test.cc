// Quality targets for every codec: the kept stream meets the target as the
// metrics measure its decoding, the next coarser setting misses it, and
// --codec auto keeps the smallest of the codecs.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "codecs3d/registry.h"
#include "decoder/mesh3d/container_decoder.h"
#include "encoder/mesh3d/codec_encoders.h"
#include "encoder/mesh3d/quality_target.h"
#include "mesh3d/metrics.h"
#include "tests/test_util.h"

namespace m4mesh {
namespace {

const char* const kCodecs[] = {"bfs3d", "affine-octree", "lcc", "cpca-wpt"};

TEST(QualityTarget, EveryCodecMeetsAKgTargetWithItsCoarsestSetting) {
  const MeshSequence s = test::test_sequence(8, 21);
  for (const char* name : kCodecs) {
    Encode3dOptions options;
    options.codec = name;
    std::vector<TargetTrial> trials;
    const Encode3dResult r = encode_to_target(s, options, {.kg = 1.0}, [&](const TargetTrial& t) { trials.push_back(t); });
    const MeshSequence decoded = decode_mesh3d(r.stream);
    EXPECT_LE(kg_error(s, decoded), 1.0) << name;
    ASSERT_FALSE(trials.empty());
    // The kept trial is the last that met the target; every trial coarser than it missed.
    const QualityKnob& knob = codec_encoding(codec3d_by_name(name)).quality;
    const auto kept = std::find_if(trials.rbegin(), trials.rend(), [](const TargetTrial& t) { return t.meets; });
    ASSERT_NE(kept, trials.rend()) << name;
    EXPECT_EQ(kept->bytes, r.stream.size()) << name;
    EXPECT_DOUBLE_EQ(kept->kg, kg_error(s, decoded)) << name;
    if (kept->parameter.rfind("--", 0) != 0) continue;  // the codec's own search
    const std::string value = kept->parameter.substr(kept->parameter.find(' ') + 1);
    const size_t index = static_cast<size_t>(std::find(knob.coarse_to_fine.begin(), knob.coarse_to_fine.end(), value) - knob.coarse_to_fine.begin());
    ASSERT_LT(index, knob.coarse_to_fine.size()) << name;
    if (index == 0) continue;
    options.codec_options[knob.option] = knob.coarse_to_fine[index - 1];
    EXPECT_GT(kg_error(s, decode_mesh3d(encode_mesh3d(s, options).stream)), 1.0) << name << " at " << knob.coarse_to_fine[index - 1];
  }
}

// --max-error: no decoded vertex farther from its original than the target
// (measured as `m4mesh metrics` measures it), one knob value coarser farther.
TEST(QualityTarget, EveryCodecMeetsAMaxErrorWithItsCoarsestSetting) {
  const MeshSequence s = test::test_sequence(8, 24);
  const double target = 0.0015 * diameter(s.frames[0]);
  for (const char* name : kCodecs) {
    Encode3dOptions options;
    options.codec = name;
    std::vector<TargetTrial> trials;
    const Encode3dResult r = encode_to_target(s, options, {.max_error = target}, [&](const TargetTrial& t) { trials.push_back(t); });
    const double reached = compare_sequences(s, decode_mesh3d(r.stream)).max_error;
    EXPECT_LE(reached, target) << name;
    const auto kept = std::find_if(trials.rbegin(), trials.rend(), [](const TargetTrial& t) { return t.meets; });
    ASSERT_NE(kept, trials.rend()) << name;
    EXPECT_DOUBLE_EQ(kept->max_error, reached) << name;
    const QualityKnob& knob = codec_encoding(codec3d_by_name(name)).quality;
    const std::string value = kept->parameter.substr(kept->parameter.find(' ') + 1);
    const size_t index = static_cast<size_t>(std::find(knob.coarse_to_fine.begin(), knob.coarse_to_fine.end(), value) - knob.coarse_to_fine.begin());
    ASSERT_LT(index, knob.coarse_to_fine.size()) << name << ": " << kept->parameter;
    EXPECT_GT(index, 0u) << name << ": the target is met at the coarsest setting, so nothing shows it chose well";
    if (index == 0) continue;
    options.codec_options[knob.option] = knob.coarse_to_fine[index - 1];
    for (const auto& [option, beside] : knob.beside) options.codec_options.try_emplace(option, beside);
    EXPECT_GT(compare_sequences(s, decode_mesh3d(encode_mesh3d(s, options).stream)).max_error, target) << name << " at " << knob.coarse_to_fine[index - 1];
  }
}

TEST(QualityTarget, PsnrTargetsAndTheSmallestCodec) {
  const MeshSequence s = test::test_sequence(8, 22);
  Encode3dOptions options;
  options.codec = "affine-octree";
  const Encode3dResult r = encode_to_target(s, options, {.psnr = 50}, [](const TargetTrial&) {});
  EXPECT_GE(psnr(s, decode_mesh3d(r.stream)), 50);
  std::string chosen;
  std::vector<TargetTrial> best;
  const Encode3dResult smallest = encode_smallest(s, options, {.kg = 2.0}, [&](const TargetTrial& t) { best.push_back(t); }, chosen);
  for (const TargetTrial& t : best) {
    if (t.meets) {
      EXPECT_LE(smallest.stream.size(), t.bytes) << t.codec;
    }
  }
  EXPECT_EQ(decode_mesh3d(smallest.stream).frames.size(), s.frames.size());
  EXPECT_FALSE(chosen.empty());
}

TEST(QualityTarget, CodecAutoKeepsTheSameStreamOnOneThreadAndOnSeveral) {
  const MeshSequence s = test::test_sequence(6, 24);
  std::string one_chosen, many_chosen;
  std::vector<TargetTrial> one_trials, many_trials;
  Encode3dOptions one, many;
  one.threads = 1;
  many.threads = 4;
  const Encode3dResult a = encode_smallest(s, one, {.kg = 1.0}, [&](const TargetTrial& t) { one_trials.push_back(t); }, one_chosen);
  const Encode3dResult b = encode_smallest(s, many, {.kg = 1.0}, [&](const TargetTrial& t) { many_trials.push_back(t); }, many_chosen);
  EXPECT_EQ(a.stream, b.stream);
  EXPECT_EQ(one_chosen, many_chosen);
  // codecs3d(), not kCodecs: a whole-binary run also holds registry_test's toy codecs.
  const std::span<const Codec3d> codecs = codecs3d();
  ASSERT_EQ(one_trials.size(), codecs.size());
  ASSERT_EQ(many_trials.size(), one_trials.size());
  for (size_t k = 0; k < one_trials.size(); ++k) {
    EXPECT_EQ(many_trials[k].codec, codecs[k].name);  // reported in registry order
    EXPECT_EQ(many_trials[k].codec, one_trials[k].codec);
    EXPECT_EQ(many_trials[k].parameter, one_trials[k].parameter);
    EXPECT_EQ(many_trials[k].bytes, one_trials[k].bytes);
    EXPECT_EQ(many_trials[k].kg, one_trials[k].kg);
  }
}

// A subject that walks 12 times its own size per frame: at 24 bits no grid
// over the first frame's box holds the last frames (±2^26 steps are 4
// boxes), the grid over every frame's box does.
MeshSequence walking_away() {
  MeshSequence s = test::test_sequence(6, 23);
  const auto [lo, hi] = std::minmax_element(s.frames[0].begin(), s.frames[0].end(), [](const Vec3& a, const Vec3& b) { return a.x < b.x; });
  const double size = hi->x - lo->x;
  for (size_t f = 0; f < s.frames.size(); ++f)
    for (Vec3& v : s.frames[f]) v.x += 12 * size * static_cast<double>(f);
  return s;
}

TEST(QualityTarget, ASubjectThatLeavesTheFirstFramesBoxEncodesAtEverySetting) {
  const MeshSequence s = walking_away();
  for (const char* codec : {"bfs3d", "affine-octree", "lcc"}) {
    Encode3dOptions options;
    options.codec = codec;
    options.codec_options["bits"] = "24";
    const MeshSequence decoded = decode_mesh3d(encode_mesh3d(s, options).stream);
    EXPECT_LT(kg_error(s, decoded), 1.0) << codec;
  }
  std::string chosen;
  const Encode3dResult best = encode_smallest(s, Encode3dOptions{}, {.kg = 1}, [](const TargetTrial&) {}, chosen);
  EXPECT_LE(kg_error(s, decode_mesh3d(best.stream)), 1.0);
}

TEST(QualityTarget, UnreachableAndConflictingTargetsAreUsageErrors) {
  const MeshSequence s = test::test_sequence(4, 23);
  Encode3dOptions options;
  EXPECT_THROW(encode_to_target(s, options, {}, [](const TargetTrial&) {}), Error);
  for (const QualityTarget& nonsense : {QualityTarget{.kg = -1}, QualityTarget{.kg = 0}, QualityTarget{.kg = std::nan("")},
                                        QualityTarget{.psnr = -5}, QualityTarget{.psnr = INFINITY}, QualityTarget{.kg = 1, .psnr = 40},
                                        QualityTarget{.max_error = 0}, QualityTarget{.kg = 1, .max_error = 0.1}}) {
    try {
      encode_to_target(s, options, nonsense, [](const TargetTrial&) { ADD_FAILURE() << "a trial for a target that is not one"; });
      ADD_FAILURE() << "accepted";
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::kUsage) << e.what();
    }
  }
  EXPECT_THROW(encode_to_target(s, options, {.kg = 1e-9}, [](const TargetTrial&) {}), Error);
  options.codec_options["bits"] = "12";
  EXPECT_THROW(encode_to_target(s, options, {.kg = 1}, [](const TargetTrial&) {}), Error);
}

}  // namespace
}  // namespace m4mesh
