#include "mesh3d/draco_base.h"

#include <algorithm>

#include <draco/compression/decode.h>
#include <draco/compression/encode.h>
#include <draco/mesh/mesh.h>

#include "common/error.h"

namespace m4mesh {

namespace {

Error base_error(const std::string& message) { return Error(ErrorKind::kInput, "", kNoPlane, kNoOffset, message); }

template <class T>
std::unique_ptr<draco::Mesh> draco_mesh(std::span<const Triangle> faces, std::span<const std::array<T, 3>> positions,
                                        draco::DataType type) {
  auto mesh = std::make_unique<draco::Mesh>();
  mesh->set_num_points(static_cast<uint32_t>(positions.size()));
  draco::GeometryAttribute attribute;
  attribute.Init(draco::GeometryAttribute::POSITION, nullptr, 3, type, false, sizeof(T) * 3, 0);
  const int id = mesh->AddAttribute(attribute, true, static_cast<uint32_t>(positions.size()));
  for (uint32_t i = 0; i < positions.size(); ++i)
    mesh->attribute(id)->SetAttributeValue(draco::AttributeValueIndex(i), positions[i].data());
  for (const Triangle& t : faces)
    mesh->AddFace(draco::Mesh::Face{draco::PointIndex(t.v[0]), draco::PointIndex(t.v[1]), draco::PointIndex(t.v[2])});
  return mesh;
}

}  // namespace

std::vector<uint8_t> encode_base_mesh(std::span<const Triangle> faces, std::span<const IntPoint3> positions) {
  const std::unique_ptr<draco::Mesh> mesh = draco_mesh(faces, positions, draco::DT_INT32);
  draco::Encoder encoder;
  encoder.SetEncodingMethod(draco::MESH_SEQUENTIAL_ENCODING);
  draco::EncoderBuffer buffer;
  const draco::Status status = encoder.EncodeMeshToBuffer(*mesh, &buffer);
  if (!status.ok()) throw base_error(std::string("Draco cannot encode the base mesh: ") + status.error_msg());
  return std::vector<uint8_t>(buffer.data(), buffer.data() + buffer.size());
}

BaseMesh decode_base_mesh(std::span<const uint8_t> data, uint32_t vertex_count, uint32_t face_count) {
  // "DRACO", bitstream version 2.2, a triangular mesh (1), sequential connectivity (0).
  static const uint8_t kHeader[9] = {'D', 'R', 'A', 'C', 'O', 2, 2, 1, 0};
  if (data.size() < sizeof kHeader || !std::equal(kHeader, kHeader + sizeof kHeader, data.begin()))
    throw base_error("not a Draco 2.2 mesh with sequential connectivity");
  draco::DecoderBuffer buffer;
  buffer.Init(reinterpret_cast<const char*>(data.data()), data.size());
  draco::Decoder decoder;
  auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
  if (!decoded.ok()) throw base_error(std::string("Draco cannot decode the base mesh: ") + decoded.status().error_msg());
  const std::unique_ptr<draco::Mesh> mesh = std::move(decoded).value();
  if (mesh->num_points() != vertex_count || mesh->num_faces() != face_count)
    throw base_error("the base mesh has " + std::to_string(mesh->num_points()) + " vertices and " +
                     std::to_string(mesh->num_faces()) + " faces where the object header says " +
                     std::to_string(vertex_count) + " and " + std::to_string(face_count));
  const draco::PointAttribute* position = mesh->GetNamedAttribute(draco::GeometryAttribute::POSITION);
  if (mesh->num_attributes() != 1 || position == nullptr || position->data_type() != draco::DT_INT32 || position->num_components() != 3)
    throw base_error("the base mesh must have one attribute: POSITION, 3 × INT32");
  BaseMesh base;
  base.positions.resize(vertex_count);
  for (uint32_t i = 0; i < vertex_count; ++i) {
    const draco::AttributeValueIndex value = position->mapped_index(draco::PointIndex(i));
    if (value.value() >= position->size()) throw base_error("a base mesh vertex has no position");
    position->GetValue(value, base.positions[i].data());
  }
  base.faces.resize(face_count);
  for (uint32_t f = 0; f < face_count; ++f) {
    const draco::Mesh::Face& face = mesh->face(draco::FaceIndex(f));
    for (int j = 0; j < 3; ++j) {
      if (face[j].value() >= vertex_count) throw base_error("a base mesh face index is out of range");
      base.faces[f].v[j] = face[j].value();
    }
  }
  return base;
}

size_t draco_frame_size(std::span<const Triangle> faces, std::span<const std::array<float, 3>> positions, int bits) {
  const std::unique_ptr<draco::Mesh> mesh = draco_mesh(faces, positions, draco::DT_FLOAT32);
  draco::Encoder encoder;
  encoder.SetEncodingMethod(draco::MESH_EDGEBREAKER_ENCODING);
  encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, bits);
  draco::EncoderBuffer buffer;
  const draco::Status status = encoder.EncodeMeshToBuffer(*mesh, &buffer);
  if (!status.ok()) throw base_error(std::string("Draco cannot encode a frame: ") + status.error_msg());
  return buffer.size();
}

}  // namespace m4mesh
