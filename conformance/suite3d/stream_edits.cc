#include "conformance/suite3d/stream_edits.h"

#include <set>

#include "bitstream/bit_reader.h"
#include "codecs3d/codec_decoder.h"
#include "codecs3d/codec_encoder.h"
#include "syntax/mesh3d/base_mesh.h"

namespace m4mesh::suite3d {

ContainerUnit& unit_of(ContainerParts& parts, UnitType type, uint32_t frame) {
  for (ContainerUnit& unit : parts.units)
    if (const UnitHeader header = unit_header_of(unit.payload); header.type() == type && header.frame_index == frame) return unit;
  throw Error(ErrorKind::kStructure, "", kNoPlane, kNoOffset, "suite: no such unit");
}

UnitHeader unit_header_of(const std::vector<uint8_t>& payload) {
  BitReader reader(payload.data(), payload.size());
  syntax::ReadIO in(reader);
  UnitHeader header;
  syntax::describe(in, header);
  return header;
}

std::vector<uint8_t> unit_header_bytes(const std::vector<uint8_t>& payload) {
  UnitHeader header;
  syntax::CountIO count;
  syntax::describe(count, header);
  return {payload.begin(), payload.begin() + static_cast<std::ptrdiff_t>(count.bits() / 8)};
}

FieldBytes unit_header_field(const char* name) {
  UnitHeader header;
  return field_bytes(name, header);
}

uint64_t field_value(const std::vector<uint8_t>& payload, FieldBytes field) {
  uint64_t value = 0;
  for (size_t i = 0; i < field.count; ++i) value = value << 8 | payload.at(field.first + i);
  return value;
}

void put_field(std::vector<uint8_t>& payload, FieldBytes field, uint64_t value) {
  for (size_t i = 0; i < field.count; ++i) payload.at(field.last() - i) = static_cast<uint8_t>(value >> (8 * i));
}

void add_bins_byte(std::vector<uint8_t>& payload, FieldBytes length) {
  const uint64_t bins = field_value(payload, length);
  payload.insert(payload.begin() + static_cast<std::ptrdiff_t>(length.first + length.count + bins), 0x00);
  put_field(payload, length, bins + 1);
}

namespace {

// The first base mesh unit of a stream, read, and the number of its faces
// the traversal coded.
struct FirstBaseMesh {
  BaseMesh base;
  size_t traversal_faces = 0;
  BaseMeshCoding coding;  // the unit's blend
};

FirstBaseMesh first_base_mesh(const ContainerParts& parts) {
  BitReader object_reader(parts.object_payload.data(), parts.object_payload.size());
  syntax::ReadIO object_in(object_reader);
  ObjectHeader object;
  syntax::describe(object_in, object);
  const std::vector<uint8_t>& payload = parts.units.at(0).payload;
  BitReader reader(payload.data(), payload.size());
  syntax::ReadIO in(reader);
  UnitHeader header;
  syntax::describe(in, header);
  BaseMesh base = read_base_mesh(in, object, nullptr);
  BaseMeshData data;
  const size_t loose = field_value(payload, field_bytes("loose_face_count", header, data));
  const uint64_t blend = field_value(payload, field_bytes("position_blend", header, data));
  const uint64_t order = field_value(payload, field_bytes("vertex_order", header, data));
  return {std::move(base), object.face_count - loose, {static_cast<uint32_t>(blend), order == kVertexOrderCoding}};
}

}  // namespace

BaseMesh base_mesh_of(const ContainerParts& parts) { return first_base_mesh(parts).base; }

std::vector<uint32_t> untraversed_vertices(const std::vector<uint8_t>& stream) {
  const auto [base, traversal_faces, coding] = first_base_mesh(split_container(stream));
  std::set<uint32_t> reached;
  for (size_t f = 0; f < traversal_faces; ++f) reached.insert(base.faces[f].v.begin(), base.faces[f].v.end());
  std::vector<uint32_t> untraversed;
  for (uint32_t v = 0; v < base.positions.size(); ++v)
    if (!reached.contains(v)) untraversed.push_back(v);
  return untraversed;
}

std::vector<uint8_t> with_untraversed_order(const std::vector<uint8_t>& stream, std::span<const uint32_t> untraversed) {
  return edited(stream, [&](ContainerParts& parts) {
    const FirstBaseMesh first = first_base_mesh(parts);
    BitWriter writer;
    syntax::WriteIO out(writer);
    write_base_mesh(out, first.base.faces, first.base.positions, first.coding, untraversed);
    std::vector<uint8_t>& payload = parts.units.at(0).payload;
    payload = unit_header_bytes(payload);
    payload.insert(payload.end(), writer.bytes().begin(), writer.bytes().end());
  });
}

const std::vector<uint8_t>& stream_of(const std::vector<SuiteCase>& cases, const std::string& id) {
  for (const SuiteCase& c : cases)
    if (c.id == id) return c.stream;
  throw Error(ErrorKind::kStructure, "", kNoPlane, kNoOffset, "suite: no case " + id);
}

}  // namespace m4mesh::suite3d
