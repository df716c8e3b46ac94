#include <filesystem>

#include "cli/encode3d.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <fstream>
#include <cstdio>
#include <iostream>
#include <set>

#include "cli/console.h"
#include "cli/gltf.h"
#include "cli/sequence_files.h"
#include "codecs3d/registry.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "encoder/mesh3d/codec_encoders.h"
#include "encoder/mesh3d/container_encoder.h"
#include "encoder/mesh3d/quality_target.h"
#include "syntax/mesh3d/base_mesh.h"

namespace m4mesh {

namespace fs = std::filesystem;

namespace {

using console::say;

// The frames to code and their rate: a glTF animation baked, or a sequence
// (read frame by frame when large: open_sequence).
std::pair<std::unique_ptr<FrameSource>, double> read_input(const Encode3dArgs& args) {
  if (is_gltf_path(args.input)) {
    GltfAnimation animation = read_gltf(args.input, {.mesh = args.gltf_mesh, .animation = args.gltf_animation, .fps = args.fps});
    console::detail("%s: animation baked at %.6g frames a second%s", args.input.c_str(), animation.fps, args.fps ? "" : " (its keyframes)");
    return {std::make_unique<SequenceSource>(std::move(animation.sequence)), animation.fps};
  }
  if (!args.gltf_mesh.empty() || !args.gltf_animation.empty()) throw usage_error("--mesh and --animation choose in a glTF input (.glb or .gltf)");
  return {open_sequence(args.input, !console::quiet()), args.fps.value_or(25)};
}

// Whether a file starts as a mesh3d stream (its first 4 bytes).
bool starts_as_stream(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  uint8_t head[4] = {};
  in.read(reinterpret_cast<char*>(head), 4);
  return in.gcount() == 4 && is_mesh3d_stream(head);
}

}  // namespace

std::pair<uint32_t, uint32_t> frame_rate_fraction(double fps) {
  uint32_t fitting = 1;
  for (uint32_t den = 1; den <= 1000 && fps * den <= 65535; den *= 10) {
    fitting = den;
    if (std::abs(fps * den - std::round(fps * den)) < 1e-6 * fps * den) break;
  }
  return {static_cast<uint32_t>(std::max(1L, std::lround(fps * fitting))), fitting};
}

void add_codec_options(CLI::App& command, Encode3dArgs& args) {
  std::string names;
  for (const Codec3d& c : codecs3d())
    names += (names.empty() ? "" : ", ") + c.name;
  command.add_option("--codec", args.codec, "codec: " + names + ", or auto (every codec at the quality target, the smallest kept)")
      ->capture_default_str();
  command.add_option("--target-kg", args.target_kg,
                     "the smallest stream whose decoded KG error is at most this (percent), searching the codec's quality parameter");
  command.add_option("--target-psnr", args.target_psnr, "the smallest stream whose decoded PSNR is at least this (dB)");
  command.add_option("--max-error", args.max_error, "the smallest stream with no decoded vertex farther than this from its original (the model's units)");
  command.add_option("--threads", args.threads, "trials at once in --codec auto and in cpca-wpt's own search (default 0: every core this process may use; the stream kept does not depend on it)");
  // One flag per option name; codecs that share a name share the flag.
  std::set<std::string> added;
  for (const Codec3d& c : codecs3d())
    for (const CodecOption& o : codec_encoding(c).options) {
      if (o.name == "target-kg" || !added.insert(o.name).second) continue;  // the target is a flag of every codec
      std::string owners;
      for (const Codec3d& other : codecs3d())
        for (const CodecOption& p : codec_encoding(other).options)
          if (p.name == o.name) owners += (owners.empty() ? "" : ", ") + other.name;
      const std::string help = o.help + " [" + owners + "]" + (o.default_value.empty() ? "" : " (default " + o.default_value + ")");
      const std::string name = o.name;
      if (o.kind == OptionKind::kFlag)
        command.add_flag_function("--" + name, [&args, name](int64_t) { args.codec_options[name] = "1"; }, help);
      else
        command.add_option_function<std::string>("--" + name, [&args, name](const std::string& v) { args.codec_options[name] = v; }, help);
    }
}

Encode3dOptions encode3d_options(const Encode3dArgs& args) {
  Encode3dOptions options;
  options.codec = args.codec;
  options.codec_options = args.codec_options;
  options.hashes = !args.no_hash;
  options.hash_group = args.hash_group;
  options.threads = args.threads;
  return options;
}

int run_encode3d(const Encode3dArgs& args) {
  refuse_trace_to_output(args.trace, args.output);
  refuse_overwriting(args.input, args.output);
  if (fs::is_regular_file(args.input) && starts_as_stream(args.input))
    throw usage_error(args.input + ": a mesh3d stream; encode3d takes frames (m4mesh decode3d turns a stream into frames)");
  const auto reading = std::chrono::steady_clock::now();
  const auto [input, fps] = read_input(args);
  const FrameSource& sequence = *input;
  sequence.scan();
  console::detail("%s: %u frames of %u vertices and %zu faces read in %.3f s", args.input.c_str(), sequence.frame_count(),
                  sequence.vertex_count(), sequence.faces().size(),
                  std::chrono::duration<double>(std::chrono::steady_clock::now() - reading).count());
  Trace trace(std::cout);
  Encode3dOptions options = encode3d_options(args);
  options.reorder = args.reorder;
  if (args.position_blend != "auto") {
    const std::string& text = args.position_blend;
    if (text.empty() || text.size() > 2 || !std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; }) ||
        std::stoul(text) > kPositionBlendUnit)
      throw usage_error("--position-blend is auto or 0 … 16, not " + text);
    options.position_blend = static_cast<uint32_t>(std::stoul(text));
  }
  std::tie(options.frame_rate_num, options.frame_rate_den) = frame_rate_fraction(fps);
  options.trace = args.trace ? &trace : nullptr;
  // The stream goes to its file as it is written; the file appears when it is complete.
  AtomicFile output(args.output);
  options.output = [&](std::span<const uint8_t> bytes) { output.write({reinterpret_cast<const char*>(bytes.data()), bytes.size()}); };
  options.restart_output = [&] { output.restart(); };
  // Codecs count their own steps: frames.
  console::Progress progress("encoding", sequence.frame_count());
  options.progress = [&](size_t done, size_t total) { progress.update(done, total); };
  const QualityTarget target{args.target_kg, args.target_psnr, args.max_error};
  const bool targeted = target.set();
  if (targeted) check_target(target);
  if (args.codec == "auto" && !targeted) throw usage_error("--codec auto needs --target-kg, --target-psnr or --max-error");
  if (targeted && args.trace) throw usage_error("--trace and a quality target: trace the stream the search keeps");
  const double vertex_frames_all = static_cast<double>(sequence.vertex_count()) * static_cast<double>(sequence.frame_count());
  const double bits = 8.0 / vertex_frames_all;
  std::vector<TargetTrial> trials;
  auto print_trial = [&](const TargetTrial& t) {
    progress.finish();
    trials.push_back(t);
    if (t.bytes == 0 && !t.meets) {  // left out: the reason in the last column
      say("  %-14s %-22s %10s       %8s       %9s       %8s      %10s  left out: %s", t.codec.c_str(), "-", "-", "-", "-", "-", "-", t.note.c_str());
      return;
    }
    say("  %-14s %-22s %10llu bytes %8.4f bpvf  KG %9.5f  PSNR %8.3f  max %10.4g  %s%s%s", t.codec.c_str(), t.parameter.c_str(),
        static_cast<unsigned long long>(t.bytes), t.bpvf(), t.kg, t.psnr, t.max_error, t.meets ? "meets" : "misses", t.note.empty() ? "" : "  ",
        t.note.c_str());
  };
  const auto start = std::chrono::steady_clock::now();
  Encode3dResult result;
  if (args.codec == "auto") {
    const bool sampled = static_cast<double>(sequence.vertex_count()) * sequence.frame_count() > static_cast<double>(kWholeSearchVertexFrames);
    say(sampled ? "every codec at the target, on a sample of the frames, then the whole sequence with the smallest:" : "every codec at the target:");
    result = encode_smallest(sequence, options, target, print_trial, options.codec);
    // Why: the codecs' best trials come first, one each, in registry order.
    const TargetTrial* kept = nullptr;
    const TargetTrial* next = nullptr;
    for (size_t i = 0; i < std::min(trials.size(), codecs3d().size()); ++i)
      if (trials[i].meets && trials[i].codec == options.codec)
        kept = &trials[i];
      else if (trials[i].meets && (!next || trials[i].bytes < next->bytes))
        next = &trials[i];
    std::string why;
    if (kept) why = ": the smallest stream " + std::string(sampled ? "of the sample " : "") + "that meets the target (" + std::to_string(kept->bytes) + " bytes";
    if (kept && next) why += "; next " + next->codec + ", " + std::to_string(next->bytes);
    if (kept) why += ")";
    say("kept: %s%s", options.codec.c_str(), why.c_str());
  } else if (targeted) {
    say("%s, searching its quality for the target:", args.codec.c_str());
    result = encode_to_target(sequence, options, target, print_trial);
  } else {
    result = encode_mesh3d(sequence, options);
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  progress.finish();
  output.commit();
  const double vertex_frames = static_cast<double>(sequence.vertex_count()) * static_cast<double>(sequence.frame_count() - 1);
  char figure[160];
  // The whole stream's rate is rd's bpvf and metrics' stream rate.
  std::snprintf(figure, sizeof figure, " (%.4f bits/vertex/frame)", static_cast<double>(result.stream_bytes) * bits);
  std::string line = args.output + ": " + std::to_string(result.stream_bytes) + " bytes" + figure;
  for (uint32_t t = 0; t < kUnitTypes; ++t) {
    const uint64_t bytes = result.unit_bytes[t];
    if (bytes == 0) continue;
    std::snprintf(figure, sizeof figure, ", %s %llu bytes", unit_type_name(static_cast<UnitType>(t)), static_cast<unsigned long long>(bytes));
    line += figure;
    if (static_cast<UnitType>(t) == UnitType::kBaseMesh && result.unit_count[t] > 1)
      std::snprintf(figure, sizeof figure, " in %llu units (%.2f bits/vertex each)", static_cast<unsigned long long>(result.unit_count[t]),
                    8.0 * static_cast<double>(bytes) / static_cast<double>(result.unit_count[t]) / sequence.vertex_count());
    else if (static_cast<UnitType>(t) == UnitType::kBaseMesh)
      std::snprintf(figure, sizeof figure, " (%.2f bits/vertex)", 8.0 * static_cast<double>(bytes) / sequence.vertex_count());
    else if (static_cast<UnitType>(t) == UnitType::kFrame && vertex_frames > 0)
      std::snprintf(figure, sizeof figure, " (%.3f bits/vertex/frame)", 8.0 * static_cast<double>(bytes) / vertex_frames);
    else
      figure[0] = '\0';
    line += figure;
  }
  line += ", other " + std::to_string(result.other_bytes);
  say("%s", line.c_str());
  if (!result.statistics.empty()) {
    std::string figures = options.codec + ":";
    for (size_t i = 0; i < result.statistics.size(); ++i) {
      std::snprintf(figure, sizeof figure, "%s%.10g %s", i ? ", " : " ", result.statistics[i].second, result.statistics[i].first.c_str());
      figures += figure;
    }
    say("%s", figures.c_str());
  }
  // In millions, thousands or units: a slow codec's rate is far below a million.
  const double rate = vertex_frames_all / seconds;
  const auto [scaled, unit] = rate >= 1e6 ? std::pair{rate / 1e6, "M "} : rate >= 1e3 ? std::pair{rate / 1e3, "k "} : std::pair{rate, ""};
  say("encoded %s of %s in %.3f s (%.1f %svertices/s)", console::counted(sequence.frame_count(), "frame", "frames").c_str(),
      console::counted(sequence.vertex_count(), "vertex", "vertices").c_str(), seconds, scaled, unit);
  return 0;
}

}  // namespace m4mesh
