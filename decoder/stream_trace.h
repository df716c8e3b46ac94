// What `m4mesh trace` prints of a 2D or 3D stream (syntax/trace.h): the
// whole of it, one part, or its fixed fields alone.
#pragma once

#include <cstdint>
#include <optional>
#include <ostream>
#include <span>
#include <string>
#include <vector>

namespace m4mesh {

struct TraceSelection {
  // Only this part (Trace's parts: −1 the object header or mesh object,
  // k the 3D unit or 2D plane k); reading stops once it is traced (the 3D
  // object header after the first unit, where a header's section may be read).
  std::optional<int64_t> part;
  // Bins and raw bits of arithmetic-coded sections too (3D).
  bool symbols = true;
};

// Reads the stream's syntax as the decoder does, printing its elements to
// `out`; an error in the stream is thrown after the lines before it.
void trace_stream(std::span<const uint8_t> stream, std::ostream& out, const TraceSelection& selection = {});

// What each unit of a 3D stream is, as tools list it: its unit type, then
// its frame ("frame 3"), or for a cpca-wpt refinement unit its cluster and
// kind ("refinement, cluster 2 start"). A unit whose header cannot be
// read is "unreadable"; an error in the container is thrown.
std::vector<std::string> unit_labels3d(std::span<const uint8_t> stream);

}  // namespace m4mesh
