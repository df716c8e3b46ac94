// The base mesh on every sequence of ../shared/data (synthetic when
// absent): bits per vertex of its first frame at 10, 12 and 14 bits, in
// input order and with --reorder, beside Draco's edgebreaker and sequential
// coding of the same grid positions, all in one run; its decoding speed,
// and its position order's alone.
#include <benchmark/benchmark.h>

#include <numeric>

#include "anchors/draco_reference.h"
#include "bench/sequences.h"
#include "codecs3d/codec_decoder.h"
#include "codecs3d/codec_encoder.h"
#include "encoder/mesh3d/base_mesh.h"
#include "mesh3d/position_order.h"
#include "mesh3d/quantization.h"

namespace m4mesh {
namespace {

const char* const kSequences[] = {"horse-gallop",
                                  "pcow",
                                  "openfamc_testdata/dance_mesh",
                                  "openfamc_testdata/dog_mesh",
                                  "openfamc_testdata/handstand_mesh",
                                  "cloth/flag/flag.pc2"};

std::vector<IntPoint3> grid_positions(const MeshSequence& s, int bits) {
  const Grid grid = Grid::over(s.frames[0], bits, true);
  std::vector<IntPoint3> q(s.vertex_count);
  for (uint32_t i = 0; i < s.vertex_count; ++i) grid.quantize(s.frames[0][i], q[i]);
  return q;
}

std::vector<uint8_t> base_unit(const MeshSequence& s, const std::vector<IntPoint3>& q, bool reorder) {
  const BaseMeshPlan plan = plan_base_mesh(s.faces, s.vertex_count, reorder);
  std::vector<IntPoint3> positions = q;
  if (reorder)
    for (uint32_t i = 0; i < s.vertex_count; ++i) positions[i] = q[plan.input_of[i]];
  BitWriter writer;
  syntax::WriteIO io(writer);
  write_base_mesh(io, plan.faces, positions, BaseMeshCoding{std::nullopt, reorder});
  return writer.take_bytes();
}

// Counters: bits per vertex, m4mesh in input order and reordered, Draco
// edgebreaker and sequential on the same grid positions.
void BM_BaseMeshRate(benchmark::State& state) {
  const MeshSequence& s = bench::sequence(kSequences[state.range(0)]);
  const int bits = static_cast<int>(state.range(1));
  const std::vector<IntPoint3> q = grid_positions(s, bits);
  size_t ordered = 0;
  for (auto _ : state) ordered = base_unit(s, q, false).size();
  const double v = s.vertex_count;
  state.counters["m4mesh"] = 8.0 * static_cast<double>(ordered) / v;
  state.counters["m4mesh_reorder"] = 8.0 * static_cast<double>(base_unit(s, q, true).size()) / v;
  state.counters["draco_eb"] = 8.0 * static_cast<double>(draco_grid_size(s.faces, q, true)) / v;
  state.counters["draco_seq"] = 8.0 * static_cast<double>(draco_grid_size(s.faces, q, false)) / v;
  state.SetLabel(bench::label(kSequences[state.range(0)]) + " " + std::to_string(bits) + " bits");
}
BENCHMARK(BM_BaseMeshRate)->ArgsProduct({{0, 1, 2, 3, 4, 5}, {10, 12, 14}})->Unit(benchmark::kMillisecond)->Iterations(1);

// Bits per vertex of each part at 12 bits in the input order, each coded
// alone.
void BM_BaseMeshParts(benchmark::State& state) {
  const MeshSequence& s = bench::sequence(kSequences[state.range(0)]);
  const std::vector<IntPoint3> q = grid_positions(s, 12);
  const BaseMeshPlan plan = plan_base_mesh(s.faces, s.vertex_count, false);
  BaseMeshParts parts;
  for (auto _ : state) parts = base_mesh_parts(plan.faces, q, BaseMeshCoding{});
  const double v = s.vertex_count;
  state.counters["connectivity"] = 8.0 * static_cast<double>(parts.connectivity) / v;
  state.counters["order"] = 8.0 * static_cast<double>(parts.vertex_order) / v;
  state.counters["positions"] = 8.0 * static_cast<double>(parts.positions) / v;
  state.SetLabel(bench::label(kSequences[state.range(0)]));
}
BENCHMARK(BM_BaseMeshParts)->DenseRange(0, 5)->Unit(benchmark::kMillisecond)->Iterations(1);

void BM_BaseMeshDecode(benchmark::State& state) {
  const MeshSequence& s = bench::sequence(kSequences[state.range(0)]);
  const std::vector<uint8_t> unit = base_unit(s, grid_positions(s, 12), false);
  const ObjectHeader header{kFormatVersion, 1, s.vertex_count, static_cast<uint32_t>(s.faces.size()), 1, 25, 1};
  for (auto _ : state) {
    BitReader reader(unit.data(), unit.size());
    syntax::ReadIO io(reader);
    benchmark::DoNotOptimize(read_base_mesh(io, header, nullptr).positions.data());
  }
  state.SetLabel(bench::label(kSequences[state.range(0)]) + ", position_blend " + std::to_string(unit[1]));
  state.counters["vertices/s"] = benchmark::Counter(static_cast<double>(state.iterations()) * s.vertex_count, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_BaseMeshDecode)->Arg(0)->Arg(2)->Unit(benchmark::kMillisecond);

// The position order alone (PositionOrder::of over every vertex), on the faces as a decoder has them.
void BM_PositionOrder(benchmark::State& state) {
  const MeshSequence& s = bench::sequence(kSequences[state.range(0)]);
  const std::vector<uint8_t> unit = base_unit(s, grid_positions(s, 12), false);
  const ObjectHeader header{kFormatVersion, 1, s.vertex_count, static_cast<uint32_t>(s.faces.size()), 1, 25, 1};
  BitReader reader(unit.data(), unit.size());
  syntax::ReadIO io(reader);
  const BaseMesh base = read_base_mesh(io, header, nullptr);
  const MeshPredictor predictor(base.faces, s.vertex_count);
  std::vector<uint32_t> all(s.vertex_count);
  std::iota(all.begin(), all.end(), 0u);
  for (auto _ : state) benchmark::DoNotOptimize(PositionOrder(predictor, s.vertex_count).of(all).data());
  state.SetLabel(bench::label(kSequences[state.range(0)]));
  state.counters["vertices/s"] = benchmark::Counter(static_cast<double>(state.iterations()) * s.vertex_count, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_PositionOrder)->Arg(0)->Arg(2)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace m4mesh

BENCHMARK_MAIN();
