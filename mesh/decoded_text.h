// The decoded-output text of §9 (the conformance format), written
// incrementally with its MD5, and read back as encoder input.
#pragma once

#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "common/md5.h"
#include "mesh/plane.h"

namespace m4mesh {

class DecodedTextWriter {
 public:
  using Sink = std::function<void(std::string_view)>;
  // sink may be empty: only the MD5 is computed.
  explicit DecodedTextWriter(Sink sink = {});

  // triangles: canonical (§9); ignored for P-planes.
  void plane(const PlaneInfo& info, std::span<const Point> nodes, std::span<const Triangle> triangles);
  // Writes `end` and returns the MD5 of the whole text.
  std::string finish();
  // Hands the planes written so far to the sink without `end`: the text of
  // a decoding that stopped early, incomplete by §9's own rule.
  void finish_incomplete();

 private:
  void flush_if_full();
  void flush();

  Sink sink_;
  Md5 md5_;
  std::string buffer_;
  int64_t plane_index_ = 0;
};

// Parses §9 text; errors name `source` and the line.
std::vector<MeshPlane> parse_decoded_text(std::string_view text, const std::string& source);

}  // namespace m4mesh
