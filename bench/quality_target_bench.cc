// --codec auto at a KG target on the real sequences (synthetic when
// absent): the stream every codec needs, the one kept, the KG reached and
// the time the whole search takes, on one thread and on every core (the
// same stream). One iteration per case: the search is the figure.
#include <benchmark/benchmark.h>

#include "bench/sequences.h"
#include "encoder/mesh3d/quality_target.h"

namespace m4mesh {
namespace {

const char* const kSequences[] = {"horse-gallop", "pcow", "openfamc_testdata/dance_mesh", "openfamc_testdata/dog_mesh",
                                  "openfamc_testdata/handstand_mesh"};

void BM_CodecAuto(benchmark::State& state) {
  const MeshSequence& s = bench::sequence(kSequences[state.range(0)]);
  const QualityTarget target{static_cast<double>(state.range(1)) / 10.0, std::nullopt};
  Encode3dOptions options;
  options.threads = static_cast<unsigned>(state.range(2));
  std::string chosen;
  std::vector<TargetTrial> trials;
  Encode3dResult result;
  for (auto _ : state) {
    trials.clear();
    result = encode_smallest(s, options, target, [&](const TargetTrial& t) { trials.push_back(t); }, chosen);
  }
  const double vertex_frames = static_cast<double>(s.vertex_count) * static_cast<double>(s.frames.size());
  state.counters["bytes"] = static_cast<double>(result.stream.size());
  state.counters["bpvf"] = 8.0 * static_cast<double>(result.stream.size()) / vertex_frames;
  std::string label = bench::label(kSequences[state.range(0)]);
  label += " KG<=" + std::to_string(*target.kg).substr(0, 3) + ":";
  for (const TargetTrial& t : trials) {
    label += " " + t.codec + (t.meets ? " " + t.parameter + " " + std::to_string(t.bytes) + " B" : " misses");
    if (t.codec == chosen) state.counters["kg"] = t.kg;
  }
  state.SetLabel(label + "; kept " + chosen + (options.threads == 1 ? "; one thread" : "; every core"));
}
BENCHMARK(BM_CodecAuto)->ArgsProduct({{0, 1, 2, 3, 4}, {1, 5}, {1, 0}})->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();

}  // namespace
}  // namespace m4mesh

BENCHMARK_MAIN();
