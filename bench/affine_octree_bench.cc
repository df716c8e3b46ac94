// Affine-Octree on the real sequences (../shared/data; synthetic when
// absent): decode speed, and the paper's Table IV (matrices, size, ratio to
// 32-bit floats, PSNR) with KG error and STED, at ME = 1, 5, 10, 15 %.
#include <benchmark/benchmark.h>

#include "bench/sequences.h"
#include "decoder/mesh3d/container_decoder.h"
#include "encoder/mesh3d/container_encoder.h"
#include "mesh3d/metrics.h"

namespace m4mesh {
namespace {

using bench::kNames;
using bench::sequence;

Encode3dOptions options_for(int64_t me_percent, int64_t matrix_bits) {
  Encode3dOptions options;
  options.codec = "affine-octree";
  options.codec_options = {{"me", std::to_string(me_percent)}, {"matrix-bits", std::to_string(matrix_bits)}};
  options.hashes = false;
  return options;
}

std::string label(int64_t name, const Encode3dOptions& o) {
  return bench::label(name) + " ME " + o.codec_options.at("me") + "% k " + o.codec_options.at("matrix-bits");
}

void BM_AffineOctreeDecode(benchmark::State& state) {
  const MeshSequence& s = sequence(kNames[state.range(0)]);
  const Encode3dOptions options = options_for(state.range(1), state.range(2));
  const std::vector<uint8_t> stream = encode_mesh3d(s, options).stream;
  for (auto _ : state) {
    state.PauseTiming();
    Mesh3dDecoder decoder(stream);
    decoder.next_frame();  // the base mesh (Draco)
    state.ResumeTiming();
    while (decoder.next_frame()) benchmark::DoNotOptimize(decoder.positions().data());
  }
  state.SetLabel(label(state.range(0), options));
  state.counters["vertices/s"] = benchmark::Counter(
      static_cast<double>(state.iterations()) * s.vertex_count * static_cast<double>(s.frames.size() - 1), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_AffineOctreeDecode)->ArgsProduct({{0, 1}, {1, 15}, {16}})->Unit(benchmark::kMillisecond);

void BM_AffineOctreeEncode(benchmark::State& state) {
  const MeshSequence& s = sequence(kNames[state.range(0)]);
  const Encode3dOptions options = options_for(state.range(1), state.range(2));
  for (auto _ : state) benchmark::DoNotOptimize(encode_mesh3d(s, options).stream.data());
  state.SetLabel(label(state.range(0), options));
  state.counters["vertices/s"] = benchmark::Counter(
      static_cast<double>(state.iterations()) * s.vertex_count * static_cast<double>(s.frames.size()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_AffineOctreeEncode)->ArgsProduct({{0, 1}, {1}, {16}})->Unit(benchmark::kMillisecond);

// Table IV: the whole stream (base mesh with its connectivity included, no
// hash units) against 32-bit floats of every frame's positions.
void BM_AffineOctreeTable(benchmark::State& state) {
  const MeshSequence& s = sequence(kNames[state.range(0)]);
  const Encode3dOptions options = options_for(state.range(1), state.range(2));
  Encode3dResult encoded;
  for (auto _ : state) encoded = encode_mesh3d(s, options);
  const SequenceMetrics m = compare_sequences(s, decode_mesh3d(encoded.stream));
  const double raw = 12.0 * s.vertex_count * static_cast<double>(s.frames.size());
  state.SetLabel(label(state.range(0), options));
  for (const auto& [name, value] : encoded.statistics) state.counters[name] = static_cast<double>(value);
  state.counters["bytes"] = static_cast<double>(encoded.stream.size());
  state.counters["base_bytes"] = static_cast<double>(encoded.base_bytes());
  state.counters["ratio"] = raw / static_cast<double>(encoded.stream.size());
  state.counters["psnr"] = m.psnr;
  state.counters["kg"] = m.kg_error;
  state.counters["sted"] = m.sted;
}
BENCHMARK(BM_AffineOctreeTable)->ArgsProduct({{0, 1}, {1, 5, 10, 15}, {16, 12}})->Iterations(1)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace m4mesh

BENCHMARK_MAIN();
