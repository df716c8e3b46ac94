// The native anchor of the WebAssembly decoder's speed (scripts/web_bench.mjs):
// each stream decoded to its conformance output (every frame, hash units
// verified, the MD5), exactly what the web module's decodedMd5 does.
// Streams: M4MESH_DECODE_STREAMS (comma-separated paths), else every
// stream to decode of the 3D conformance suite.
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <sstream>

#include "common/atomic_file.h"
#include "common/md5.h"
#include "conformance/manifest.h"
#include "decoder/mesh3d/container_decoder.h"

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

void decode(benchmark::State& state, const std::vector<uint8_t>& stream) {
  for (auto _ : state) {
    const std::vector<uint8_t> frames = decoded_frames3d(stream);
    benchmark::DoNotOptimize(md5_hex(frames));
  }
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * stream.size()));
}

}  // namespace
}  // namespace m4mesh

int main(int argc, char** argv) {
  for (const std::string& path : m4mesh::streams()) {
    auto stream = std::make_shared<std::vector<uint8_t>>(m4mesh::read_file(path));
    benchmark::RegisterBenchmark(("Decode/" + std::filesystem::path(path).filename().string()).c_str(),
                                 [stream](benchmark::State& state) { m4mesh::decode(state, *stream); })
        ->Unit(benchmark::kMillisecond);
  }
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
