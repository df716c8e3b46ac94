#include "cli/commands3d.h"

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <algorithm>
#include <charconv>
#include <cmath>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <limits>
#include <set>

#include "cli/console.h"
#include "codecs3d/registry.h"
#include "encoder/mesh3d/codec_encoders.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "common/md5.h"
#include "decoder/mesh3d/container_decoder.h"
#include "encoder/mesh3d/base_mesh.h"
#include "encoder/mesh3d/container_encoder.h"
#include "encoder/mesh3d/quality_target.h"
#include "mesh3d/metrics.h"
#include "mesh3d/ply.h"
#include "mesh3d/quantization.h"
#include "syntax/mesh3d/base_mesh.h"

namespace m4mesh {

namespace {

namespace fs = std::filesystem;
using console::say;

}  // namespace

namespace {

// A sequence output's form from its name: a folder of OBJ frames (no
// extension, or a trailing '/'), .m4seq, .pc2 (with its .obj), PLY frames
// (a .ply name, with a '*' for the frame number when there are several) or
// .f32; anything else is a usage error, not a folder. Standard output ("-")
// takes `format`: m4seq (the default) or f32.
enum class SequenceOutput { kObjFolder, kM4seq, kPc2, kPly, kF32 };
SequenceOutput sequence_output(const std::string& output, bool f32_allowed, const std::string& format = "") {
  if (output == "-") {
    if (format.empty() || format == "m4seq") return SequenceOutput::kM4seq;
    if (format == "f32" && f32_allowed) return SequenceOutput::kF32;
    throw usage_error("--format " + format + ": standard output takes m4seq" + std::string(f32_allowed ? " or f32" : ""));
  }
  if (!format.empty())
    throw usage_error("--format is for -o - (standard output); a file's form comes from its name");
  const fs::path path(output);
  const std::string extension = path.filename().empty() ? "" : path.extension().string();
  if (extension.empty()) return SequenceOutput::kObjFolder;
  if (extension == ".m4seq") return SequenceOutput::kM4seq;
  if (extension == ".pc2") return SequenceOutput::kPc2;
  if (extension == ".ply") return SequenceOutput::kPly;
  if (extension == ".f32" && f32_allowed) return SequenceOutput::kF32;
  throw usage_error(output + ": unknown output format '" + extension + "' (a folder of OBJ frames, .m4seq, .pc2, .ply" + (f32_allowed ? ", .f32" : "") +
                  "; a folder whose name holds a dot takes a trailing '/')");
}

// PLY frames: the '*' of the name replaced by 0001, 0002, …; a name
// without '*' takes one frame. Existing files are refused before any is written.
void write_ply_frames(const MeshSequence& sequence, const std::string& output) {
  const size_t star = fs::path(output).filename().string().find('*');
  if (star == std::string::npos && sequence.frames.size() != 1)
    throw usage_error(output + ": " + std::to_string(sequence.frames.size()) + " frames need a name with '*' for the frame number (frames/*.ply)");
  std::vector<std::string> paths;
  for (size_t k = 0; k < sequence.frames.size(); ++k) {
    std::string path = output;
    if (star != std::string::npos) {
      char number[24];
      std::snprintf(number, sizeof number, "%04zu", k + 1);
      path.replace(output.size() - fs::path(output).filename().string().size() + star, 1, number);
    }
    console::check_output(path);
    paths.push_back(path);
  }
  if (const fs::path folder = fs::path(output).parent_path(); !folder.empty()) fs::create_directories(folder);
  for (size_t k = 0; k < paths.size(); ++k) write_ply_frame(sequence.frames[k], sequence.faces, paths[k]);
}

// A whole sequence to a .m4seq, .pc2 or PLY output.
void write_sequence_file(SequenceOutput form, const MeshSequence& sequence, const std::string& output) {
  if (form == SequenceOutput::kPc2)
    write_pc2_sequence(sequence, output);
  else if (form == SequenceOutput::kPly)
    write_ply_frames(sequence, output);
  else
    write_binary_sequence(sequence, output);
}

// Whether a file name is one obj_frame_name gives (0001.obj, …).
bool is_obj_frame_name(const std::string& name) {
  const std::string stem = name.size() > 4 ? name.substr(0, name.size() - 4) : "";
  return name.ends_with(".obj") && stem.size() >= 4 && std::all_of(stem.begin(), stem.end(), [](char c) { return c >= '0' && c <= '9'; });
}

// The OBJ frames written into `staging` become the frames of `folder`:
// its earlier frame files (0001.obj, …) go, its other files stay.
void install_obj_frames(const fs::path& staging, const fs::path& output) {
  fs::path folder = output.lexically_normal();
  if (folder.filename().empty()) folder = folder.parent_path();
  if (!fs::is_directory(folder)) {
    fs::remove(folder);  // a file the user named as the output (-y)
    fs::rename(staging, folder);
    return;
  }
  for (const fs::directory_entry& entry : fs::directory_iterator(folder))
    if (entry.is_regular_file() && is_obj_frame_name(entry.path().filename().string())) fs::remove(entry.path());
  for (const fs::directory_entry& entry : fs::directory_iterator(staging)) fs::rename(entry.path(), folder / entry.path().filename());
  fs::remove(staging);
}

// A staging folder beside `output` (a trailing '/' is not part of the
// name), of this process's own: nothing the user did not name is touched.
fs::path staging_folder(const std::string& output) {
  fs::path folder = fs::path(output).lexically_normal();
  if (folder.filename().empty()) folder = folder.parent_path();
  return folder.string() + ".partial-" + std::to_string(getpid());
}

}  // namespace

MeshSequence load_sequence_or_stream(const std::string& path, StreamFacts* facts) {
  console::set_input(path);
  if (facts) *facts = StreamFacts{};
  if (path == "-" || fs::is_regular_file(path)) {
    const std::vector<uint8_t> bytes = read_file(path);
    if (is_mesh3d_stream(bytes)) {
      if (facts) {
        const Mesh3dDecoder header(bytes);
        *facts = {header.codec().name, bytes.size(), header.vertex_order() == kVertexOrderCoding};
      }
      return decode_mesh3d(bytes);
    }
  }
  return load_sequence(path, !console::quiet());
}

MeshSequence original_as_decoded(const MeshSequence& original, const MeshSequence& decoded, bool coding_order, const std::string& decoded_name) {
  if (!coding_order || original.vertex_count != decoded.vertex_count) return original;
  // The faces alone fix the coding order: the encoder's plan gives the numbering back.
  const MeshSequence renumbered = in_coding_order(original, plan_base_mesh(original.faces, original.vertex_count, true), true);
  if (!same_faces(renumbered.faces, decoded.faces))
    throw Error(ErrorKind::kInput, "", kNoPlane, kNoOffset,
                decoded_name + " numbers its vertices in coding order, but its faces are not the original's in that order: not a stream of this original");
  return renumbered;
}

void refuse_overwriting(const std::string& input, const std::string& output) {
  if (input != "-" && output != "-") {
    // A PC2 cache comes with the OBJ beside it (its faces), as an input and as an output.
    auto with_faces = [](const std::string& path) {
      std::vector<fs::path> paths{path};
      if (fs::path(path).extension() == ".pc2") paths.push_back(pc2_faces_path(path));
      return paths;
    };
    std::error_code ignored;
    for (const fs::path& in : with_faces(input))
      for (const fs::path& out : with_faces(output))
        if (fs::equivalent(in, out, ignored))
          throw usage_error(out.string() + ": the output is the input; refusing to overwrite it");
  }
  console::check_output(output);
}

void refuse_trace_to_output(bool trace, const std::string& output) {
  if (trace && output == "-")
    throw usage_error("--trace prints to standard output, which -o - takes: write the stream to a file");
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
  command.add_option("--threads", args.threads, "trials at once in --codec auto and in cpca-wpt's own search (default 0: every core; the stream kept does not depend on it)");
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

int run_encode3d(const Encode3dArgs& args) {
  refuse_trace_to_output(args.trace, args.output);
  refuse_overwriting(args.input, args.output);
  if (fs::is_regular_file(args.input) && is_mesh3d_stream(read_file(args.input)))
    throw usage_error(args.input + ": a mesh3d stream; encode3d takes frames (m4mesh decode3d turns a stream into frames)");
  const auto reading = std::chrono::steady_clock::now();
  const MeshSequence sequence = load_sequence(args.input, !console::quiet());
  console::detail("%s: %zu frames of %u vertices and %zu faces read in %.3f s", args.input.c_str(), sequence.frames.size(),
                  sequence.vertex_count, sequence.faces.size(),
                  std::chrono::duration<double>(std::chrono::steady_clock::now() - reading).count());
  Trace trace(std::cout);
  Encode3dOptions options;
  options.codec = args.codec;
  options.codec_options = args.codec_options;
  options.hashes = !args.no_hash;
  options.hash_group = args.hash_group;
  options.reorder = args.reorder;
  options.frame_rate_num = static_cast<uint32_t>(args.fps);
  options.trace = args.trace ? &trace : nullptr;
  options.threads = args.threads;
  // Codecs count their own steps: frames, or cpca-wpt's units.
  console::Progress progress("encoding", sequence.frames.size());
  options.progress = [&](size_t done, size_t total) { progress.update(done, total); };
  const QualityTarget target{args.target_kg, args.target_psnr};
  const bool targeted = target.set();
  if (targeted) check_target(target);
  if (args.codec == "auto" && !targeted) throw usage_error("--codec auto needs --target-kg or --target-psnr");
  if (targeted && args.trace) throw usage_error("--trace and a quality target: trace the stream the search keeps");
  const double bits = 8.0 / (static_cast<double>(sequence.vertex_count) * static_cast<double>(sequence.frames.size()));
  auto print_trial = [&](const TargetTrial& t) {
    progress.finish();
    say("  %-14s %-22s %10llu bytes %8.4f bpvf  KG %9.5f  PSNR %8.3f  %s", t.codec.c_str(), t.parameter.c_str(),
                 static_cast<unsigned long long>(t.bytes), static_cast<double>(t.bytes) * bits, t.kg, t.psnr,
                 t.meets ? "meets" : "misses");
  };
  const auto start = std::chrono::steady_clock::now();
  Encode3dResult result;
  if (args.codec == "auto") {
    say("every codec at the target:");
    result = encode_smallest(sequence, options, target, print_trial, options.codec);
    say("kept: %s", options.codec.c_str());
  } else if (targeted) {
    say("%s, searching its quality for the target:", args.codec.c_str());
    result = encode_to_target(sequence, options, target, print_trial);
  } else {
    result = encode_mesh3d(sequence, options);
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  progress.finish();
  write_file_atomically(args.output, std::string_view(reinterpret_cast<const char*>(result.stream.data()), result.stream.size()));
  const double vertex_frames = static_cast<double>(sequence.vertex_count) * static_cast<double>(sequence.frames.size() - 1);
  char figure[160];
  // The whole stream's rate is rd's bpvf and metrics' stream rate.
  std::snprintf(figure, sizeof figure, " (%.4f bits/vertex/frame)",
                8.0 * static_cast<double>(result.stream.size()) / (static_cast<double>(sequence.vertex_count) * static_cast<double>(sequence.frames.size())));
  std::string line = args.output + ": " + std::to_string(result.stream.size()) + " bytes" + figure;
  for (uint32_t t = 0; t < kUnitTypes; ++t) {
    const uint64_t bytes = result.unit_bytes[t];
    if (bytes == 0) continue;
    std::snprintf(figure, sizeof figure, ", %s %llu bytes", unit_type_name(static_cast<UnitType>(t)), static_cast<unsigned long long>(bytes));
    line += figure;
    if (static_cast<UnitType>(t) == UnitType::kBaseMesh && result.unit_count[t] > 1)
      std::snprintf(figure, sizeof figure, " in %llu units (%.2f bits/vertex each)", static_cast<unsigned long long>(result.unit_count[t]),
                    8.0 * static_cast<double>(bytes) / static_cast<double>(result.unit_count[t]) / sequence.vertex_count);
    else if (static_cast<UnitType>(t) == UnitType::kBaseMesh)
      std::snprintf(figure, sizeof figure, " (%.2f bits/vertex)", 8.0 * static_cast<double>(bytes) / sequence.vertex_count);
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
  say("encoded %zu frames of %u vertices in %.3f s (%.1f M vertices/s)", sequence.frames.size(), sequence.vertex_count, seconds, static_cast<double>(sequence.vertex_count) * static_cast<double>(sequence.frames.size()) / seconds / 1e6);
  return 0;
}

std::pair<uint32_t, uint32_t> frame_range(const std::string& text) {
  if (text.empty()) return {0, UINT32_MAX};
  const size_t colon = text.find(':');
  auto number = [&](const std::string& part, uint32_t otherwise) {
    if (part.empty()) return otherwise;
    uint32_t value = 0;
    const auto [end, error] = std::from_chars(part.data(), part.data() + part.size(), value);
    if (error != std::errc() || end != part.data() + part.size())
      throw usage_error("--frames " + text + ": frames A:B, A: or :B");
    return value;
  };
  if (colon == std::string::npos) throw usage_error("--frames " + text + ": frames A:B, A: or :B");
  const std::pair<uint32_t, uint32_t> range{number(text.substr(0, colon), 0), number(text.substr(colon + 1), UINT32_MAX)};
  if (range.first > range.second) throw usage_error("--frames " + text + ": A is after B");
  return range;
}

int run_decode3d(const Decode3dArgs& args) {
  const bool writes = !args.output.empty();
  if (!writes && !args.md5) throw usage_error("decode3d needs -o OUTPUT, or --md5");
  if (writes) refuse_overwriting(args.input, args.output);
  const auto [first, last] = frame_range(args.frames);
  std::vector<uint8_t> stream = read_file(args.input);
  if (args.max_bytes > 0) {
    const ContainerPrefix prefix = container_prefix(split_container(stream), stream.size(), args.max_bytes);
    if (prefix.units == 0)
      throw usage_error("--max-bytes " + std::to_string(args.max_bytes) + " holds no unit: the first ends later");
    say("prefix: %zu units, %llu of %zu bytes", prefix.units, static_cast<unsigned long long>(prefix.bytes), stream.size());
    stream.resize(prefix.bytes);
  }
  Decode3dOptions options;
  options.verify = args.verify;
  const SequenceOutput form = writes ? sequence_output(args.output, true, args.format) : SequenceOutput::kF32;
  Mesh3dDecoder decoder(stream, options);
  console::detail("%s: codec %s, %u vertices, %u faces, %u frames", args.input.c_str(), decoder.codec().name.c_str(),
                  decoder.header().vertex_count, decoder.header().face_count, decoder.header().frame_count);
  if (decoder.vertex_order() == kVertexOrderCoding)
    say("note: %s numbers its vertices in coding order (encode3d --reorder), not necessarily the input's", args.input.c_str());
  if (const uint32_t start = first > 0 ? decoder.seek(first) : 0; start > 0)
    console::detail("%s: decoding from the intra refresh at frame %u", args.input.c_str(), start);
  const bool to_folder = writes && form == SequenceOutput::kObjFolder;
  Md5 md5;  // of every frame's binary32 bytes: the 3D conformance hash
  // Frames go to a staging folder that gives the output its frames only when all are decoded.
  const fs::path temporary = staging_folder(args.output);
  console::Progress progress("decoding frame", decoder.header().frame_count);
  MeshSequence sequence;
  sequence.vertex_count = decoder.header().vertex_count;
  std::vector<uint32_t> written;
  bool failed = false;
  try {
    // Every frame is decoded (a group hash may cover frames after the range); those in the range are written.
    while (decoder.next_frame()) {
      progress.update(decoder.frame_index() + 1);
      if (decoder.frame_index() < first || decoder.frame_index() > last) continue;
      if (args.md5) {
        const std::vector<uint8_t> bytes = frame_bytes(decoder.positions());
        md5.update(bytes.data(), bytes.size());
      }
      written.push_back(decoder.frame_index());
      if (!writes) continue;
      std::vector<Vec3> frame;
      frame.reserve(decoder.positions().size());
      for (const Float3& p : decoder.positions()) frame.push_back({p[0], p[1], p[2]});
      if (to_folder) {
        fs::create_directories(temporary);
        write_obj_frame(frame, decoder.faces(), (temporary / obj_frame_name(decoder.frame_index())).string());
      } else {
        sequence.frames.push_back(std::move(frame));
      }
      // Past the range nothing is written; without --verify nothing more is needed.
      if (decoder.frame_index() == last && !args.verify) break;
    }
  } catch (const Error& e) {
    if (!args.keep_going) {
      fs::remove_all(temporary);
      throw;
    }
    std::fprintf(stderr, "error: %s: %s\n", args.input.c_str(), e.what());
    failed = true;
  } catch (...) {
    fs::remove_all(temporary);
    throw;
  }
  progress.finish();
  if (written.empty() && failed) {
    std::fprintf(stderr, "%s: no frame decoded before the error; nothing written\n", args.input.c_str());
    return 1;
  }
  if (written.empty()) throw usage_error("--frames " + args.frames + ": the stream has no frame there");
  if (to_folder) {
    install_obj_frames(temporary, fs::path(args.output));
  } else if (writes && form == SequenceOutput::kF32) {
    std::string bytes;
    for (const std::vector<Vec3>& frame : sequence.frames) {
      std::vector<Float3> positions;
      for (const Vec3& v : frame) positions.push_back({static_cast<float>(v.x), static_cast<float>(v.y), static_cast<float>(v.z)});
      const std::vector<uint8_t> b = frame_bytes(positions);
      bytes.append(b.begin(), b.end());
    }
    write_file_atomically(args.output, bytes);
  } else if (writes) {
    sequence.faces = decoder.faces();
    write_sequence_file(form, sequence, args.output);
  }
  if (failed) {
    std::fprintf(stderr, "%s: decoded %zu frames before the error; %s holds them\n", args.input.c_str(), written.size(), args.output.c_str());
    return 1;
  }
  say("%s: %zu frames of %u vertices%s", writes ? args.output.c_str() : args.input.c_str(), written.size(), decoder.header().vertex_count,
              decoder.has_end_code() || args.max_bytes > 0 ? "" : " (warning: no end code)");
  // Hash units may check a group of frames after its last: the results come
  // at the end, on standard error when the frames fill standard output.
  std::FILE* report = args.output == "-" ? stderr : stdout;
  if (args.md5) std::fprintf(report, "%s\n", md5.hex_digest().c_str());
  std::vector<uint32_t> mismatched, unchecked;
  for (uint32_t f : written) {
    const std::optional<bool> ok = decoder.hash_result(f);
    if (args.verify) std::fprintf(report, "frame %u: %s\n", f, !ok ? "NO HASH" : *ok ? "OK" : "MISMATCH");
    if (ok.has_value() && !*ok) mismatched.push_back(f);
    if (!ok.has_value()) unchecked.push_back(f);
  }
  if (args.verify) std::fprintf(report, "verify: %zu mismatches, %zu frames without a hash\n", mismatched.size(), unchecked.size());
  if (!mismatched.empty())
    std::fprintf(stderr, "error: %s: %zu decoded frames differ from their hash unit (the first: frame %u)\n", args.input.c_str(),
                 mismatched.size(), mismatched.front());
  // --verify promises that every frame was checked: a frame without a hash fails it.
  if (args.verify && !unchecked.empty())
    std::fprintf(stderr,
                 "error: %s: --verify: %zu frames carry no hash to check (the first: frame %u): the stream was encoded with --no-hash, "
                 "or --frames starts inside a group whose hash covers frames not decoded\n",
                 args.input.c_str(), unchecked.size(), unchecked.front());
  return mismatched.empty() && (!args.verify || unchecked.empty()) ? 0 : 1;
}

namespace {

// Per unit_type, the units of a stream and their bytes (start codes included).
struct UnitSizes {
  uint64_t bytes[kUnitTypes] = {};
  uint64_t count[kUnitTypes] = {};
};
UnitSizes unit_sizes(const ContainerParts& parts, uint64_t stream_size) {
  UnitSizes sizes;
  for (size_t k = 0; k < parts.units.size(); ++k) {
    const uint64_t end = k + 1 < parts.units.size() ? parts.units[k + 1].byte_offset : stream_size - (parts.has_end_code ? 4 : 0);
    const uint32_t type = parts.units[k].payload.empty() ? kUnitTypes : parts.units[k].payload[0];
    if (type < kUnitTypes) {
      sizes.bytes[type] += end - parts.units[k].byte_offset;
      ++sizes.count[type];
    }
  }
  return sizes;
}

}  // namespace

const char* vertex_order_name(uint32_t order) {
  switch (order) {
    case kVertexOrderCoding: return "coding order (the input's only if it was in coding order: encode3d --reorder)";
    case kVertexOrderFromGate: return "the input's (sent, predicted by the gate's vertex)";
    default: return "the input's (sent, predicted by parallelograms of input numbers)";
  }
}

int run_info3d(const std::string& input) {
  const std::vector<uint8_t> stream = read_file(input);
  const ContainerParts parts = split_container(stream);
  Mesh3dDecoder decoder(stream);
  const ObjectHeader& h = decoder.header();
  std::printf("%s: %zu bytes, mesh3d container, codec_id %u (%s), %u vertices, %u faces, %u frames at %u/%u fps\n", input.c_str(),
              stream.size(), h.codec_id, decoder.codec().name.c_str(), h.vertex_count, h.face_count, h.frame_count, h.frame_rate_num,
              h.frame_rate_den);
  if (const std::optional<uint32_t> order = decoder.vertex_order())
    std::printf("  vertex order: %s\n", vertex_order_name(*order));
  const UnitSizes unit = unit_sizes(parts, stream.size());
  const uint64_t* sizes = unit.bytes;
  const uint64_t* counts = unit.count;
  for (uint32_t t = 0; t < kUnitTypes; ++t)
    if (counts[t])
      std::printf("  %-10s units: %llu, %llu bytes\n", unit_type_name(static_cast<UnitType>(t)), static_cast<unsigned long long>(counts[t]),
                  static_cast<unsigned long long>(sizes[t]));
  const uint32_t frame_units = static_cast<uint32_t>(UnitType::kFrame);
  if (h.frame_count > 1 && counts[frame_units])
    std::printf("  frames: %.3f bits/vertex/frame\n",
                8.0 * static_cast<double>(sizes[frame_units]) / (static_cast<double>(h.vertex_count) * (h.frame_count - 1)));
  std::printf("  end code %s\n", parts.has_end_code ? "present" : "MISSING");
  // A stream cut short or broken is not summarised as if it were whole: every unit is decoded.
  while (decoder.next_unit()) {
  }
  return 0;
}

int run_trace3d(const std::string& input) {
  const std::vector<uint8_t> stream = read_file(input);
  Trace trace(std::cout);
  Decode3dOptions options;
  options.trace = &trace;
  Mesh3dDecoder decoder(stream, options);
  while (decoder.next_unit()) {
  }
  return 0;
}

int run_metrics(const MetricsArgs& args) {
  if (args.json && args.csv) throw usage_error("--json or --csv, not both");
  console::set_input(args.original);
  const MeshSequence given_original = load_sequence(args.original, !console::quiet());
  // The stream is checked against the sequence before anything is printed.
  struct Rate {
    const char* key;
    const char* label;
    double value;
  };
  std::vector<Rate> rates;
  if (!args.stream.empty()) {
    console::set_input(args.stream);
    const std::vector<uint8_t> stream = read_file(args.stream);
    const ObjectHeader h = Mesh3dDecoder(stream).header();
    if (h.vertex_count != given_original.vertex_count || h.face_count != given_original.faces.size() || h.frame_count != given_original.frames.size())
      throw Error(ErrorKind::kInput, "", kNoPlane, kNoOffset,
                  args.stream + ": a stream of " + std::to_string(h.vertex_count) + " vertices, " + std::to_string(h.face_count) + " faces, " +
                      std::to_string(h.frame_count) + " frames, not of the sequence compared (" + std::to_string(given_original.vertex_count) +
                      ", " + std::to_string(given_original.faces.size()) + ", " + std::to_string(given_original.frames.size()) + ")");
    const UnitSizes sizes = unit_sizes(split_container(stream), stream.size());
    const double v = static_cast<double>(given_original.vertex_count), f = static_cast<double>(given_original.frames.size());
    const uint64_t frame_bytes = sizes.bytes[static_cast<uint32_t>(UnitType::kFrame)];
    const uint64_t refinement_bytes = sizes.bytes[static_cast<uint32_t>(UnitType::kRefinement)];
    // The same columns for every codec: the whole stream first (rd's bpvf), a part a codec lacks empty (JSON: null).
    constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
    rates.push_back({"stream_rate_bpvf", "(the whole stream over vertices × frames, as rd's bpvf)", 8.0 * static_cast<double>(stream.size()) / (v * f)});
    rates.push_back({"frame_rate_bpvf", "(frame units over vertices × (frames − 1))",
                     frame_bytes > 0 && f > 1 ? 8.0 * static_cast<double>(frame_bytes) / (v * (f - 1)) : kNone});
    rates.push_back({"refinement_rate_bpvf", "(refinement units over vertices × frames)",
                     refinement_bytes > 0 ? 8.0 * static_cast<double>(refinement_bytes) / (v * f) : kNone});
  }
  StreamFacts facts;
  const MeshSequence decoded = load_sequence_or_stream(args.decoded, &facts);
  const MeshSequence original = original_as_decoded(given_original, decoded, facts.coding_order, args.decoded);
  for (const std::string& warning : metrics_warnings(original)) say("warning: %s", warning.c_str());
  const SequenceMetrics m = compare_sequences(original, decoded);
  const std::vector<FrameMetrics> frames = args.per_frame ? per_frame_metrics(original, decoded) : std::vector<FrameMetrics>{};
  const std::pair<const char*, double> figures[] = {{"kg_error_percent", m.kg_error}, {"rmse", m.rmse},
                                                    {"max_error", m.max_error},       {"psnr_db", m.psnr},
                                                    {"sted_spatial", m.sted_spatial}, {"sted_temporal", m.sted_temporal},
                                                    {"sted", m.sted}};
  auto number = [](double x) {
    char text[32];
    std::snprintf(text, sizeof text, "%.9g", x);
    return std::string(text);
  };
  if (args.json) {
    // JSON has no infinity: a lossless frame's PSNR is null.
    auto value = [](double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); };
    nlohmann::json out;
    for (const auto& [key, figure] : figures) out[key] = value(figure);
    for (const Rate& r : rates) out[r.key] = value(r.value);
    if (args.per_frame)
      for (size_t f = 0; f < frames.size(); ++f)
        out["frames"].push_back({{"frame", f}, {"rmse", frames[f].rmse}, {"max_error", frames[f].max_error}, {"psnr_db", value(frames[f].psnr)}});
    std::printf("%s\n", out.dump(2).c_str());
  } else if (args.csv && args.per_frame) {
    std::printf("frame,rmse,max_error,psnr_db\n");
    for (size_t f = 0; f < frames.size(); ++f)
      std::printf("%zu,%.9g,%.9g,%.9g\n", f, frames[f].rmse, frames[f].max_error, frames[f].psnr);
  } else if (args.csv) {
    std::string header, row;
    for (const auto& [key, value] : figures) {
      header += std::string(header.empty() ? "" : ",") + key;
      row += std::string(row.empty() ? "" : ",") + number(value);
    }
    for (const Rate& r : rates) {
      header += std::string(",") + r.key;
      row += "," + (std::isnan(r.value) ? std::string() : number(r.value));
    }
    std::printf("%s\n%s\n", header.c_str(), row.c_str());
  } else {
    std::printf("KG error      %.6f %%\n", m.kg_error);
    std::printf("RMSE          %.9g\n", m.rmse);
    std::printf("max error     %.9g\n", m.max_error);
    std::printf("PSNR          %.3f dB\n", m.psnr);
    std::printf("STED spatial  %.9g\n", m.sted_spatial);
    std::printf("STED temporal %.9g\n", m.sted_temporal);
    std::printf("STED          %.9g\n", m.sted);
    for (const Rate& r : rates)
      if (!std::isnan(r.value)) std::printf("%-13s %.4f bits/vertex/frame %s\n", r.key[0] == 's' ? "stream" : "rate", r.value, r.label);
    if (args.per_frame) {
      std::printf("%6s %16s %16s %10s\n", "frame", "RMSE", "max error", "PSNR dB");
      for (size_t f = 0; f < frames.size(); ++f) std::printf("%6zu %16.9g %16.9g %10.3f\n", f, frames[f].rmse, frames[f].max_error, frames[f].psnr);
    }
  }
  return 0;
}

int run_convert(const std::string& input, const std::string& output) {
  refuse_overwriting(input, output);
  const SequenceOutput form = sequence_output(output, false);
  const MeshSequence sequence = load_sequence(input, !console::quiet());
  if (form == SequenceOutput::kObjFolder) {
    const fs::path staging = staging_folder(output);
    try {
      write_obj_frames(sequence, staging.string());
      install_obj_frames(staging, fs::path(output));
    } catch (...) {
      fs::remove_all(staging);
      throw;
    }
  } else
    write_sequence_file(form, sequence, output);
  say("%s: %zu frames of %u vertices", output.c_str(), sequence.frames.size(), sequence.vertex_count);
  return 0;
}

int run_progressive(const ProgressiveArgs& args) {
  console::set_input(args.original);
  const MeshSequence given_original = load_sequence(args.original, !console::quiet());
  console::set_input(args.stream);
  const std::vector<uint8_t> stream = read_file(args.stream);
  const bool coding_order = Mesh3dDecoder(stream).vertex_order() == kVertexOrderCoding;
  const uint64_t step = args.step > 0 ? args.step : std::max<uint64_t>(1, stream.size() / 40);
  // Set up at the first unit, whose faces the original is matched to
  // (for_each_prefix refuses a stream that is not progressive before).
  std::optional<MeshSequence> original;
  std::optional<MetricsReference> reference;  // of *original
  uint64_t next_report = 0;
  for_each_prefix(stream, [&](size_t units, uint64_t bytes, const MeshSequence& decoded) {
    const bool first = !reference;
    if (first) {
      original = original_as_decoded(given_original, decoded, coding_order, args.stream);
      reference.emplace(*original);
    }
    if (bytes < next_report && bytes < stream.size()) return;
    next_report = bytes + step;
    const SequenceMetrics m = reference->compare(decoded);
    // Units: the base mesh and refinements (hash units count in the bytes).
    if (first) std::printf("%6s %10s %10s %10s %12s\n", "units", "bytes", "KG %", "PSNR dB", "STED");
    std::printf("%6zu %10llu %10.5f %10.3f %12.9f\n", units, static_cast<unsigned long long>(bytes), m.kg_error, m.psnr, m.sted);
  });
  return 0;
}

}  // namespace m4mesh
