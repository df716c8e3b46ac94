// cpca-wpt's plan (docs/codec_cpca_wpt.md, "Order"): which operators of
// one noise step are sent, and in which order: by weight (WPT) or round
// robin over the clusters (RPT).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "encoder/mesh3d/cpca_wpt_operators.h"

namespace m4mesh::cpca_wpt {

// The operators of one noise step, their order and how many are sent.
struct Plan {
  int noise = 0;  // log2 Δ in half steps
  std::vector<Operator> operators;
  std::vector<size_t> order;  // indices into operators, in stream order
  size_t sent = 0;
  double estimated_kg = 0;  // of the prefix sent, from the gains
  uint64_t bytes = 0;       // of the prefix sent
  std::vector<size_t> chains;  // per cluster, the components its chain of operators holds (before the order)
};

// RPT: round r sends every cluster's r-th operator, in cluster order.
std::vector<size_t> round_robin(const std::vector<std::vector<size_t>>& per_cluster);

// WPT: the next unit of the cluster whose next units remove the most
// error per bit, W = Σ gain / Σ bits over the best run of them (so that
// a cheap start with little gain counts with the components it opens;
// ties: the lowest cluster).
std::vector<size_t> by_weight(const std::vector<Operator>& operators, const std::vector<std::vector<size_t>>& per_cluster);

}  // namespace m4mesh::cpca_wpt
