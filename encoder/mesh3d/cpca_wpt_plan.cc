#include "encoder/mesh3d/cpca_wpt_plan.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace m4mesh::cpca_wpt {

std::vector<size_t> round_robin(const std::vector<std::vector<size_t>>& per_cluster) {
  std::vector<size_t> order;
  for (size_t round = 0;; ++round) {
    const size_t before = order.size();
    for (const std::vector<size_t>& ops : per_cluster)
      if (round < ops.size()) order.push_back(ops[round]);
    if (order.size() == before) return order;
  }
}

std::vector<size_t> by_weight(const std::vector<Operator>& operators, const std::vector<std::vector<size_t>>& per_cluster) {
  std::vector<size_t> order, next(per_cluster.size(), 0);
  for (;;) {
    size_t best = SIZE_MAX;
    double best_weight = 0;
    for (size_t c = 0; c < per_cluster.size(); ++c) {
      double gain = 0, bits = 0, weight = -INFINITY;
      for (size_t j = next[c]; j < per_cluster[c].size(); ++j) {
        gain += operators[per_cluster[c][j]].gain;
        bits += 8.0 * static_cast<double>(operators[per_cluster[c][j]].bytes);
        weight = std::max(weight, gain / bits);
      }
      if (next[c] < per_cluster[c].size() && (best == SIZE_MAX || weight > best_weight)) {
        best = c;
        best_weight = weight;
      }
    }
    if (best == SIZE_MAX) return order;
    order.push_back(per_cluster[best][next[best]++]);
  }
}

}  // namespace m4mesh::cpca_wpt
