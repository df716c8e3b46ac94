#include "encoder/mesh3d/quality_target.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>

#include "codecs3d/registry.h"
#include "common/error.h"
#include "common/parallel.h"
#include "encoder/mesh3d/base_mesh.h"
#include "encoder/mesh3d/codec_encoders.h"
#include "mesh3d/metrics.h"

namespace m4mesh {

namespace {


bool has_option(const Codec3d& codec, const std::string& name) {
  const std::vector<CodecOption>& options = codec_encoding(codec).options;
  return std::any_of(options.begin(), options.end(), [&](const CodecOption& o) { return o.name == name; });
}

// Encodes and measures the decoder's output (the encoder's closed loop
// knows it exactly: it is what the hash units cover).
TargetTrial trial(const MeshSequence& s, Encode3dOptions options, const QualityTarget& target, const std::string& parameter,
                  Encode3dResult& result) {
  options.keep_decoded = true;
  result = encode_mesh3d(s, options);
  std::optional<MeshSequence> reordered;
  if (!result.input_of.empty()) reordered = renumbered(s, result.input_of);
  const MeshSequence& original = reordered ? *reordered : s;
  TargetTrial t{options.codec, parameter, result.stream.size(), kg_error(original, result.decoded), psnr(original, result.decoded), false};
  t.meets = target.kg ? t.kg <= *target.kg : t.psnr >= *target.psnr;
  return t;
}

}  // namespace

void check_target(const QualityTarget& target) {
  if (target.kg.has_value() == target.psnr.has_value()) throw usage_error("give one quality target: --target-kg or --target-psnr");
  const double value = target.kg ? *target.kg : *target.psnr;
  if (!std::isfinite(value) || value <= 0)
    throw usage_error(std::string(target.kg ? "--target-kg " : "--target-psnr ") + std::to_string(value) + ": a target is a finite number above 0" +
                      (target.kg ? " (percent)" : " (dB)"));
}

Encode3dResult encode_to_target(const MeshSequence& s, const Encode3dOptions& options, const QualityTarget& target,
                                const TrialReport& report) {
  check_target(target);
  check_sequence(s);
  const Codec3d& codec = codec3d_by_name(options.codec);
  Encode3dResult result;
  if (target.kg && has_option(codec, "target-kg")) {
    Encode3dOptions own = options;
    own.codec_options["target-kg"] = std::to_string(*target.kg);
    const TargetTrial t = trial(s, own, target, "its own search", result);
    report(t);
    if (!t.meets) throw usage_error("the target is out of reach for " + codec.name);
    return result;
  }
  const QualityKnob& knob = codec_encoding(codec).quality;
  if (knob.coarse_to_fine.empty()) throw usage_error(codec.name + " has no quality parameter to search");
  if (options.codec_options.count(knob.option))
    throw usage_error("--" + knob.option + " and a quality target: the target chooses --" + knob.option + " (" + codec.name + ")");
  // The smallest index that meets the target, by bisection; results kept
  // by index. A setting that cannot code the sequence counts as missing it
  // (reported, not fatal); the search starts at the finest that codes.
  std::map<size_t, Encode3dResult> results;
  auto meets = [&](size_t index) -> std::optional<bool> {
    Encode3dOptions tried = options;
    const std::string parameter = "--" + knob.option + " " + knob.coarse_to_fine[index];
    tried.codec_options[knob.option] = knob.coarse_to_fine[index];
    for (const auto& [name, value] : knob.beside) tried.codec_options.try_emplace(name, value);
    try {
      const TargetTrial t = trial(s, tried, target, parameter, results[index]);
      report(t);
      return t.meets;
    } catch (const Error& e) {
      if (e.kind() != ErrorKind::kInput && e.kind() != ErrorKind::kLimit) throw;
      report(TargetTrial{codec.name, parameter + " cannot code the sequence: " + e.message(), 0, 0, 0, false});
      return std::nullopt;
    }
  };
  size_t lo = 0, hi = knob.coarse_to_fine.size() - 1;
  std::optional<bool> finest = meets(hi);
  while (!finest && hi > 0) finest = meets(--hi);
  if (!finest) throw usage_error(codec.name + " cannot code the sequence at any --" + knob.option);
  if (!*finest)
    throw usage_error("the target is out of reach for " + codec.name + " even at --" + knob.option + " " + knob.coarse_to_fine[hi]);
  while (lo < hi) {
    const size_t mid = lo + (hi - lo) / 2;
    if (meets(mid).value_or(false))
      hi = mid;
    else
      lo = mid + 1;
  }
  return std::move(results[hi]);
}

Encode3dResult encode_smallest(const MeshSequence& s, const Encode3dOptions& options, const QualityTarget& target,
                               const TrialReport& report_codec, std::string& chosen) {
  check_target(target);
  check_sequence(s);
  // Each codec's search on a thread of its own; reported in registry order.
  const std::span<const Codec3d> codecs = codecs3d();
  struct Search {
    Encode3dResult result;
    TargetTrial last;
    bool met = false;
  };
  std::vector<Search> searches(codecs.size());
  const bool alone = worker_count(options.threads) == 1;
  parallel_for(
      codecs.size(), options.threads,
      [&](size_t k) {
        Encode3dOptions tried = options;
        tried.codec = codecs[k].name;
        if (!alone) tried.progress = nullptr;  // trials on other threads would mix their progress
        Search& search = searches[k];
        try {
          search.result = encode_to_target(s, tried, target, [&](const TargetTrial& t) {
            if (t.meets || search.last.codec.empty()) search.last = t;
          });
          search.met = true;
        } catch (const Error& e) {
          // A codec that misses the target or cannot code the sequence is left out.
          if (e.kind() != ErrorKind::kUsage && e.kind() != ErrorKind::kInput && e.kind() != ErrorKind::kLimit) throw;
          search.last.codec = codecs[k].name;
          search.last.parameter = e.message();
          search.last.meets = false;
        }
      },
      [&](size_t k) { report_codec(searches[k].last); });
  Encode3dResult* best = nullptr;
  for (size_t k = 0; k < codecs.size(); ++k)
    if (searches[k].met && (!best || searches[k].result.stream.size() < best->stream.size())) {
      best = &searches[k].result;
      chosen = codecs[k].name;
    }
  if (!best) throw usage_error("no codec reaches the target");
  return std::move(*best);
}

}  // namespace m4mesh
