#include "conformance/suite3d/suite3d.h"

#include "conformance/suite3d/cases.h"

namespace m4mesh {

std::vector<SuiteCase> build_suite3d(bool traced) {
  using namespace suite3d;
  std::vector<SuiteCase> suite;
  auto add = [&suite](std::vector<SuiteCase> cases) {
    for (SuiteCase& c : cases) suite.push_back(std::move(c));
  };
  for (auto group : {affine_octree_cases, bfs3d_cases, lcc_cases, cpca_cases, group_hash_cases, base_mesh_cases, container_cases, untraversed_cases,
                     cpca_segment_cases})
    add(group(traced));
  // The streams to reject, made from those above, in the manifest's order.
  const std::vector<SuiteCase> valid = suite;
  for (auto rejected : {container_header_rejected, affine_octree_rejected, container_unit_rejected, bfs3d_rejected, lcc_rejected,
                        cpca_rejected, group_hash_rejected, base_mesh_unit_rejected, container_edge_rejected, base_mesh_count_rejected,
                        affine_octree_edge_rejected, bfs3d_prefix_rejected, base_mesh_traversal_rejected, bfs3d_header_rejected,
                        container_rules_rejected, header_range_ends_rejected,
                        bfs3d_rules_rejected, base_mesh_rules_rejected, cpca_segment_rejected})
    add(rejected(valid));
  return suite;
}

}  // namespace m4mesh
