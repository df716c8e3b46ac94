// P-plane decode and encode speed on a 256×256 uniform mesh with smooth
// random motion (issue 2 targets: decode ≥ 30 M nodes/s, encode ≥ 20 M
// nodes/s on one core).
#include <benchmark/benchmark.h>

#include <cmath>

#include "decoder/mesh_object_decoder.h"
#include "encoder/mesh_object_encoder.h"

namespace m4mesh {
namespace {

constexpr uint32_t kSide = 256;
constexpr int kInterPlanes = 16;

// A smooth field of random low-frequency waves plus ±1 jitter, per plane.
std::vector<MeshPlane> smooth_motion_planes() {
  UniformParams grid{kSide, kSide, 4, 4, 2};
  MeshPlane intra;
  intra.info.uniform = grid;
  intra.nodes = uniform_nodes(grid);
  std::vector<MeshPlane> planes{intra};
  uint64_t state = 12345;
  auto random = [&] {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(state >> 11) / 9007199254740992.0;
  };
  for (int k = 0; k < kInterPlanes; ++k) {
    MeshPlane inter;
    inter.info.intra = false;
    inter.nodes = planes.back().nodes;
    const double fx = 1 + 3 * random(), fy = 1 + 3 * random(), phase = 6.28 * random();
    for (uint32_t r = 0; r < kSide; ++r) {
      for (uint32_t c = 0; c < kSide; ++c) {
        const double u = static_cast<double>(c) / kSide, v = static_cast<double>(r) / kSide;
        Point& p = inter.nodes[r * kSide + c];
        p.x += static_cast<int32_t>(std::lround(12 * std::sin(6.28 * fx * u + phase) * std::cos(6.28 * fy * v) + 2 * random() - 1));
        p.y += static_cast<int32_t>(std::lround(12 * std::cos(6.28 * fy * v + phase) * std::sin(6.28 * fx * u) + 2 * random() - 1));
      }
    }
    planes.push_back(std::move(inter));
  }
  return planes;
}

const std::vector<MeshPlane>& planes() {
  static const std::vector<MeshPlane> p = smooth_motion_planes();
  return p;
}

void BM_DecodePPlanes(benchmark::State& state) {
  const std::vector<uint8_t> stream = encode(planes()).stream;
  for (auto _ : state) {
    state.PauseTiming();
    Decoder decoder(stream);
    decoder.next();  // the I-plane
    decoder.next();  // the first P-plane, which also builds the traversal (once per I-plane)
    state.ResumeTiming();
    while (decoder.next()) benchmark::DoNotOptimize(decoder.nodes().data());
  }
  state.counters["nodes/s"] = benchmark::Counter(static_cast<double>(state.iterations()) * (kInterPlanes - 1) * kSide * kSide,
                                                 benchmark::Counter::kIsRate);
  state.counters["bits/node"] = 8.0 * static_cast<double>(stream.size()) / (kInterPlanes * kSide * kSide);
}
BENCHMARK(BM_DecodePPlanes)->Unit(benchmark::kMillisecond);

void BM_EncodePPlanes(benchmark::State& state) {
  for (auto _ : state) {
    state.PauseTiming();
    Encoder encoder;
    encoder.add(planes()[0]);
    state.ResumeTiming();
    for (int k = 1; k <= kInterPlanes; ++k) encoder.add(planes()[k]);
    benchmark::DoNotOptimize(encoder.finish().stream.data());
  }
  state.counters["nodes/s"] = benchmark::Counter(static_cast<double>(state.iterations()) * kInterPlanes * kSide * kSide,
                                                 benchmark::Counter::kIsRate);
}
BENCHMARK(BM_EncodePPlanes)->Unit(benchmark::kMillisecond);

// The traversal of a 256×256 uniform mesh, built once per I-plane.
void BM_UniformTraversal(benchmark::State& state) {
  const UniformParams grid{kSide, kSide, 4, 4, 2};
  for (auto _ : state) {
    const MeshTopology mesh = uniform_topology(grid);
    benchmark::DoNotOptimize(method2_order(mesh.triangles, mesh.neighbours, size_t{kSide} * kSide, 0, 1).node.data());
  }
}
BENCHMARK(BM_UniformTraversal)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace m4mesh

BENCHMARK_MAIN();
