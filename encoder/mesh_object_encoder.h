// The 2D mesh object encoder: planes (§9 form) in, a stream out.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "mesh/plane.h"
#include "mesh/traversal.h"
#include "syntax/trace.h"

namespace m4mesh {

struct EncoderOptions {
  MotionMethod method = MotionMethod::kMethod2;
  // Delaunay I-planes: code the nodes in the given order (it must be valid:
  // boundary counterclockwise from the top-left node) instead of §10's.
  bool keep_node_order = false;
  bool end_code = true;
  Trace* trace = nullptr;
  // Notices: a Delaunay input whose triangles differ from the decoder's, a
  // P-plane coded as a new I-plane, …
  std::function<void(const std::string&)> report;
};

struct EncodeResult {
  std::vector<uint8_t> stream;
  int64_t intra_planes = 0;
  int64_t inter_planes = 0;
};

// Encodes plane by plane (see encode()).
class Encoder {
 public:
  explicit Encoder(const EncoderOptions& options = {});
  ~Encoder();
  Encoder(const Encoder&) = delete;
  Encoder& operator=(const Encoder&) = delete;

  void add(const MeshPlane& plane);
  EncodeResult finish();

 private:
  class Impl;
  std::unique_ptr<Impl> impl_;
};

// Input planes hold every plane's node positions by the input's node index;
// the encoder reorders Delaunay nodes (§10) and keeps that order for the
// P-planes that follow. A P-plane with range 0 gets the smallest range (§10).
EncodeResult encode(std::span<const MeshPlane> planes, const EncoderOptions& options = {});

// §10: the coded order of a Delaunay node set whose first `boundary` nodes
// are the boundary polygon (either orientation): boundary counterclockwise
// from the top-left node, then nearest interior node in L1 distance.
std::vector<NodeIndex> delaunay_node_order(std::span<const Point> nodes, uint32_t boundary);

}  // namespace m4mesh
