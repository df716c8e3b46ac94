// I-plane decode of 65,535 random nodes inside the 1024×1024 half-pixel
// square, against CGAL's constrained Delaunay triangulation of the same
// points (issue 3 target: ours ≤ 1.0× CGAL's time).
#include <benchmark/benchmark.h>

#include <set>

#include "decoder/mesh_object_decoder.h"
#include "encoder/mesh_object_encoder.h"
#include "mesh/cdt.h"
#include "tests/cgal_reference.h"

namespace m4mesh {
namespace {

// Boundary: the square's corners; 65,531 distinct random interior nodes, in §10 order.
const std::vector<Point>& square_nodes() {
  static const std::vector<Point> nodes = [] {
    std::vector<Point> raw{{0, 0}, {0, 1023}, {1023, 1023}, {1023, 0}};
    std::set<std::pair<int, int>> used;
    uint64_t state = 99;
    while (raw.size() < 65535) {
      state = state * 6364136223846793005ULL + 1442695040888963407ULL;
      const Point p{static_cast<int32_t>(1 + (state >> 33) % 1022), static_cast<int32_t>(1 + (state >> 13) % 1022)};
      if (used.insert({p.x, p.y}).second) raw.push_back(p);
    }
    std::vector<Point> ordered;
    for (NodeIndex i : delaunay_node_order(raw, 4)) ordered.push_back(raw[i]);
    return ordered;
  }();
  return nodes;
}

void BM_IPlaneDecode65535(benchmark::State& state) {
  MeshPlane intra;
  intra.info.kind = MeshKind::kDelaunay;
  intra.info.boundary = 4;
  intra.nodes = square_nodes();
  EncoderOptions options;
  options.keep_node_order = true;
  const std::vector<uint8_t> stream = encode(std::vector<MeshPlane>{intra}, options).stream;
  for (auto _ : state) {
    Decoder decoder(stream);
    decoder.next();
    benchmark::DoNotOptimize(decoder.triangles().data());
  }
  state.counters["nodes/s"] = benchmark::Counter(static_cast<double>(state.iterations()) * 65535, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_IPlaneDecode65535)->Unit(benchmark::kMillisecond);

// Growth with the node count: Google Benchmark fits the complexity (expected N log N).
void BM_IPlaneDecodeScaling(benchmark::State& state) {
  const size_t count = static_cast<size_t>(state.range(0));
  std::vector<Point> raw{{0, 0}, {0, 1023}, {1023, 1023}, {1023, 0}};
  raw.insert(raw.end(), square_nodes().begin() + 4, square_nodes().begin() + static_cast<std::ptrdiff_t>(count));
  std::vector<Point> ordered;
  for (NodeIndex i : delaunay_node_order(raw, 4)) ordered.push_back(raw[i]);
  MeshPlane intra;
  intra.info.kind = MeshKind::kDelaunay;
  intra.info.boundary = 4;
  intra.nodes = ordered;
  const std::vector<uint8_t> stream = encode(std::vector<MeshPlane>{intra}).stream;
  for (auto _ : state) {
    Decoder decoder(stream);
    decoder.next();
    benchmark::DoNotOptimize(decoder.triangles().data());
  }
  state.SetComplexityN(static_cast<int64_t>(count));
}
BENCHMARK(BM_IPlaneDecodeScaling)->RangeMultiplier(4)->Range(1024, 65535)->Unit(benchmark::kMillisecond)->Complexity();

void BM_OurCdt65535(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(constrained_delaunay(square_nodes(), 4).triangles.data());
}
BENCHMARK(BM_OurCdt65535)->Unit(benchmark::kMillisecond);

void BM_CgalCdt65535(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(reference::cgal_cdt(square_nodes(), 4).data());
}
BENCHMARK(BM_CgalCdt65535)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace m4mesh

BENCHMARK_MAIN();
