// MeshObject framing (§3): the object start code, the plane loop and the
// end code. The reader hands out one plane at a time so that memory stays
// bounded by one plane, whatever the stream length.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "syntax/io.h"
#include "syntax/structures.h"

namespace m4mesh::syntax {

struct Warning {
  int64_t plane;
  int64_t bit_offset;
  std::string message;
};

class MeshObjectReader {
 public:
  // Reads mesh_object_start_code.
  explicit MeshObjectReader(std::span<const uint8_t> stream, Trace* trace = nullptr);

  // The next plane; false after the end code, or at the end of the data
  // where the end code is missing (a warning).
  bool next(MeshObjectPlane& plane);

  int64_t planes_read() const { return plane_index_; }
  uint64_t position() const { return reader_.position(); }
  bool has_end_code() const { return has_end_code_; }
  const std::vector<Warning>& warnings() const { return warnings_; }
  // nr_of_mesh_nodes of the current mesh (0 before the first I-plane).
  uint32_t mesh_nodes() const { return mesh_nodes_; }

 private:
  BitReader reader_;
  ReadIO io_;
  int64_t plane_index_ = 0;
  uint32_t mesh_nodes_ = 0;
  bool finished_ = false;
  bool has_end_code_ = false;
  std::vector<Warning> warnings_;
};

class MeshObjectWriter {
 public:
  // Writes mesh_object_start_code.
  explicit MeshObjectWriter(Trace* trace = nullptr);

  void write(MeshObjectPlane& plane);
  uint64_t position() const { return writer_.position(); }
  std::vector<uint8_t> finish(bool with_end_code = true);

 private:
  BitWriter writer_;
  WriteIO io_;
  int64_t plane_index_ = 0;
  uint32_t mesh_nodes_ = 0;
};

// Where node `node` of an I-plane's Delaunay geometry begins (its node0_x,
// else its delta_x_len_vlc), in bits from the plane's start code.
uint64_t delaunay_node_offset(MeshObjectPlane plane, uint32_t node);

// The whole stream in memory (tests, tools).
MeshObject read_mesh_object(std::span<const uint8_t> stream, Trace* trace = nullptr);
std::vector<uint8_t> write_mesh_object(MeshObject& object, Trace* trace = nullptr);

}  // namespace m4mesh::syntax
