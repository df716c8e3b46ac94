// The 2D mesh object decoder: a stream in, one decoded plane at a time out.
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "mesh/plane.h"
#include "mesh/traversal.h"
#include "syntax/mesh_object.h"

namespace m4mesh {

struct DecoderOptions {
  MotionMethod method = MotionMethod::kMethod2;
  Trace* trace = nullptr;
};

class Decoder {
 public:
  // The stream is not copied: it must outlive the decoder.
  Decoder(std::span<const uint8_t> stream, const DecoderOptions& options = {});
  Decoder(std::vector<uint8_t>&&, const DecoderOptions& = {}) = delete;

  // Decodes the next plane; false at the end of the object.
  bool next();

  int64_t plane_index() const { return reader_.planes_read() - 1; }
  const PlaneInfo& info() const { return info_; }
  // Node positions after the current plane, by node index.
  std::span<const Point> nodes() const { return nodes_; }
  // Canonical triangles (§9) of the current mesh.
  std::span<const Triangle> triangles();
  const std::vector<syntax::Warning>& warnings() const { return reader_.warnings(); }
  bool has_end_code() const { return reader_.has_end_code(); }
  // The coding order of the current mesh's P-planes.
  const MotionOrder& motion_order() const { return order_; }
  uint64_t bit_position() const { return reader_.position(); }

 private:
  void decode_geometry(const MeshGeometry& geometry, uint64_t plane_start);
  void build_order();
  void decode_motion(const MeshMotion& motion, uint64_t plane_start);

  DecoderOptions options_;
  syntax::MeshObjectReader reader_;
  MeshObjectPlane plane_;
  PlaneInfo info_;        // the current plane
  PlaneInfo intra_info_;  // the I-plane of the current mesh
  std::vector<Point> nodes_;
  MeshTopology mesh_;
  MotionOrder order_;
  bool order_ready_ = false;
  std::vector<Triangle> triangles_;
  bool triangles_ready_ = false;
  std::vector<Point> vectors_;  // per node, plus the zero slot
};

// Delaunay node coordinates from node0 and the deltas.
std::vector<Point> delaunay_node_positions(const DelaunayGeometry& geometry);

// Decodes a whole stream into §9 text (sink may be empty) and returns its MD5.
std::string decode_to_text(std::span<const uint8_t> stream, const DecoderOptions& options,
                           const std::function<void(std::string_view)>& sink);

}  // namespace m4mesh
