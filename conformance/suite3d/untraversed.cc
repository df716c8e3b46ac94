// Loose faces and vertices outside the base mesh traversal under every
// codec, those vertices numbered in orders m4mesh's encoder never uses
// (docs/base_mesh.md: they take the coding numbers after the traversal in
// any order): a decoder that reads output order for coding order, or
// leaves loose faces out of a prediction, decodes these streams otherwise.
#include <algorithm>

#include "conformance/suite3d/cases.h"
#include "conformance/suite3d/inputs.h"
#include "conformance/suite3d/stream_edits.h"
#include "syntax/mesh3d/cpca_wpt.h"

namespace m4mesh::suite3d {

namespace {

// The vertices outside the traversal in two orders m4mesh's encoder never
// uses: decreasing, and odd places first, then even ones.
std::vector<std::vector<uint32_t>> other_orders(const std::vector<uint32_t>& increasing) {
  std::vector<uint32_t> decreasing(increasing.rbegin(), increasing.rend()), interleaved;
  for (size_t start : {size_t{1}, size_t{0}})
    for (size_t i = start; i < increasing.size(); i += 2) interleaved.push_back(increasing[i]);
  return {decreasing, interleaved};
}

constexpr const char* kOrderNames[2] = {"decreasing", "interleaved"};
constexpr const char* kOrderPurposes[2] = {"in decreasing output order", "odd places first, then even ones"};

}  // namespace

std::vector<SuiteCase> untraversed_cases(bool traced) {
  const MeshSequence awkward = awkward_mesh(4);
  std::vector<SuiteCase> suite;
  int number = 1;
  auto id = [&number](const std::string& codec, const char* order) {
    char text[64];
    std::snprintf(text, sizeof text, "ut-%02d-%s-%s", number++, codec.c_str(), order);
    return std::string(text);
  };
  // The frame codecs and unit_kind 1 address vertices by output number: the
  // encoder's stream with its base mesh unit written again keeps its frames
  // and hash units.
  const struct {
    const char* id;
    const char* codec;
    Encode3dOptions options;
  } codecs[] = {
      {"bfs3d", "bfs3d", Encode3dOptions{}},
      {"ao", "Affine-Octree", affine("1")},
      {"lcc", "lcc", lcc({})},
      {"cpca", "cpca-wpt, components in index order (unit_kind 1)", cpca({{"clusters", "2"}})},
  };
  for (const auto& c : codecs) {
    Encode3dOptions o = c.options;
    o.hash_group = 1;
    const std::vector<uint8_t> stream = encode_mesh3d(awkward, o).stream;
    if (std::string(c.id) != "bfs3d")  // base-01-awkward is bfs3d's
      suite.push_back(valid(id(c.id, "increasing"), std::string(c.codec) + " over loose faces and vertices in no face, numbered as m4mesh does",
                            {"base-mesh"}, awkward, c.options, traced));
    const std::vector<std::vector<uint32_t>> orders = other_orders(untraversed_vertices(stream));
    for (size_t k = 0; k < orders.size(); ++k)
      suite.push_back(written_case(id(c.id, kOrderNames[k]), std::string(c.codec) + ": the vertices outside the traversal numbered " + kOrderPurposes[k],
                                   {"base-mesh"}, with_untraversed_order(stream, orders[k])));
  }
  // Kinds 2 and 3 take the members in coding order: written for each order.
  for (const uint32_t kind : {kCpcaMeshComponent, kCpcaTrajectory}) {
    const std::string name = kind == kCpcaTrajectory ? "cpca-trajectory" : "cpca-mesh";
    const std::string codec = kind == kCpcaTrajectory ? "cpca-wpt, trajectory components (unit_kind 3)" : "cpca-wpt, components over the mesh (unit_kind 2)";
    const std::vector<uint8_t> stream = cpca_over_mesh_stream(awkward, kind, {});
    suite.push_back(written_case(id(name, "increasing"), codec + " over loose faces and vertices in no face, written symbol by symbol", {"cpca"},
                                 stream));
    const std::vector<std::vector<uint32_t>> orders = other_orders(untraversed_vertices(stream));
    for (size_t k = 0; k < orders.size(); ++k)
      suite.push_back(written_case(id(name, kOrderNames[k]), codec + ": the vertices outside the traversal numbered " + kOrderPurposes[k], {"cpca"},
                                   cpca_over_mesh_stream(awkward, kind, orders[k])));
  }
  return suite;
}

}  // namespace m4mesh::suite3d
