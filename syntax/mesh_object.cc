#include "syntax/mesh_object.h"

#include "syntax/describe.h"

namespace m4mesh::syntax {

MeshObjectReader::MeshObjectReader(std::span<const uint8_t> stream, Trace* trace)
    : reader_(stream.data(), stream.size()), io_(reader_, trace) {
  io_.start_code("mesh_object_start_code", kMeshObjectStartCode);
}

bool MeshObjectReader::next(MeshObjectPlane& plane) {
  if (finished_) return false;
  // The first plane follows the object start code unconditionally (do … while).
  if (plane_index_ > 0 && nextbits_bytealigned(reader_) != kMeshObjectPlaneStartCode) {
    finished_ = true;
    io_.set_plane(kNoPlane);
    if (reader_.bits_left() == 0) {
      warnings_.push_back({kNoPlane, static_cast<int64_t>(reader_.position()),
                           "mesh_object_end_code missing at the end of the data"});
      return false;
    }
    io_.start_code("mesh_object_end_code", kMeshObjectEndCode);
    has_end_code_ = true;
    if (reader_.bits_left() != 0)
      throw Error(ErrorKind::kTrailingData, "mesh_object_end_code", kNoPlane,
                  static_cast<int64_t>(reader_.position()),
                  std::to_string(reader_.bits_left() / 8) + " bytes after the end code");
    return false;
  }
  io_.set_plane(plane_index_);
  describe(io_, plane, mesh_nodes_);
  ++plane_index_;
  return true;
}

MeshObjectWriter::MeshObjectWriter(Trace* trace) : io_(writer_, trace) {
  io_.start_code("mesh_object_start_code", kMeshObjectStartCode);
}

void MeshObjectWriter::write(MeshObjectPlane& plane) {
  io_.set_plane(plane_index_);
  describe(io_, plane, mesh_nodes_);
  ++plane_index_;
}

std::vector<uint8_t> MeshObjectWriter::finish(bool with_end_code) {
  io_.set_plane(kNoPlane);
  if (plane_index_ == 0)
    throw Error(ErrorKind::kStructure, "MeshObject", kNoPlane, kNoOffset, "a mesh object needs at least one plane");
  if (with_end_code) io_.start_code("mesh_object_end_code", kMeshObjectEndCode);
  return writer_.take_bytes();
}

uint64_t delaunay_node_offset(MeshObjectPlane plane, uint32_t node) {
  CountIO count(node == 0 ? "node0_x" : "delta_x_len_vlc", node == 0 ? 0 : node - 1);
  uint32_t mesh_nodes = 0;
  describe(count, plane, mesh_nodes);
  return count.offset_of_watched();
}

MeshObject read_mesh_object(std::span<const uint8_t> stream, Trace* trace) {
  MeshObjectReader reader(stream, trace);
  MeshObject object;
  MeshObjectPlane plane;
  while (reader.next(plane)) object.planes.push_back(std::move(plane));
  object.has_end_code = reader.has_end_code();
  return object;
}

std::vector<uint8_t> write_mesh_object(MeshObject& object, Trace* trace) {
  MeshObjectWriter writer(trace);
  for (MeshObjectPlane& plane : object.planes) writer.write(plane);
  return writer.finish(object.has_end_code);
}

}  // namespace m4mesh::syntax
