// What the 3D suite's streams exercise, read from the decoder's trace of
// each stream: every arithmetic-coded bin by element, context and value,
// and the header and unit fields that choose a normative process (a
// prediction, a reference or coding mode, temporal prediction, an intra
// refresh, cpca-wpt's shifts). The catalog lists every such item the
// syntax allows, by area, with the items no valid stream can reach left
// out (docs/conformance.md argues each).
#pragma once

#include <cstdint>
#include <map>
#include <set>
#include <span>
#include <string>

namespace m4mesh {

// Items are "AREA: text", e.g. "base-mesh: gate_new_vertex ctx 9 = 1",
// "lcc: coding_mode = 1".
std::set<std::string> coverage_items3d(std::span<const uint8_t> stream);

// Every reachable item, by area (base-mesh, container, bfs3d,
// affine-octree, lcc, cpca-wpt).
std::map<std::string, std::set<std::string>> coverage_catalog3d();

}  // namespace m4mesh
