// The scale benchmark: every codec's encoder (at a KG target) and decoder
// on sequences from 10^5 to 10^8 vertex-frames, made on the fly (no file
// holds the frames): a herd of galloping horses (../shared/data's horse,
// each copy offset in space and a phase later in the gallop, the herd
// moving forward), or a rippling sheet when the data is absent. Two
// series: the horse alone over more and more frames (memory must stay
// flat), and a herd of 12 (101,172 vertices) over 10, 100 and 1,000
// frames. Each run is a child process of its own, so that its peak
// memory (getrusage) is its own; Draco coding every frame is the anchor
// of the same run. Prints time, rate, peak memory and bits per
// vertex-frame per run, then per codec and series the exponent of time
// against size (a least-squares fit of log time on log size).
//
//   m4mesh_scale_bench [--max 1e8] [--codecs bfs3d,affine-octree,lcc,cpca-wpt,draco]
//                      [--series frames,mesh] [--target-kg 0.5] [--json out.json]
//   m4mesh_scale_bench --segments [--target-kg 0.5]   (what cpca-wpt's segments cost in rate)
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "anchors/draco_reference.h"
#include "bench/sequences.h"
#include "common/parallel.h"
#include "decoder/mesh3d/container_decoder.h"
#include "encoder/mesh3d/quality_target.h"
#include "mesh3d/frame_source.h"

namespace m4mesh::bench {
namespace {

// `tiles` copies of a base sequence side by side, each a few frames later
// in the base's cycle (played forwards, then backwards), all moving along
// x by a tenth of the base's extent a cycle.
class HerdSource final : public FrameSource {
 public:
  HerdSource(const MeshSequence& base, uint32_t tiles, uint32_t frames) : base_(base), tiles_(tiles), frames_(frames) {
    const Box3 box = box_of(base.frames[0]);
    extent_ = {box.hi.x - box.lo.x, box.hi.y - box.lo.y, box.hi.z - box.lo.z};
    for (uint32_t t = 0; t < tiles; ++t)
      for (const Triangle& f : base.faces)
        faces_.push_back({{f.v[0] + t * base.vertex_count, f.v[1] + t * base.vertex_count, f.v[2] + t * base.vertex_count}});
  }
  uint32_t vertex_count() const override { return tiles_ * base_.vertex_count; }
  std::span<const Triangle> faces() const override { return faces_; }
  uint32_t frame_count() const override { return frames_; }
  void read(uint32_t index, std::span<Vec3> out) const override {
    const uint32_t cycle = 2 * static_cast<uint32_t>(base_.frames.size()) - 2;
    const double forward = 0.1 * extent_.x * index / cycle;
    for (uint32_t t = 0; t < tiles_; ++t) {
      const uint32_t phase = (index + 7 * t) % cycle;
      const std::vector<Vec3>& frame = base_.frames[phase < base_.frames.size() ? phase : cycle - phase];
      const double dx = 1.5 * extent_.x * (t % 4) + forward, dz = 1.5 * extent_.z * (t / 4);
      for (uint32_t v = 0; v < base_.vertex_count; ++v) {
        const Vec3& p = frame[v];
        out[t * base_.vertex_count + v] = {p.x + dx, p.y, p.z + dz};
      }
    }
  }

 private:
  const MeshSequence& base_;
  uint32_t tiles_, frames_;
  Vec3 extent_;
  std::vector<Triangle> faces_;
};

struct Run {
  std::string codec;
  std::string series;
  uint32_t vertices = 0, frames = 0;
  double encode_seconds = 0, decode_seconds = 0, kg = 0;
  uint64_t bytes = 0;
  long encode_peak_kb = 0, decode_peak_kb = 0;
  std::string error;

