// Decoding speed (docs/rate_distortion.md, "Decoding speed"; the native
// anchor of scripts/web_bench.mjs): each stream decoded to its
// conformance output, every frame with its hash units checked and the
// frames' bytes in memory (a buffer kept from one run to the next),
// exactly what the web module's decodedMd5 does but for the MD5 of the
// output. Per stream:
//   Decode/NAME       the whole stream; counter vf/s (vertex-frames a second)
//   FirstFrame/NAME   until the first frame is handed out
//   BaseMesh/NAME     the object header and the first unit alone
//   Bins/NAME         the stream's arithmetic-coded bins alone (below); counter
//                     vf/s as if decoding took only their time
// Streams: M4MESH_DECODE_STREAMS (comma-separated paths; scripts/decode_corpus.sh
// makes the corpus's), else every stream to decode of the 3D conformance suite.
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#ifdef __GLIBC__
#include <malloc.h>
#endif
#include <map>
#include <sstream>
#include <streambuf>

#include "bitstream/arithmetic.h"
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

// A stream's bins as its trace lists them, section by section (a section's
// index starts again at 0), each coded again with one context per element
// and context number of its section: decoding them is the arithmetic
// decoder's own work on the stream's bins, with no binarization, prediction
// or reconstruction.
class StreamBins : public std::streambuf {
 public:
  struct Section {
    std::vector<uint8_t> bytes;
    std::vector<uint32_t> context_of;  // per bin
    uint32_t contexts = 0;
  };

  explicit StreamBins(std::span<const uint8_t> stream) {
    std::ostream out(this);
    trace_mesh3d(stream, out);
    finish();
  }
  const std::vector<Section>& sections() const { return sections_; }
  uint64_t ones() const { return ones_; }

 private:
  int overflow(int c) override {
    if (c == '\n') take(), line_.clear();
    else if (c != traits_type::eof()) line_ += static_cast<char>(c);
    return c;
  }
  std::streamsize xsputn(const char* s, std::streamsize n) override {
    for (std::streamsize i = 0; i < n; ++i) overflow(s[i]);
    return n;
  }
  void take() {
    const std::optional<TraceLine> line = parse_trace_line(line_);
    if (!line || !line->bin()) return;
    if (line->position.ends_with(":0")) finish(), sections_.emplace_back(), ids_.clear();
    Section& section = sections_.back();
    const auto [id, added] = ids_.try_emplace(line->name + "#" + std::to_string(line->context), section.contexts);
    if (added) ++section.contexts, contexts_.emplace_back();
    const int bin = line->value == "1";
    encoder_.encode(contexts_[id->second], bin);
    section.context_of.push_back(id->second);
    ones_ += bin;
  }
  void finish() {
    if (!sections_.empty() && sections_.back().bytes.empty()) sections_.back().bytes = encoder_.finish();
    encoder_ = ArithmeticEncoder();
    contexts_.clear();
  }

  std::string line_;
  std::vector<Section> sections_;
  std::map<std::string, uint32_t> ids_;
  std::vector<BinContext> contexts_;
  ArithmeticEncoder encoder_;
  uint64_t ones_ = 0;
};

void bins(benchmark::State& state, const std::vector<uint8_t>& stream, std::unique_ptr<StreamBins>& prepared, uint64_t& vertex_frames) {
  if (!prepared) prepared = std::make_unique<StreamBins>(stream), vertex_frames = decoded_frames3d(stream).size() / 12;
  uint64_t count = 0, ones = 0;
  std::vector<BinContext> contexts;
  for (auto _ : state) {
    count = 0, ones = 0;
    for (const StreamBins::Section& section : prepared->sections()) {
      contexts.assign(section.contexts, BinContext{});
      ArithmeticDecoder decoder(section.bytes);
      for (const uint32_t c : section.context_of) ones += static_cast<uint64_t>(decoder.decode(contexts[c]));
      count += section.context_of.size();
    }
    benchmark::DoNotOptimize(ones);
  }
  if (ones != prepared->ones()) state.SkipWithError("the bins decoded again differ from the trace's");
  state.counters["bins/s"] = benchmark::Counter(static_cast<double>(count), benchmark::Counter::kIsIterationInvariantRate);
  state.counters["vf/s"] = benchmark::Counter(static_cast<double>(vertex_frames), benchmark::Counter::kIsIterationInvariantRate);
}

}  // namespace
}  // namespace m4mesh

int main(int argc, char** argv) {
#ifdef __GLIBC__
  // The heap kept as it grows, as in a player that decodes stream after stream: with glibc's own thresholds
  // (moved by the sizes freed so far) a decoding's frames were returned to the system and faulted in again on one
  // run of a binary and not on the next (2.2x on the horse), and a page fault took about 18 us on this project's VM.
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
#endif
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
    auto prepared = std::make_shared<std::unique_ptr<m4mesh::StreamBins>>();
    auto vertex_frames = std::make_shared<uint64_t>(0);
    benchmark::RegisterBenchmark(("Bins/" + name).c_str(), [stream, prepared, vertex_frames](benchmark::State& state) {
      m4mesh::bins(state, *stream, *prepared, *vertex_frames);
    })->Unit(benchmark::kMillisecond);
  }
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
