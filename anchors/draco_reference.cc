#include "anchors/draco_reference.h"

#include <algorithm>

#include <draco/compression/decode.h>
#include <draco/compression/encode.h>
#include <draco/mesh/mesh.h>

#include "common/error.h"

namespace m4mesh {

namespace {

Error reference_error(const std::string& message) { return Error(ErrorKind::kInput, "", kNoPlane, kNoOffset, message); }

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

size_t draco_grid_size(std::span<const Triangle> faces, std::span<const IntPoint3> positions, bool edgebreaker) {
  const std::unique_ptr<draco::Mesh> mesh = draco_mesh(faces, positions, draco::DT_INT32);
  draco::Encoder encoder;
  encoder.SetEncodingMethod(edgebreaker ? draco::MESH_EDGEBREAKER_ENCODING : draco::MESH_SEQUENTIAL_ENCODING);
  draco::EncoderBuffer buffer;
  const draco::Status status = encoder.EncodeMeshToBuffer(*mesh, &buffer);
  if (!status.ok()) throw reference_error(std::string("Draco cannot encode a mesh: ") + status.error_msg());
  return buffer.size();
}

std::vector<char> draco_frame_encoded(std::span<const Triangle> faces, std::span<const std::array<float, 3>> positions, int bits) {
  const std::unique_ptr<draco::Mesh> mesh = draco_mesh(faces, positions, draco::DT_FLOAT32);
  draco::Encoder encoder;
  encoder.SetEncodingMethod(draco::MESH_EDGEBREAKER_ENCODING);
  encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, bits);
  draco::EncoderBuffer buffer;
  const draco::Status status = encoder.EncodeMeshToBuffer(*mesh, &buffer);
  if (!status.ok()) throw reference_error(std::string("Draco cannot encode a frame: ") + status.error_msg());
  return {buffer.data(), buffer.data() + buffer.size()};
}

size_t draco_frame_size(std::span<const Triangle> faces, std::span<const std::array<float, 3>> positions, int bits) {
  return draco_frame_encoded(faces, positions, bits).size();
}

size_t draco_frame_decode(std::span<const char> encoded) {
  draco::DecoderBuffer input;
  input.Init(encoded.data(), encoded.size());
  draco::Decoder decoder;
  auto decoded = decoder.DecodeMeshFromBuffer(&input);
  if (!decoded.ok()) throw reference_error(std::string("Draco cannot decode its frame: ") + decoded.status().error_msg());
  return std::move(decoded).value()->num_points();
}

std::vector<std::array<float, 3>> draco_frame_decoded(std::span<const Triangle> faces, std::span<const std::array<float, 3>> positions,
                                                      int bits) {
  const std::unique_ptr<draco::Mesh> mesh = draco_mesh(faces, positions, draco::DT_FLOAT32);
  draco::Encoder encoder;
  encoder.SetEncodingMethod(draco::MESH_SEQUENTIAL_ENCODING);
  encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, bits);
  draco::EncoderBuffer buffer;
  draco::Status status = encoder.EncodeMeshToBuffer(*mesh, &buffer);
  if (!status.ok()) throw reference_error(std::string("Draco cannot encode a frame: ") + status.error_msg());
  draco::DecoderBuffer input;
  input.Init(buffer.data(), buffer.size());
  draco::Decoder decoder;
  auto decoded = decoder.DecodeMeshFromBuffer(&input);
  if (!decoded.ok()) throw reference_error(std::string("Draco cannot decode its frame: ") + decoded.status().error_msg());
  const std::unique_ptr<draco::Mesh> out = std::move(decoded).value();
  const draco::PointAttribute* attribute = out->GetNamedAttribute(draco::GeometryAttribute::POSITION);
  if (!attribute || out->num_points() != positions.size()) throw reference_error("Draco's decoded frame has other points");
  std::vector<std::array<float, 3>> result(positions.size());
  for (uint32_t i = 0; i < positions.size(); ++i) attribute->GetMappedValue(draco::PointIndex(i), result[i].data());
  return result;
}

}  // namespace m4mesh