  double vertex_frames() const { return static_cast<double>(vertices) * frames; }
};

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Runs `work` in a child process; its text result (through a pipe) and
// its peak resident memory in KiB.
std::pair<std::string, long> in_child(const std::function<std::string()>& work) {
  int fds[2];
  if (pipe(fds) != 0) throw std::runtime_error("pipe");
  const pid_t child = fork();
  if (child == 0) {
    close(fds[0]);
    std::string out;
    try {
      out = work();
    } catch (const std::exception& e) {
      out = std::string("error ") + e.what();
    }
    const ssize_t written = write(fds[1], out.data(), out.size());
    _exit(written == static_cast<ssize_t>(out.size()) ? 0 : 1);
  }
  close(fds[1]);
  std::string out;
  char buffer[4096];
  for (ssize_t n; (n = read(fds[0], buffer, sizeof buffer)) > 0;) out.append(buffer, static_cast<size_t>(n));
  close(fds[0]);
  int status = 0;
  rusage usage{};
  wait4(child, &status, 0, &usage);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) out = "error the child process failed";
  return {out, usage.ru_maxrss};
}

Run measure(const std::string& codec, const std::string& series, const MeshSequence& base, uint32_t tiles, uint32_t frames,
            double target_kg) {
  Run run;
  run.codec = codec;
  run.series = series;
  run.vertices = tiles * base.vertex_count;
  run.frames = frames;
  const std::string stream = (std::filesystem::temp_directory_path() / ("m4mesh-scale-" + std::to_string(getpid()) + ".m4m")).string();
  const auto [encoded, encode_peak] = in_child([&] {
    const HerdSource source(base, tiles, frames);
    const auto start = std::chrono::steady_clock::now();
    std::ostringstream out;
    if (codec == "draco") {
      // Every frame coded alone with edgebreaker at 12 bits, then decoded (in this process: no stream file).
      uint64_t bytes = 0;
      std::vector<std::vector<char>> coded;
      FrameReader reader(source);
      std::vector<std::array<float, 3>> floats(source.vertex_count());
      for (uint32_t f = 0; f < frames; ++f) {
        const std::span<const Vec3> frame = reader.get(f);
        for (size_t v = 0; v < frame.size(); ++v)
          floats[v] = {static_cast<float>(frame[v].x), static_cast<float>(frame[v].y), static_cast<float>(frame[v].z)};
        if (coded.size() == 64) coded.erase(coded.begin());  // bounded: the decode below times the last 64 frames
        coded.push_back(draco_frame_encoded(source.faces(), floats, 12));
        bytes += coded.back().size();
      }
      const double encode = seconds_since(start);
      const auto decoding = std::chrono::steady_clock::now();
      size_t decoded = 0;
      for (const std::vector<char>& frame : coded) decoded += draco_frame_decode(frame);
      const double decode = coded.empty() ? 0 : seconds_since(decoding) * frames / static_cast<double>(coded.size());
      out << encode << ' ' << bytes << " 0 " << decode << ' ' << decoded;
      return out.str();
    }
    std::ofstream file(stream, std::ios::binary);
    Encode3dOptions options;
    options.codec = codec;
    options.output = [&](std::span<const uint8_t> bytes) { file.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size())); };
    options.restart_output = [&] {
      file.close();
      file.open(stream, std::ios::binary | std::ios::trunc);
    };
    Encode3dResult result;
    if (target_kg > 0)
      result = encode_to_target(source, options, {.kg = target_kg}, [](const TargetTrial&) {});
    else
      result = encode_mesh3d(source, options);
    out << seconds_since(start) << ' ' << result.stream_bytes << ' ' << result.kg;
    return out.str();
  });
  std::istringstream in(encoded);
  if (encoded.starts_with("error")) {
    run.error = encoded.substr(6);
    return run;
  }
  in >> run.encode_seconds >> run.bytes >> run.kg;
  run.encode_peak_kb = encode_peak;
  if (codec == "draco") {
    in >> run.decode_seconds;
    run.decode_peak_kb = encode_peak;
    return run;
  }
  const auto [decoded, decode_peak] = in_child([&] {
    const auto start = std::chrono::steady_clock::now();
    Mesh3dDecoder decoder(ContainerSource::open_file(stream));
    double checksum = 0;
    while (decoder.next_frame()) checksum += decoder.positions()[0][0];
    std::ostringstream out;
    out << seconds_since(start) << ' ' << checksum;
    return out.str();
  });
  std::filesystem::remove(stream);
  if (decoded.starts_with("error")) {
    run.error = "decode: " + decoded.substr(6);
    return run;
  }
  std::istringstream(decoded) >> run.decode_seconds;
  run.decode_peak_kb = decode_peak;
  return run;
}

