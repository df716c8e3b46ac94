#include "cli/commands3d.h"

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>

#include "common/atomic_file.h"
#include "common/error.h"
#include "decoder/mesh3d_decoder.h"
#include "encoder/mesh3d_encoder.h"
#include "mesh3d/metrics.h"

namespace m4mesh {

namespace {

namespace fs = std::filesystem;

// Progress on long runs, for a person at a terminal.
void progress(const char* what, size_t done, size_t total) {
  if (total < 20 || !isatty(fileno(stderr))) return;
  std::fprintf(stderr, "\r%s frame %zu/%zu", what, done, total);
  if (done == total) std::fprintf(stderr, "\n");
}

uint32_t codec_of(const std::string& name) {
  if (name == "bfs3d") return kCodecBfs3d;
  if (name == "affine-octree") return kCodecAffineOctree;
  throw Error(ErrorKind::kUsage, "", kNoPlane, kNoOffset, "codec '" + name + "' is not implemented (available: bfs3d, affine-octree)");
}

}  // namespace

int run_encode3d(const Encode3dArgs& args) {
  const MeshSequence sequence = load_sequence(args.input, true);
  Encode3dOptions options;
  options.codec_id = codec_of(args.codec);
  options.bits = args.bits;
  options.parallelogram = args.parallelogram;
  options.max_error = args.max_error / 100;
  options.matrix_bits = args.matrix_bits;
  options.max_depth = args.max_depth;
  options.intra_period = args.intra_period;
  options.hashes = !args.no_hash;
  options.frame_rate_num = static_cast<uint32_t>(args.fps);
  options.progress = [](size_t done, size_t total) { progress("encoding", done, total); };
  const auto start = std::chrono::steady_clock::now();
  const Encode3dResult result = encode_mesh3d(sequence, options);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  write_file_atomically(args.output, std::string_view(reinterpret_cast<const char*>(result.stream.data()), result.stream.size()));
  const double vertex_frames = static_cast<double>(sequence.vertex_count) * static_cast<double>(sequence.frames.size() - 1);
  std::printf("%s: %zu bytes: base mesh %llu bytes (%.2f bits/vertex), frames %llu bytes (%.3f bits/vertex/frame), other %llu bytes\n",
              args.output.c_str(), result.stream.size(), static_cast<unsigned long long>(result.base_bytes),
              8.0 * static_cast<double>(result.base_bytes) / sequence.vertex_count,
              static_cast<unsigned long long>(result.frame_bytes),
              vertex_frames > 0 ? 8.0 * static_cast<double>(result.frame_bytes) / vertex_frames : 0.0,
              static_cast<unsigned long long>(result.other_bytes));
  if (options.codec_id == kCodecAffineOctree)
    std::printf("affine-octree: %llu matrices, %llu vertices coded directly\n", static_cast<unsigned long long>(result.matrices),
                static_cast<unsigned long long>(result.direct_vertices));
  std::printf("encoded %zu frames of %u vertices in %.3f s (%.1f M vertices/s)\n", sequence.frames.size(), sequence.vertex_count,
              seconds, static_cast<double>(sequence.vertex_count) * static_cast<double>(sequence.frames.size()) / seconds / 1e6);
  return 0;
}

int run_decode3d(const Decode3dArgs& args) {
  const std::vector<uint8_t> stream = read_file(args.input);
  Mesh3dDecoder decoder(stream, args.verify);
  const std::string extension = fs::path(args.output).extension().string();
  const bool to_folder = extension != ".m4seq" && extension != ".f32";
  // Frames go to a temporary folder that becomes the output only when all decoded.
  const fs::path temporary = args.output + ".partial";
  if (to_folder && fs::exists(args.output) && !fs::is_empty(args.output))
    throw Error(ErrorKind::kIo, "", kNoPlane, kNoOffset, args.output + ": the output folder exists and is not empty");
  fs::remove_all(temporary);
  MeshSequence sequence;
  sequence.vertex_count = decoder.header().vertex_count;
  int mismatches = 0, unchecked = 0;
  try {
    while (decoder.next_frame()) {
      std::vector<Vec3> frame;
      frame.reserve(decoder.positions().size());
      for (const Float3& p : decoder.positions()) frame.push_back({p[0], p[1], p[2]});
      if (to_folder) {
        fs::create_directories(temporary);
        write_obj_frame(frame, decoder.faces(), (temporary / obj_frame_name(decoder.frame_index())).string());
      } else {
        sequence.frames.push_back(std::move(frame));
      }
      const std::optional<bool> ok = decoder.hash_matches();
      if (args.verify) std::printf("frame %u: %s\n", decoder.frame_index(), !ok ? "NO HASH" : *ok ? "OK" : "MISMATCH");
      mismatches += ok.has_value() && !*ok;
      unchecked += !ok.has_value();
      progress("decoding", decoder.frame_index() + 1, decoder.header().frame_count);
    }
  } catch (...) {
    fs::remove_all(temporary);
    throw;
  }
  if (to_folder) {
    fs::remove(args.output);
    fs::rename(temporary, args.output);
  } else if (extension == ".f32") {
    std::string bytes;
    for (const std::vector<Vec3>& frame : sequence.frames) {
      std::vector<Float3> positions;
      for (const Vec3& v : frame) positions.push_back({static_cast<float>(v.x), static_cast<float>(v.y), static_cast<float>(v.z)});
      const std::vector<uint8_t> b = frame_bytes(positions);
      bytes.append(b.begin(), b.end());
    }
    write_file_atomically(args.output, bytes);
  } else {
    sequence.faces = decoder.faces();
    write_binary_sequence(sequence, args.output);
  }
  std::printf("%s: %u frames of %u vertices%s\n", args.output.c_str(), decoder.frame_index() + 1, decoder.header().vertex_count,
              decoder.has_end_code() ? "" : " (warning: no end code)");
  if (args.verify) {
    std::printf("verify: %d mismatches, %d frames without a hash\n", mismatches, unchecked);
    return mismatches == 0 && unchecked == 0 ? 0 : 1;
  }
  return mismatches == 0 ? 0 : 1;
}

int run_info3d(const std::string& input) {
  const std::vector<uint8_t> stream = read_file(input);
  const ContainerParts parts = split_container(stream);
  Mesh3dDecoder decoder(stream);
  const ObjectHeader& h = decoder.header();
  const char* codec_names[] = {"", "bfs3d", "affine-octree", "lcc", "cpca-wpt"};
  std::printf("%s: %zu bytes, mesh3d container, codec_id %u (%s), %u vertices, %u faces, %u frames at %u/%u fps\n",
              input.c_str(), stream.size(), h.codec_id, codec_names[h.codec_id], h.vertex_count, h.face_count, h.frame_count, h.frame_rate_num,
              h.frame_rate_den);
  uint64_t sizes[4] = {0, 0, 0, 0};
  uint64_t counts[4] = {0, 0, 0, 0};
  for (size_t k = 0; k < parts.units.size(); ++k) {
    const uint64_t end = k + 1 < parts.units.size() ? parts.units[k + 1].byte_offset : stream.size() - (parts.has_end_code ? 4 : 0);
    const uint32_t type = parts.units[k].payload.empty() ? 0 : parts.units[k].payload[0];
    if (type < 4) {
      sizes[type] += end - parts.units[k].byte_offset;
      ++counts[type];
    }
  }
  const char* names[4] = {"base mesh", "frame", "refinement", "frame hash"};
  for (int t = 0; t < 4; ++t)
    if (counts[t]) std::printf("  %-10s units: %llu, %llu bytes\n", names[t], static_cast<unsigned long long>(counts[t]),
                               static_cast<unsigned long long>(sizes[t]));
  if (h.frame_count > 1)
    std::printf("  frames: %.3f bits/vertex/frame\n",
                8.0 * static_cast<double>(sizes[1]) / (static_cast<double>(h.vertex_count) * (h.frame_count - 1)));
  std::printf("  end code %s\n", parts.has_end_code ? "present" : "MISSING");
  return 0;
}

int run_metrics(const MetricsArgs& args) {
  const MeshSequence original = load_sequence(args.original, true);
  MeshSequence decoded;
  if (fs::is_regular_file(args.decoded) && is_mesh3d_stream(read_file(args.decoded)))
    decoded = decode_mesh3d(read_file(args.decoded));
  else
    decoded = load_sequence(args.decoded, true);
  const SequenceMetrics m = compare_sequences(original, decoded);
  std::printf("KG error      %.6f %%\n", m.kg_error);
  std::printf("RMSE          %.9g\n", m.rmse);
  std::printf("max error     %.9g\n", m.max_error);
  std::printf("PSNR          %.3f dB\n", m.psnr);
  std::printf("STED spatial  %.9g\n", m.sted_spatial);
  std::printf("STED temporal %.9g\n", m.sted_temporal);
  std::printf("STED          %.9g\n", m.sted);
  if (!args.stream.empty()) {
    const std::vector<uint8_t> stream = read_file(args.stream);
    std::printf("rate          %.4f bits/vertex/frame (whole stream over all frames)\n",
                8.0 * static_cast<double>(stream.size()) / (static_cast<double>(original.vertex_count) * static_cast<double>(original.frames.size())));
  }
  return 0;
}

int run_convert(const std::string& input, const std::string& output) {
  const MeshSequence sequence = load_sequence(input, true);
  if (fs::path(output).extension() == ".m4seq")
    write_binary_sequence(sequence, output);
  else
    write_obj_frames(sequence, output);
  std::printf("%s: %zu frames of %u vertices\n", output.c_str(), sequence.frames.size(), sequence.vertex_count);
  return 0;
}

}  // namespace m4mesh
