// What tools and benchmarks read of a clustered-PCA stream beside
// decoding it (docs/codec_cpca_wpt.md).
#pragma once

#include <cstdint>
#include <vector>

#include "syntax/mesh3d/container.h"

namespace m4mesh {

// The cluster of every vertex: the header's map, read with the base mesh's
// faces when its prediction needs them.
std::vector<uint32_t> cpca_cluster_map(const ContainerParts& parts);

}  // namespace m4mesh