// The slope of log(seconds) against log(vertex-frames), least squares.
double exponent(const std::vector<const Run*>& runs, double Run::*seconds) {
  double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (const Run* r : runs) {
    if (!r->error.empty() || r->*seconds <= 0) continue;
    const double x = std::log(r->vertex_frames()), y = std::log(r->*seconds);
    n += 1;
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
  }
  return n >= 2 ? (n * sxy - sx * sy) / (n * sxx - sx * sx) : NAN;
}

// What segments cost: cpca-wpt at one quality target over a long sequence,
// as one model and in segments of 1/2, 1/4 and 1/10 of its frames (the
// horse over 480 frames, ten gallops; the cloth flag's 300 frames).
void segment_costs(const MeshSequence& horse, double target_kg) {
  std::vector<std::pair<std::string, MeshSequence>> cases;
  cases.emplace_back(label(0) + " × 480", read_all_frames(HerdSource(horse, 1, 480)));
  if (const fs::path flag = kData / "cloth" / "flag" / "flag.pc2"; fs::exists(flag)) cases.emplace_back("cloth flag", load_sequence(flag.string()));
  std::printf("cpca-wpt in segments, at KG %g:\n%-22s %8s %8s %10s %8s %9s %10s\n", target_kg, "sequence", "segment", "segments", "bytes", "bpvf",
              "KG %", "vs whole");
  for (const auto& [name, sequence] : cases) {
    const uint32_t n = static_cast<uint32_t>(sequence.frames.size());
    uint64_t whole = 0;
    for (const uint32_t length : {n, n / 2, n / 4, n / 10}) {
      Encode3dOptions options;
      options.codec = "cpca-wpt";
      options.codec_options = {{"segment-frames", std::to_string(length)}};
      Encode3dResult r;
      try {
        r = encode_to_target(sequence, options, {.kg = target_kg}, [](const TargetTrial&) {});
      } catch (const Error& e) {
        std::printf("%-22s %8u %8u  %s\n", name.c_str(), length, (n + length - 1) / length, e.what());
        continue;
      }
      if (length == n) whole = r.stream_bytes;
      std::printf("%-22s %8u %8u %10llu %8.4f %9.4f %+9.1f%%\n", name.c_str(), length, (n + length - 1) / length,
                  static_cast<unsigned long long>(r.stream_bytes), 8.0 * static_cast<double>(r.stream_bytes) / (static_cast<double>(sequence.vertex_count) * n), r.kg,
                  100.0 * (static_cast<double>(r.stream_bytes) / static_cast<double>(whole) - 1));
      std::fflush(stdout);
    }
  }
}

std::vector<std::string> split(const std::string& text) {
  std::vector<std::string> parts;
  std::istringstream in(text);
  for (std::string part; std::getline(in, part, ',');) parts.push_back(part);
  return parts;
}

}  // namespace
}  // namespace m4mesh::bench

