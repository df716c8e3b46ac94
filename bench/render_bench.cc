// Pictures: a 512 × 512 shaded frame of the horse (the target: 50 ms on one
// core), the same beside its original with the error coloured, and a 2D
// plane's texture warp. Synthetic sequence when ../shared/data is absent.
#include <benchmark/benchmark.h>

#include "bench/sequences.h"
#include "mesh/uniform.h"
#include "render/shaded.h"
#include "render/texture_warp.h"

namespace m4mesh {
namespace {

void BM_Render3dFrame(benchmark::State& state) {
  const MeshSequence& s = bench::sequence(bench::kNames[0]);
  const auto [lo, hi] = sequence_box(s);
  Image image(512, 512);
  for (auto _ : state) {
    const Camera camera(lo, hi, 30, 20, 512);
    draw_shaded(image, 0, camera, s.frames[0], s.faces);
    benchmark::DoNotOptimize(image.pixels.data());
  }
  state.SetLabel(bench::label(0) + ", 512 × 512");
}
BENCHMARK(BM_Render3dFrame)->Unit(benchmark::kMillisecond);

void BM_Render3dCompare(benchmark::State& state) {
  const MeshSequence& s = bench::sequence(bench::kNames[0]);
  const auto [lo, hi] = sequence_box(s);
  Image image(2 * 512 + 80, 512);
  std::vector<Rgb> colours(s.vertex_count);
  for (uint32_t i = 0; i < s.vertex_count; ++i) colours[i] = error_colour(static_cast<double>(i % 97) / 96);
  for (auto _ : state) {
    const Camera camera(lo, hi, 30, 20, 512);
    draw_shaded(image, 0, camera, s.frames[0], s.faces);
    draw_shaded(image, 512, camera, s.frames[1], s.faces, colours);
    draw_legend(image, 1024, 0.01);
    benchmark::DoNotOptimize(image.pixels.data());
  }
  state.SetLabel(bench::label(0) + ", two 512 × 512 views and the legend");
}
BENCHMARK(BM_Render3dCompare)->Unit(benchmark::kMillisecond);

void BM_TextureWarp(benchmark::State& state) {
  const UniformParams grid{33, 25, 16, 16, 0};
  const std::vector<Point> nodes = uniform_nodes(grid);
  const std::vector<Triangle> triangles = uniform_triangles(grid);
  std::vector<Point> moved = nodes;
  for (size_t i = 0; i < moved.size(); ++i) moved[i].y += static_cast<int32_t>(i % 7);
  const Canvas canvas = united(canvas_over(nodes), canvas_over(moved));
  const Image texture = checkerboard(canvas.width, canvas.height);
  const TextureWarp warp(nodes, triangles, texture, canvas);
  for (auto _ : state) benchmark::DoNotOptimize(warp.render(moved, false).pixels.data());
  state.SetLabel("the demo's flag plane, " + std::to_string(canvas.width) + " × " + std::to_string(canvas.height));
}
BENCHMARK(BM_TextureWarp)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace m4mesh

BENCHMARK_MAIN();
