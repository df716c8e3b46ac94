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

bool large(const FrameSource& s) { return uint64_t{s.vertex_count()} * s.frame_count() > kWholeSearchVertexFrames; }

// Encodes and measures the decoder's output (the encoder's closed loop
// knows it exactly: it is what the hash units cover).
TargetTrial trial(const FrameSource& s, Encode3dOptions options, const QualityTarget& target, const std::string& parameter,
                  Encode3dResult& result) {
  options.measure = true;
  result = encode_mesh3d(s, options);
  TargetTrial t{options.codec, parameter, "", result.stream_bytes, result.kg, result.psnr, false,
                static_cast<double>(s.vertex_count()) * s.frame_count()};
  t.max_error = result.max_error;
  t.meets = target.met_by(t.kg, t.psnr, t.max_error);
  return t;
}

// What a search chose: the codec options it sets, and for a knob its
// place among the knob's values.
struct Setting {
  CodecOptionValues options;
  std::string parameter;
  std::optional<size_t> knob;
};

// A setting's stream of the frames searched (in memory).
struct Found {
  Setting setting;
  Encode3dResult result;
};

// The codec's own search, or the knob's values by bisection, on `s`; the
// trials' streams stay in memory.
Found search(const FrameSource& s, Encode3dOptions options, const QualityTarget& target, const TrialReport& report) {
  options.output = nullptr;
  const Codec3d& codec = codec3d_by_name(options.codec);
  if (target.kg && has_option(codec, "target-kg")) {
    Found found{{{{"target-kg", std::to_string(*target.kg)}}, "its own search", std::nullopt}, {}};
    Encode3dOptions own = options;
    own.codec_options.insert(found.setting.options.begin(), found.setting.options.end());
    const TargetTrial t = trial(s, own, target, found.setting.parameter, found.result);
    report(t);
    if (!t.meets) throw usage_error("the target is out of reach for " + codec.name);
    return found;
  }
  const QualityKnob& knob = codec_encoding(codec).quality;
  if (knob.coarse_to_fine.empty()) throw usage_error(codec.name + " has no quality parameter to search");
  if (options.codec_options.count(knob.option))
    throw usage_error("--" + knob.option + " and a quality target: the target chooses --" + knob.option + " (" + codec.name + ")");
  // The smallest index that meets the target, by bisection; results kept
  // by index. A setting that cannot code the sequence counts as missing it
  // (reported, not fatal); the search starts at the finest that codes.
  std::map<size_t, Found> results;
  auto meets = [&](size_t index) -> std::optional<bool> {
    Found& found = results[index];
    found.setting = {{{knob.option, knob.coarse_to_fine[index]}}, "--" + knob.option + " " + knob.coarse_to_fine[index], index};
    for (const auto& [name, value] : knob.beside) found.setting.options.try_emplace(name, value);
    Encode3dOptions tried = options;
    for (const auto& [name, value] : found.setting.options) tried.codec_options.try_emplace(name, value);
    try {
      const TargetTrial t = trial(s, tried, target, found.setting.parameter, found.result);
      report(t);
      return t.meets;
    } catch (const Error& e) {
      if (e.kind() != ErrorKind::kInput && e.kind() != ErrorKind::kLimit) throw;
      report(TargetTrial{codec.name, found.setting.parameter + " cannot code the sequence: " + e.message(), 0, 0, 0, false});
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

// The whole sequence at the setting found on its sample, streamed to the
// output; while it misses the target, once more a knob value finer (or
// the codec's own search aiming as much lower as it missed by).
Encode3dResult code_whole(const FrameSource& s, const Encode3dOptions& options, const QualityTarget& target, Setting setting,
                          const TrialReport& report) {
  const Codec3d& codec = codec3d_by_name(options.codec);
  const QualityKnob& knob = codec_encoding(codec).quality;
  for (int attempt = 0;; ++attempt) {
    Encode3dOptions whole = options;
    for (const auto& [name, value] : setting.options) whole.codec_options[name] = value;
    Encode3dResult result;
    TargetTrial t = trial(s, whole, target, setting.parameter, result);
    t.note = "the whole sequence";
    report(t);
    if (t.meets) return result;
    if (setting.knob && *setting.knob + 1 < knob.coarse_to_fine.size()) {
      const size_t finer = *setting.knob + 1;
      setting = {{{knob.option, knob.coarse_to_fine[finer]}}, "--" + knob.option + " " + knob.coarse_to_fine[finer], finer};
      for (const auto& [name, value] : knob.beside) setting.options.try_emplace(name, value);
    } else if (!setting.knob && attempt < 3 && t.kg > 0) {
      setting.options["target-kg"] = std::to_string(std::stod(setting.options["target-kg"]) * 0.98 * *target.kg / t.kg);
    } else {
      throw usage_error("the target is out of reach for " + codec.name + " on the whole sequence");
    }
    if (!options.restart_output && options.output)
      throw usage_error("the whole sequence missed the target at the setting its sample chose; write to a file (its bytes are taken back "
                        "for another try), not to standard output or a pipe");
    if (options.restart_output) options.restart_output();
  }
}

}  // namespace

void check_target(const QualityTarget& target) {
  if (target.kg.has_value() + target.psnr.has_value() + target.max_error.has_value() != 1)
    throw usage_error("give one quality target: --target-kg, --target-psnr or --max-error");
  const double value = target.kg ? *target.kg : target.psnr ? *target.psnr : *target.max_error;
  const char* name = target.kg ? "--target-kg " : target.psnr ? "--target-psnr " : "--max-error ";
  const char* unit = target.kg ? " (percent)" : target.psnr ? " (dB)" : " (the model's units)";
  if (!std::isfinite(value) || value <= 0) throw usage_error(name + std::to_string(value) + ": a target is a finite number above 0" + unit);
}

std::vector<uint32_t> sample_frames(uint32_t vertex_count, uint32_t frame_count) {
  const uint64_t fit = std::max<uint64_t>(1, kSampleVertexFrames / vertex_count);
  const uint32_t total = static_cast<uint32_t>(std::min<uint64_t>(fit, frame_count));
  const uint32_t runs = std::clamp<uint32_t>(total / 16, 1, kSampleRuns);
  std::vector<uint32_t> frames;
  for (uint32_t r = 0; r < runs; ++r) {
    const uint32_t length = total / runs + (r < total % runs ? 1 : 0);
    // Run r starts at the r-th of `runs` equal parts of the sequence.
    const uint32_t first = static_cast<uint32_t>(uint64_t{frame_count - length} * r / std::max<uint32_t>(runs - 1, 1));
    for (uint32_t f = first; f < first + length; ++f) frames.push_back(f);
  }
  return frames;
}

Encode3dResult encode_to_target(const FrameSource& s, const Encode3dOptions& options, const QualityTarget& target, const TrialReport& report) {
  check_target(target);
  s.scan();
  if (large(s)) {
    const ClipSource sample(s, sample_frames(s.vertex_count(), s.frame_count()));
    const std::string on_sample = "on a sample of " + std::to_string(sample.frame_count()) + " frames";
    Found found = search(sample, options, target, [&](TargetTrial t) {
      t.note = on_sample;
      report(t);
    });
    return code_whole(s, options, target, found.setting, report);
  }
  Encode3dResult result = search(s, options, target, report).result;
  if (options.output) {
    options.output(result.stream);
    result.stream.clear();
  }
  return result;
}

Encode3dResult encode_to_target(const MeshSequence& s, const Encode3dOptions& options, const QualityTarget& target, const TrialReport& report) {
  return encode_to_target(SequenceSource(s), options, target, report);
}

Encode3dResult encode_smallest(const FrameSource& whole, const Encode3dOptions& options, const QualityTarget& target,
                               const TrialReport& report_codec, std::string& chosen) {
  check_target(target);
  whole.scan();
  const std::optional<ClipSource> sample =
      large(whole) ? std::optional<ClipSource>(std::in_place, whole, sample_frames(whole.vertex_count(), whole.frame_count())) : std::nullopt;
  const FrameSource& s = sample ? static_cast<const FrameSource&>(*sample) : whole;
  const std::string on_sample = sample ? "on a sample of " + std::to_string(sample->frame_count()) + " frames" : "";
  // Each codec's search on a thread of its own; reported in registry order.
  const std::span<const Codec3d> codecs = codecs3d();
  struct Search {
    Found found;
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
        Search& search_k = searches[k];
        try {
          search_k.found = search(s, tried, target, [&](const TargetTrial& t) {
            if (t.meets || search_k.last.codec.empty()) search_k.last = t;
          });
          search_k.met = true;
        } catch (const Error& e) {
          // A codec that misses the target or cannot code the sequence is left out.
          if (e.kind() != ErrorKind::kUsage && e.kind() != ErrorKind::kInput && e.kind() != ErrorKind::kLimit) throw;
          search_k.last.codec = codecs[k].name;
          search_k.last.parameter.clear();
          search_k.last.note = e.message();
          search_k.last.meets = false;
        }
      },
      [&](size_t k) {
        TargetTrial t = searches[k].last;
        if (searches[k].met) t.note = on_sample;
        report_codec(t);
      });
  Search* best = nullptr;
  for (size_t k = 0; k < codecs.size(); ++k)
    if (searches[k].met && (!best || searches[k].found.result.stream_bytes < best->found.result.stream_bytes)) {
      best = &searches[k];
      chosen = codecs[k].name;
    }
  if (!best) throw usage_error("no codec reaches the target");
  if (sample) {
    Encode3dOptions kept = options;
    kept.codec = chosen;
    return code_whole(whole, kept, target, best->found.setting, report_codec);
  }
  Encode3dResult result = std::move(best->found.result);
  if (options.output) {
    options.output(result.stream);
    result.stream.clear();
  }
  return result;
}

Encode3dResult encode_smallest(const MeshSequence& s, const Encode3dOptions& options, const QualityTarget& target,
                               const TrialReport& report_codec, std::string& chosen) {
  return encode_smallest(SequenceSource(s), options, target, report_codec, chosen);
}

}  // namespace m4mesh
