// The cloth codec (lcc) on the windy flag (../shared/data/cloth/flag; a
// synthetic rippling sheet when absent): decode and encode speed, and the
// rate at KG error ≤ 0.1 for stream and download mode, with and without
// temporal prediction, beside bfs3d (both predictions) and Draco per
// frame tuned to the same KG, in one run.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "anchors/draco_reference.h"
#include "bench/sequences.h"
#include "decoder/mesh3d/container_decoder.h"
#include "encoder/mesh3d/container_encoder.h"
#include "mesh3d/lcc.h"
#include "mesh3d/metrics.h"

namespace m4mesh {
namespace {

const char* const kFlag = "cloth/flag/flag.pc2";

std::string flag_label() { return bench::fs::exists(bench::kData / kFlag) ? "flag" : "synthetic"; }

Encode3dOptions lcc(const std::string& mode) {
  Encode3dOptions options;
  options.codec = "lcc";
  options.codec_options = {{"mode", mode}};
  options.hashes = false;
  return options;
}

void BM_LccDecode(benchmark::State& state) {
  const MeshSequence& s = bench::sequence(kFlag);
  const std::vector<uint8_t> stream = encode_mesh3d(s, lcc("stream")).stream;
  for (auto _ : state) {
    state.PauseTiming();
    Mesh3dDecoder decoder(stream);
    decoder.next_frame();  // the reference mesh (Draco) and the model
    state.ResumeTiming();
    while (decoder.next_frame()) benchmark::DoNotOptimize(decoder.positions().data());
  }
  state.SetLabel(flag_label());
  state.counters["vertices/s"] = benchmark::Counter(
      static_cast<double>(state.iterations()) * s.vertex_count * static_cast<double>(s.frames.size() - 1), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_LccDecode)->Unit(benchmark::kMillisecond);

// Placing one frame's vertices from their indices (the decoder's
// reconstruction alone): the indices of the flag's last frame, each vertex
// measured in its own triangle's frame; by chunks of paired steps (what
// the decoder does) and one step after the other (the reference).
void BM_LccPlacement(benchmark::State& state) {
  const MeshSequence& s = bench::sequence(kFlag);
  const LccModel model(s.faces, s.frames[0], 12, 10, 0.5);
  const std::vector<Vec3>& target = s.frames.back();
  std::vector<Vec3> positions = s.frames[0];
  std::vector<int32_t> indices(3 * model.order().steps.size());
  const auto rh_index = [&](double value) {
    const double limit = model.rh_limit();
    return static_cast<int32_t>(std::clamp(std::nearbyint(value / model.rh_step()), -limit, limit));
  };
  for (size_t k = 0; k < model.order().steps.size(); ++k) {
    const LccStep& step = model.order().steps[k];
    const Cylindrical c = to_cylindrical(lcc_frame(target[step.a], target[step.b], target[step.c]), target[step.d]);
    const auto theta = static_cast<int64_t>(std::nearbyint(c.theta * model.theta_limit() / std::numbers::pi));
    indices[3 * k] = lcc_wrapped_angle(theta, model.theta_limit());
    indices[3 * k + 1] = rh_index(c.radius / model.edge_length() - model.reference_radius(k));
    indices[3 * k + 2] = rh_index(c.height / model.edge_length() - model.reference_height(k));
  }
  const bool paired = state.range(0) == 1;
  for (auto _ : state) {
    if (paired) {
      for (size_t chunk = 0; chunk * kLccStepChunk < model.order().steps.size(); ++chunk) model.place_chunk(chunk, indices, positions);
    } else {
      for (size_t k = 0; k < model.order().steps.size(); ++k)
        positions[model.order().steps[k].d] = model.place(k, positions, indices[3 * k], indices[3 * k + 1], indices[3 * k + 2]);
    }
    benchmark::DoNotOptimize(positions.data());
  }
  state.SetLabel(flag_label() + (paired ? ", paired" : ", one by one"));
  state.counters["steps/s"] = benchmark::Counter(static_cast<double>(state.iterations() * model.order().steps.size()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_LccPlacement)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

void BM_LccEncode(benchmark::State& state) {
  const MeshSequence& s = bench::sequence(kFlag);
  for (auto _ : state) benchmark::DoNotOptimize(encode_mesh3d(s, lcc("stream")).stream.data());
  state.SetLabel(flag_label());
  state.counters["vertices/s"] = benchmark::Counter(
      static_cast<double>(state.iterations()) * s.vertex_count * static_cast<double>(s.frames.size()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_LccEncode)->Unit(benchmark::kMillisecond);

// Bits per vertex per frame at KG ≤ 0.1: frame units over V × (F − 1) and
// the whole stream (no hash units) over V × F; the parameter reached.
// 0, 1: lcc stream, download (--target-kg 0.1); 2, 3: bfs3d average,
// parallelogram at the fewest bits that reach it; 4: Draco edgebreaker
// per frame at the quantization bfs3d needs; 5, 6: lcc stream, download
// with temporal prediction (--temporal, default gop).
void BM_RateAtKg01(benchmark::State& state) {
  const MeshSequence& s = bench::sequence(kFlag);
  const double vertex_frames = static_cast<double>(s.vertex_count) * static_cast<double>(s.frames.size() - 1);
  const double all_vertex_frames = static_cast<double>(s.vertex_count) * static_cast<double>(s.frames.size());
  const int64_t which = state.range(0);
  double frame_bpvf = 0, stream_bpvf = 0, kg = 0, parameter = 0;
  for (auto _ : state) {
    if (which <= 1 || which >= 5) {
      Encode3dOptions options = lcc(which % 5 == 0 ? "stream" : "download");
      options.codec_options["target-kg"] = "0.1";
      if (which >= 5) options.codec_options["temporal"] = "1";
      const Encode3dResult r = encode_mesh3d(s, options);
      frame_bpvf = 8.0 * static_cast<double>(r.frame_bytes()) / vertex_frames;
      stream_bpvf = 8.0 * static_cast<double>(r.stream.size()) / all_vertex_frames;
      kg = kg_error(s, decode_mesh3d(r.stream));
      parameter = r.statistics.at(0).second;  // theta bits
    } else {
      for (int bits = 6; bits <= 16; ++bits) {
        Encode3dOptions options;
        options.hashes = false;
        options.codec_options = {{"bits", std::to_string(bits)}, {"parallelogram", which == 3 ? "1" : "0"}};
        const Encode3dResult r = encode_mesh3d(s, options);
        kg = kg_error(s, decode_mesh3d(r.stream));
        if (kg > 0.1) continue;
        parameter = bits;
        if (which == 4) {
          double draco = 0;
          for (size_t f = 1; f < s.frames.size(); ++f) {
            std::vector<std::array<float, 3>> p;
            for (const Vec3& v : s.frames[f]) p.push_back({static_cast<float>(v.x), static_cast<float>(v.y), static_cast<float>(v.z)});
            draco += 8.0 * static_cast<double>(draco_frame_size(s.faces, p, bits));
          }
          frame_bpvf = draco / vertex_frames;
          stream_bpvf = 0;
        } else {
          frame_bpvf = 8.0 * static_cast<double>(r.frame_bytes()) / vertex_frames;
          stream_bpvf = 8.0 * static_cast<double>(r.stream.size()) / all_vertex_frames;
        }
        break;
      }
    }
  }
  const char* const names[] = {"lcc stream",          "lcc download",    "bfs3d average",        "bfs3d parallelogram",
                               "Draco per frame", "lcc stream temporal", "lcc download temporal"};
  state.SetLabel(flag_label() + " " + names[which]);
  state.counters["frame_bpvf"] = frame_bpvf;
  state.counters["stream_bpvf"] = stream_bpvf;
  state.counters["kg"] = kg;
  state.counters["bits"] = parameter;
}
BENCHMARK(BM_RateAtKg01)->DenseRange(0, 6)->Iterations(1)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace m4mesh

BENCHMARK_MAIN();
