// Streams of the 3D suite changed after their encoder wrote them: a
// container's parts edited and joined again, a unit found by type and
// frame, a field's bytes found by name in the description that reads and
// writes it (never by a counted offset), a unit rewritten from its data.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "bitstream/bit_writer.h"
#include "common/error.h"
#include "conformance/suite.h"
#include "mesh3d/base_mesh.h"
#include "syntax/io.h"
#include "syntax/mesh3d/container.h"

namespace m4mesh::suite3d {

// A stream rebuilt from its parts after `edit` changed them.
template <class Edit>
std::vector<uint8_t> edited(const std::vector<uint8_t>& stream, Edit edit) {
  ContainerParts parts = split_container(stream);
  edit(parts);
  ContainerWriter writer;
  writer.object(parts.object_payload);
  for (const ContainerUnit& unit : parts.units) writer.unit(unit.payload);
  return writer.finish();
}

// The unit of frame `frame` with unit_type `type`.
ContainerUnit& unit_of(ContainerParts& parts, UnitType type, uint32_t frame);

// A unit payload's header (unit_type, frame_index), read; and its bytes,
// which a unit rewritten from its data keeps.
UnitHeader unit_header_of(const std::vector<uint8_t>& payload);
std::vector<uint8_t> unit_header_bytes(const std::vector<uint8_t>& payload);

// Where a field lies in a payload: its first byte and its bytes.
struct FieldBytes {
  size_t first = 0;
  size_t count = 0;
  size_t last() const { return first + count - 1; }
};

// The field or section `name` of the structures `parts` described one
// after the other; it must start and end on a byte.
template <class... Parts>
FieldBytes field_bytes(const char* name, Parts&... parts) {
  syntax::CountIO count(name);
  using syntax::describe;  // unqualified: the codecs' describe() are found where this is used
  (describe(count, parts), ...);
  if (!count.found_watched() || count.offset_of_watched() % 8 != 0 || count.bits_of_watched() % 8 != 0)
    throw Error(ErrorKind::kStructure, "", kNoPlane, kNoOffset, std::string("suite: no byte-aligned field ") + name);
  return {static_cast<size_t>(count.offset_of_watched() / 8), static_cast<size_t>(count.bits_of_watched() / 8)};
}

// A field of a stream's object payload: of the object header or of the
// codec header, read from the stream.
template <class CodecHeader>
FieldBytes object_field(const std::vector<uint8_t>& stream, const char* name) {
  auto [object, header] = read_headers<CodecHeader>(split_container(stream));
  return field_bytes(name, object, header);
}

// A field of a unit payload: of the unit header, or of the unit data
// `Data` before its first section of variable length.
FieldBytes unit_header_field(const char* name);
template <class Data>
FieldBytes unit_field(const char* name) {
  UnitHeader header;
  Data data;
  return field_bytes(name, header, data);
}

// A field's value, and a new one written over its bytes, most significant first.
uint64_t field_value(const std::vector<uint8_t>& payload, FieldBytes field);
void put_field(std::vector<uint8_t>& payload, FieldBytes field, uint64_t value);

// A unit payload whose bin section, which follows its length field
// `length`, gains a zero byte that the length counts.
void add_bins_byte(std::vector<uint8_t>& payload, FieldBytes length);

// The first base mesh unit of a stream's parts, decoded.
BaseMesh base_mesh_of(const ContainerParts& parts);

// The vertices outside the traversal of `stream`'s first base mesh unit, in
// increasing output number.
std::vector<uint32_t> untraversed_vertices(const std::vector<uint8_t>& stream);

// `stream` with its first base mesh unit written again, the vertices
// outside the traversal taking their coding numbers in the order
// `untraversed` lists them (output numbers): the same decoded mesh, another
// coding order.
std::vector<uint8_t> with_untraversed_order(const std::vector<uint8_t>& stream, std::span<const uint32_t> untraversed);

// The stream of case `id`.
const std::vector<uint8_t>& stream_of(const std::vector<SuiteCase>& cases, const std::string& id);

// A unit: its header (the first bytes of the unit it replaces), then its
// data described.
template <class Data>
std::vector<uint8_t> unit_with(std::vector<uint8_t> unit_header, Data data) {
  BitWriter writer;
  syntax::WriteIO out(writer);
  using syntax::describe;
  describe(out, data);
  unit_header.insert(unit_header.end(), writer.bytes().begin(), writer.bytes().end());
  return unit_header;
}

}  // namespace m4mesh::suite3d
