// Decoding through the C interface (api/m4mesh.h: bytes pushed 64 KiB at a
// time, frames pulled as they are ready) against the library's own frame
// loop that `m4mesh decode3d` runs (Mesh3dDecoder::next_frame, hash units
// verified), on the horse and the cow (a synthetic sheet without
// ../shared/data) coded by each codec at its defaults. The interface's
// speed is the ratio of the two times in the same run. BM_PushPieces
// pushes the horse's bfs3d stream 1 byte, 1 KiB and 64 KiB at a time: a
// push's cost in proportion to its bytes gives the same time for all.
#include <benchmark/benchmark.h>

#include <map>

#include "api/m4mesh.h"
#include "bench/sequences.h"
#include "decoder/mesh3d/container_decoder.h"
#include "encoder/mesh3d/container_encoder.h"

namespace m4mesh {
namespace {

const char* const kCodecs[] = {"bfs3d", "affine-octree", "lcc", "cpca-wpt"};

const std::vector<uint8_t>& stream_of(int64_t sequence, int64_t codec) {
  static std::map<std::pair<int64_t, int64_t>, std::vector<uint8_t>> cache;
  auto it = cache.find({sequence, codec});
  if (it == cache.end()) {
    Encode3dOptions o;
    o.codec = kCodecs[codec];
    it = cache.emplace(std::pair(sequence, codec), encode_mesh3d(bench::sequence(bench::kNames[sequence]), o).stream).first;
  }
  return it->second;
}

void label(benchmark::State& state, const std::vector<uint8_t>& stream) {
  state.SetLabel(bench::label(state.range(0)) + " " + kCodecs[state.range(1)]);
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * stream.size()));
}

void BM_DecodeLibrary(benchmark::State& state) {
  const std::vector<uint8_t>& stream = stream_of(state.range(0), state.range(1));
  for (auto _ : state) {
    Mesh3dDecoder decoder(stream);
    while (decoder.next_frame()) benchmark::DoNotOptimize(decoder.positions().data());
  }
  label(state, stream);
}

void decode_in_pieces(benchmark::State& state, const std::vector<uint8_t>& stream, size_t piece) {
  std::vector<float> positions;
  for (auto _ : state) {
    m4mesh_decoder3d* d = m4mesh_decoder3d_new();
    auto pull = [&] {
      m4mesh_header3d h;
      if (m4mesh_decoder3d_header(d, &h) != M4MESH_OK) return;
      positions.resize(3 * size_t{h.vertices});
      uint32_t index = 0;
      while (m4mesh_decoder3d_next_frame(d, &index, positions.data(), positions.size()) == M4MESH_OK) benchmark::DoNotOptimize(positions.data());
    };
    for (size_t at = 0; at < stream.size(); at += piece) {
      if (m4mesh_decoder3d_push(d, stream.data() + at, std::min(piece, stream.size() - at)) != M4MESH_OK) state.SkipWithError("push failed");
      pull();
    }
    if (m4mesh_decoder3d_finish(d) != M4MESH_OK) state.SkipWithError("finish failed");
    pull();
    m4mesh_decoder3d_free(d);
  }
}

void BM_DecodeCInterface(benchmark::State& state) {
  const std::vector<uint8_t>& stream = stream_of(state.range(0), state.range(1));
  decode_in_pieces(state, stream, size_t{1} << 16);
  label(state, stream);
}

void BM_PushPieces(benchmark::State& state) {
  const std::vector<uint8_t>& stream = stream_of(0, 0);
  decode_in_pieces(state, stream, static_cast<size_t>(state.range(0)));
  state.SetLabel(bench::label(0) + " bfs3d, pieces of " + std::to_string(state.range(0)) + " bytes");
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * stream.size()));
}

void cases(benchmark::internal::Benchmark* b) {
  for (int64_t sequence = 0; sequence < 2; ++sequence)
    for (int64_t codec = 0; codec < 4; ++codec) b->Args({sequence, codec});
}

BENCHMARK(BM_DecodeLibrary)->Apply(cases)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DecodeCInterface)->Apply(cases)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PushPieces)->Arg(1)->Arg(1024)->Arg(65536)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace m4mesh

BENCHMARK_MAIN();