int main(int argc, char** argv) {
  using namespace m4mesh;
  using namespace m4mesh::bench;
  use_one_heap();  // as the m4mesh command does
  double most = 1e8, target_kg = 0.5;
  std::vector<std::string> codecs{"bfs3d", "affine-octree", "lcc", "cpca-wpt", "draco"}, series{"frames", "mesh"};
  std::string json;
  bool segments = false;
  for (int i = 1; i < argc; i += 2) {
    const std::string flag = argv[i];
    if (flag == "--segments") {
      segments = true;
      --i;
      continue;
    }
    const bool known = flag == "--max" || flag == "--codecs" || flag == "--series" || flag == "--target-kg" || flag == "--json";
    if (!known || i + 1 == argc) {
      std::fprintf(stderr, "usage: %s [--max 1e8] [--codecs LIST] [--series frames,mesh] [--target-kg 0.5] [--json FILE] [--segments]\n", argv[0]);
      return flag == "--help" || flag == "-h" ? 0 : 2;
    }
    const std::string value = argv[i + 1];
    if (flag == "--max") most = std::stod(value);
    else if (flag == "--codecs") codecs = split(value);
    else if (flag == "--series") series = split(value);
    else if (flag == "--target-kg") target_kg = std::stod(value);
    else json = value;
  }
  const MeshSequence& base = sequence("horse-gallop");
  if (segments) {
    segment_costs(base, target_kg);
    return 0;
  }
  std::printf("scale benchmark: %s (%u vertices, %zu frames), %s%s, sizes up to %.0e vertex-frames\n", label(0).c_str(), base.vertex_count,
              base.frames.size(), target_kg > 0 ? "at KG " : "codec defaults", target_kg > 0 ? std::to_string(target_kg).c_str() : "", most);
  std::printf("%-14s %-6s %8s %6s %9s %10s %9s %9s %9s %9s %9s %8s\n", "codec", "series", "vertices", "frames", "vf", "enc s", "enc Mvf/s",
              "enc MB", "dec s", "dec Mvf/s", "dec MB", "bpvf");
  std::vector<Run> runs;
  for (const std::string& kind : series) {
    // frames: the base alone, 10^5 … ; mesh: a herd of 12 over 10^6 … vertex-frames.
    const uint32_t tiles = kind == "mesh" ? 12 : 1;
    for (double size = kind == "mesh" ? 1e6 : 1e5; size <= most * 1.0001; size *= 10) {
      const uint32_t frames = static_cast<uint32_t>(std::lround(size / (tiles * base.vertex_count)));
      for (const std::string& codec : codecs) {
        const Run r = measure(codec, kind, base, tiles, std::max(frames, 2u), target_kg);
        runs.push_back(r);
        if (!r.error.empty()) {
          std::printf("%-14s %-6s %8u %6u %9.3g  error: %s\n", r.codec.c_str(), r.series.c_str(), r.vertices, r.frames, r.vertex_frames(),
                      r.error.c_str());
        } else {
          std::printf("%-14s %-6s %8u %6u %9.3g %10.3f %9.3f %9.1f %9.3f %9.2f %9.1f %8.4f\n", r.codec.c_str(), r.series.c_str(), r.vertices,
                      r.frames, r.vertex_frames(), r.encode_seconds, r.vertex_frames() / r.encode_seconds / 1e6, static_cast<double>(r.encode_peak_kb) / 1024.0,
                      r.decode_seconds, r.decode_seconds > 0 ? r.vertex_frames() / r.decode_seconds / 1e6 : 0, static_cast<double>(r.decode_peak_kb) / 1024.0,
                      8.0 * static_cast<double>(r.bytes) / r.vertex_frames());
        }
        std::fflush(stdout);
      }
    }
  }
  std::printf("\nexponent of time against size (least squares of log time on log vertex-frames):\n");
  for (const std::string& kind : series)
    for (const std::string& codec : codecs) {
      std::vector<const Run*> of;
      for (const Run& r : runs)
        if (r.codec == codec && r.series == kind) of.push_back(&r);
      std::printf("  %-14s %-6s encode %.3f  decode %.3f\n", codec.c_str(), kind.c_str(), exponent(of, &Run::encode_seconds),
                  exponent(of, &Run::decode_seconds));
    }
  if (!json.empty()) {
    nlohmann::json out = nlohmann::json::array();
    for (const Run& r : runs)
      out.push_back({{"codec", r.codec}, {"series", r.series}, {"vertices", r.vertices}, {"frames", r.frames},
                     {"encode_seconds", r.encode_seconds}, {"decode_seconds", r.decode_seconds}, {"encode_peak_kb", r.encode_peak_kb},
                     {"decode_peak_kb", r.decode_peak_kb}, {"bytes", r.bytes}, {"kg", r.kg}, {"error", r.error}});
    std::ofstream(json) << out.dump(2) << "\n";
  }
  return 0;
}
