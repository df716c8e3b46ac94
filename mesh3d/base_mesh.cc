#include "mesh3d/base_mesh.h"

#include <algorithm>
#include <bit>
#include <numeric>

#include "mesh3d/position_order.h"
#include "mesh3d/quantization.h"
#include "syntax/mesh3d/entropy_io.h"

namespace m4mesh {

namespace {

// Fenwick tree over the input numbers not yet taken, for ranks.
class UnusedSet {
 public:
  explicit UnusedSet(uint32_t size) : tree_(size + 1, 0) {
    for (uint32_t i = 1; i <= size; ++i) {
      tree_[i] += 1;
      const uint32_t parent = i + (i & (~i + 1));
      if (parent <= size) tree_[parent] += tree_[i];
    }
  }
  // How many unused numbers are below n.
  uint32_t rank(uint32_t n) const {
    uint32_t sum = 0;
    for (uint32_t i = n; i > 0; i -= i & (~i + 1)) sum += tree_[i];
    return sum;
  }
  // The unused number with `rank` unused numbers below it.
  uint32_t select(uint32_t rank) const {
    uint32_t position = 0;
    for (uint32_t step = std::bit_floor(static_cast<uint32_t>(tree_.size() - 1)); step > 0; step >>= 1)
      if (position + step < tree_.size() && tree_[position + step] <= rank) {
        position += step;
        rank -= tree_[position];
      }
    return position;
  }
  void take(uint32_t n) {
    for (uint32_t i = n + 1; i < tree_.size(); i += i & (~i + 1)) --tree_[i];
  }

 private:
  std::vector<uint32_t> tree_;
};

}  // namespace

template <class IO>
void describe_vertex_order(IO& io, syntax::BaseMeshContexts& contexts, uint32_t method, std::span<const Triangle> parents,
                           std::vector<uint32_t>& input_of) {
  if (method == kVertexOrderCoding) return;
  const uint32_t count = static_cast<uint32_t>(input_of.size());
  UnusedSet unused(count);
  int64_t previous = -1;
  for (uint32_t i = 0; i < count; ++i) {
    int64_t predicted = previous + 1;
    if (i < parents.size() && parents[i].v[0] != i) {
      const auto [a, b, d] = parents[i].v;
      predicted = method == kVertexOrderFromGate ? int64_t{input_of[a]} : int64_t{input_of[a]} + input_of[b] - input_of[d];
    }
    const uint32_t from = unused.rank(static_cast<uint32_t>(std::clamp<int64_t>(predicted, 0, count - 1)));
    int32_t difference = 0;
    if constexpr (!IO::kReading) difference = static_cast<int32_t>(int64_t{unused.rank(input_of[i])} - from);
    contexts.order.describe(io, 0, difference, syntax::kOrderNames);
    const int64_t target = int64_t{from} + difference;
    if (target < 0 || target >= count - i)
      io.fail(ErrorKind::kOutOfRange, "vertex_order_difference", "beyond the input numbers not yet taken");
    input_of[i] = unused.select(static_cast<uint32_t>(target));
    unused.take(input_of[i]);
    previous = input_of[i];
  }
}

PositionCoding::PositionCoding(std::span<const Triangle> faces, uint32_t vertex_count) : predictor(faces, vertex_count), order(vertex_count) {
  std::iota(order.begin(), order.end(), 0u);
  order = PositionOrder(predictor, vertex_count).of(order);
}

PositionPrediction predict_position(const PositionCoding& coding, std::span<const uint32_t> place, uint32_t i, uint32_t v,
                                    std::span<const IntPoint3> positions) {
  const auto known = [&place, i](uint32_t u) { return place[u] < i; };
  const auto value = [&](uint32_t u) { return positions[u]; };
  PositionPrediction prediction;
  prediction.channel = coding.predictor.predict(v, known, value, prediction.p);
  // A parallelogram's corners are known neighbours: the mean exists.
  if (prediction.channel == syntax::kParallelogramChannel) coding.predictor.neighbour_mean(v, known, value, prediction.mean);
  return prediction;
}

template <class IO>
void describe_positions(IO& io, syntax::BaseMeshContexts& contexts, const PositionCoding& coding, uint32_t blend,
                        std::vector<IntPoint3>& positions) {
  const uint32_t count = static_cast<uint32_t>(positions.size());
  const std::vector<uint32_t>& order = coding.order;
  std::vector<uint32_t> place(count);
  for (uint32_t i = 0; i < count; ++i) place[order[i]] = i;
  std::array<int64_t, 3> p{};
  const IntPoint3* previous = nullptr;
  for (uint32_t i = 0; i < count; ++i) {
    const uint32_t v = order[i];
    const int channel = blended(predict_position(coding, place, i, v, positions), blend, previous, p);
    for (int a = 0; a < 3; ++a) {
      int32_t residual = 0;
      if constexpr (!IO::kReading) residual = static_cast<int32_t>(positions[v][a] - p[a]);
      contexts.positions.describe(io, channel + a, residual, syntax::kPositionNames);
      const int64_t q = p[a] + residual;
      if (q > kMaxQuantized || q < -kMaxQuantized) io.fail(ErrorKind::kOutOfRange, "position", "a position leaves ±2^26 grid steps");
      positions[v][a] = static_cast<int32_t>(q);
    }
    previous = &positions[v];
  }
}

template <class IO>
void describe_predicted_positions(IO& io, syntax::BaseMeshContexts& contexts, const PositionCoding& coding, uint32_t blend,
                                  std::span<const PositionPrediction> predictions, std::span<const IntPoint3> positions) {
  std::array<int64_t, 3> p{};
  const IntPoint3* previous = nullptr;
  for (uint32_t i = 0; i < coding.order.size(); ++i) {
    const uint32_t v = coding.order[i];
    const int channel = blended(predictions[i], blend, previous, p);
    for (int a = 0; a < 3; ++a) {
      int32_t residual = static_cast<int32_t>(positions[v][a] - p[a]);
      contexts.positions.describe(io, channel + a, residual, syntax::kPositionNames);
    }
    previous = &positions[v];
  }
}

template void describe_predicted_positions<syntax::EntropyWriteIO<false>>(syntax::EntropyWriteIO<false>&, syntax::BaseMeshContexts&,
                                                                         const PositionCoding&, uint32_t, std::span<const PositionPrediction>,
                                                                         std::span<const IntPoint3>);

#define M4MESH_BASE_MESH_IO(IO)                                                                                        \
  template void describe_vertex_order<IO>(IO&, syntax::BaseMeshContexts&, uint32_t, std::span<const Triangle>, std::vector<uint32_t>&); \
  template void describe_positions<IO>(IO&, syntax::BaseMeshContexts&, const PositionCoding&, uint32_t, std::vector<IntPoint3>&);
M4MESH_BASE_MESH_IO(syntax::EntropyReadIO<false>)
M4MESH_BASE_MESH_IO(syntax::EntropyReadIO<true>)
M4MESH_BASE_MESH_IO(syntax::EntropyWriteIO<false>)
M4MESH_BASE_MESH_IO(syntax::EntropyWriteIO<true>)
#undef M4MESH_BASE_MESH_IO

}  // namespace m4mesh
