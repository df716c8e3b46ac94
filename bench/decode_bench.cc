// Decoding speed (docs/rate_distortion.md, "Decoding speed"; the native
// anchor of scripts/web_bench.mjs): each stream decoded to its
// conformance output, every frame with its hash units checked and the
// frames' bytes in memory (a buffer kept from one run to the next),
// exactly what the web module's decodedMd5 does but for the MD5 of the
// output. Per stream:
//   Decode/NAME       the whole stream; counter vf/s (vertex-frames a second)
//   FirstFrame/NAME   until the first frame is handed out
//   BaseMesh/NAME     the object header and the first unit alone
// Streams: M4MESH_DECODE_STREAMS (comma-separated paths; scripts/decode_corpus.sh
// makes the corpus's), else every stream to decode of the 3D conformance suite.
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <sstream>

#include "common/atomic_file.h"
#include "conformance/manifest.h"
#include "decoder/mesh3d/container_decoder.h"
#include "mesh3d/frame_hash.h"

namespace m4mesh {
namespace {

std::vector<std::string> streams() {
  std::vector<std::string> paths;
  if (const char* list = std::getenv("M4MESH_DECODE_STREAMS")) {
    std::istringstream in(list);
    for (std::string path; std::getline(in, path, ',');)
      if (!path.empty()) paths.push_back(path);
    return paths;
  }
  const std::string suite = std::string(M4MESH_SOURCE_DIR) + "/conformance/mesh3d";
  for (const ManifestEntry& e : read_manifest(suite + "/manifest.json").entries)
    if (e.valid) paths.push_back(suite + "/" + e.file);
  return paths;
}

// frames: the output's buffer, a player's, kept from one decoding to the next and first filled untimed (its
// allocation is not the decoder's).
void decode(benchmark::State& state, const std::vector<uint8_t>& stream, std::vector<uint8_t>& frames) {
  const auto decode_all = [&] {
    frames.clear();
    Mesh3dDecoder decoder(stream);
    while (decoder.next_frame()) append_frame_bytes(decoder.positions(), frames);
  };
  if (frames.empty()) decode_all();
  for (auto _ : state) {
    decode_all();
    benchmark::DoNotOptimize(frames.data());
  }
  const uint64_t vertex_frames = frames.size() / 12;
  state.counters["vf/s"] = benchmark::Counter(static_cast<double>(vertex_frames), benchmark::Counter::kIsIterationInvariantRate);
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * stream.size()));
}

void first_frame(benchmark::State& state, const std::vector<uint8_t>& stream) {
  for (auto _ : state) {
    Mesh3dDecoder decoder(stream);
    if (!decoder.next_frame()) state.SkipWithError("no frame");
    benchmark::DoNotOptimize(decoder.positions().data());
  }
}

void base_mesh(benchmark::State& state, const std::vector<uint8_t>& stream) {
  for (auto _ : state) {
    Mesh3dDecoder decoder(stream);
    if (!decoder.next_unit()) state.SkipWithError("no unit");
    benchmark::DoNotOptimize(decoder.unit().frames.data());
  }
}

}  // namespace
}  // namespace m4mesh

int main(int argc, char** argv) {
  for (const std::string& path : m4mesh::streams()) {
    auto stream = std::make_shared<std::vector<uint8_t>>(m4mesh::read_file(path));
    const std::string name = std::filesystem::path(path).filename().string();
    auto frames = std::make_shared<std::vector<uint8_t>>();
    benchmark::RegisterBenchmark(("Decode/" + name).c_str(), [stream, frames](benchmark::State& state) { m4mesh::decode(state, *stream, *frames); })
        ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("FirstFrame/" + name).c_str(), [stream](benchmark::State& state) { m4mesh::first_frame(state, *stream); })
        ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("BaseMesh/" + name).c_str(), [stream](benchmark::State& state) { m4mesh::base_mesh(state, *stream); })
        ->Unit(benchmark::kMillisecond);
  }
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
