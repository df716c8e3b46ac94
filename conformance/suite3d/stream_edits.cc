#include "conformance/suite3d/stream_edits.h"

#include "bitstream/bit_reader.h"

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

const std::vector<uint8_t>& stream_of(const std::vector<SuiteCase>& cases, const std::string& id) {
  for (const SuiteCase& c : cases)
    if (c.id == id) return c.stream;
  throw Error(ErrorKind::kStructure, "", kNoPlane, kNoOffset, "suite: no case " + id);
}

}  // namespace m4mesh::suite3d
