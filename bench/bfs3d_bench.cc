// bfs3d on the real sequences (../shared/data; synthetic when absent):
// encode and decode speed, and the rate and distortion at 10, 12 and 14
// bits against Draco coding every frame on its own, in one run.
#include <benchmark/benchmark.h>

#include <cmath>

#include "anchors/draco_reference.h"
#include "bench/sequences.h"
#include "decoder/mesh3d/container_decoder.h"
#include "encoder/mesh3d/container_encoder.h"
#include "mesh3d/metrics.h"

namespace m4mesh {
namespace {

using bench::kNames;
using bench::label;
using bench::sequence;

void BM_Bfs3dDecode(benchmark::State& state) {
  const MeshSequence& s = sequence(kNames[state.range(0)]);
  Encode3dOptions options;
  options.codec_options["bits"] = std::to_string(state.range(1));
  const std::vector<uint8_t> stream = encode_mesh3d(s, options).stream;
  for (auto _ : state) {
    state.PauseTiming();
    Mesh3dDecoder decoder(stream);
    decoder.next_frame();  // the base mesh (Draco) and its traversal
    state.ResumeTiming();
    while (decoder.next_frame()) benchmark::DoNotOptimize(decoder.positions().data());
  }
  state.SetLabel(label(state.range(0)));
  state.counters["vertices/s"] = benchmark::Counter(
      static_cast<double>(state.iterations()) * s.vertex_count * static_cast<double>(s.frames.size() - 1), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_Bfs3dDecode)->ArgsProduct({{0, 1}, {12}})->Unit(benchmark::kMillisecond);

void BM_Bfs3dEncode(benchmark::State& state) {
  const MeshSequence& s = sequence(kNames[state.range(0)]);
  Encode3dOptions options;
  options.codec_options["bits"] = std::to_string(state.range(1));
  for (auto _ : state) benchmark::DoNotOptimize(encode_mesh3d(s, options).stream.data());
  state.SetLabel(label(state.range(0)));
  state.counters["vertices/s"] = benchmark::Counter(
      static_cast<double>(state.iterations()) * s.vertex_count * static_cast<double>(s.frames.size()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_Bfs3dEncode)->ArgsProduct({{0, 1}, {12}})->Unit(benchmark::kMillisecond);

// Rate and distortion, as counters: bfs3d's bits per vertex per frame over
// frames 1 … F−1 (the base mesh apart), Draco's on the same frames at the
// same quantization, KG error and STED.
void BM_Bfs3dRate(benchmark::State& state) {
  const MeshSequence& s = sequence(kNames[state.range(0)]);
  const int bits = static_cast<int>(state.range(1));
  const bool parallelogram = state.range(2) != 0;
  Encode3dOptions options;
  options.codec_options["bits"] = std::to_string(bits);
  if (parallelogram) options.codec_options["parallelogram"] = "1";
  Encode3dResult encoded;
  for (auto _ : state) encoded = encode_mesh3d(s, options);
  const MeshSequence decoded = decode_mesh3d(encoded.stream);
  double draco_bits = 0;
  for (size_t f = 1; f < s.frames.size(); ++f) {
    std::vector<std::array<float, 3>> p;
    for (const Vec3& v : s.frames[f]) p.push_back({static_cast<float>(v.x), static_cast<float>(v.y), static_cast<float>(v.z)});
    draco_bits += 8.0 * static_cast<double>(draco_frame_size(s.faces, p, bits));
  }
  const double vertex_frames = static_cast<double>(s.vertex_count) * static_cast<double>(s.frames.size() - 1);
  const SequenceMetrics m = compare_sequences(s, decoded);
  state.SetLabel(label(state.range(0)) + (parallelogram ? " parallelogram" : " average"));
  state.counters["bpvf"] = 8.0 * static_cast<double>(encoded.frame_bytes()) / vertex_frames;
  state.counters["draco_bpvf"] = draco_bits / vertex_frames;
  state.counters["base_bpv"] = 8.0 * static_cast<double>(encoded.base_bytes()) / s.vertex_count;
  state.counters["kg"] = m.kg_error;
  state.counters["sted"] = m.sted;
}
BENCHMARK(BM_Bfs3dRate)->ArgsProduct({{0, 1}, {10, 12, 14}, {0, 1}})->Iterations(1)->Unit(benchmark::kMillisecond);

// Every metric of `m4mesh metrics` on a 300 × 300 sheet (90,000 vertices)
// over 3 frames, against a copy moved by a small ripple (issue 16's case:
// 9.4 s when the diameter took every pair of vertices; target < 0.5 s).
void BM_Metrics90k(benchmark::State& state) {
  const int n = 300;
  MeshSequence s = bench::grid_sheet(n);
  MeshSequence moved = s;
  for (int f = 0; f < 3; ++f) {
    std::vector<Vec3> frame, ripple;
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        frame.push_back({x / 150.0, y / 150.0, 0.1 * std::sin(0.05 * x + 0.3 * f)});
        ripple.push_back({frame.back().x, frame.back().y, frame.back().z + 1e-4 * std::cos(0.2 * y)});
      }
    s.frames.push_back(std::move(frame));
    moved.frames.push_back(std::move(ripple));
  }
  SequenceMetrics m;
  for (auto _ : state) m = compare_sequences(s, moved);
  state.counters["sted"] = m.sted;
}
BENCHMARK(BM_Metrics90k)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace m4mesh

BENCHMARK_MAIN();
