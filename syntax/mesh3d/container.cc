#include "syntax/mesh3d/container.h"

#include "bitstream/emulation.h"
#include "bitstream/start_codes.h"

namespace m4mesh {

const char* unit_type_name(UnitType type) {
  static const char* const kNames[kUnitTypes] = {"base mesh", "frame", "refinement", "frame hash", "group hash"};
  return static_cast<uint32_t>(type) < kUnitTypes ? kNames[static_cast<uint32_t>(type)] : "unknown";
}

namespace {

// Byte offset of the next 0x000001 prefix at or after `from`, or size.
size_t next_prefix(std::span<const uint8_t> s, size_t from) {
  for (size_t i = from; i + 2 < s.size(); ++i)
    if (s[i] == 0 && s[i + 1] == 0 && s[i + 2] == 1) return i;
  return s.size();
}

Error container_error(ErrorKind kind, const char* element, uint64_t byte, const std::string& message) {
  return Error(kind, element, kNoPlane, static_cast<int64_t>(byte * 8), message);
}

}  // namespace

bool is_mesh3d_stream(std::span<const uint8_t> s) {
  return s.size() >= 4 && s[0] == 0 && s[1] == 0 && s[2] == 1 && s[3] == (kMesh3dObjectStartCode & 0xFF);
}

ContainerParts split_container(std::span<const uint8_t> s) {
  if (s.size() < 4) throw container_error(ErrorKind::kTruncated, "mesh3d_object_start_code", 0, "the data ends inside this element");
  if (!is_mesh3d_stream(s)) throw container_error(ErrorKind::kMissingStartCode, "mesh3d_object_start_code", 0, "not a mesh3d container");
  ContainerParts parts;
  size_t at = 0;
  bool first = true;
  while (at < s.size()) {
    if (at + 4 > s.size()) throw container_error(ErrorKind::kTruncated, "start code", at, "the data ends inside a start code");
    const uint32_t code = uint32_t{s[at]} << 24 | uint32_t{s[at + 1]} << 16 | uint32_t{s[at + 2]} << 8 | s[at + 3];
    if (code == kMeshObjectEndCode) {
      if (first) throw container_error(ErrorKind::kStructure, "mesh_object_end_code", at, "no object header");
      parts.has_end_code = true;
      if (at + 4 != s.size())
        throw container_error(ErrorKind::kTrailingData, "mesh_object_end_code", at + 4,
                              std::to_string(s.size() - at - 4) + " bytes after the end code");
      break;
    }
    const bool object = code == kMesh3dObjectStartCode;
    if (object != first || (!object && code != kMesh3dUnitStartCode))
      throw container_error(ErrorKind::kMissingStartCode, first ? "mesh3d_object_start_code" : "mesh3d_unit_start_code", at,
                            "unexpected start code");
    const size_t end = next_prefix(s, at + 4);
    std::vector<uint8_t> payload = unescape_payload(s.subspan(at + 4, end - at - 4));
    if (object)
      parts.object_payload = std::move(payload);
    else
      parts.units.push_back({code, at, std::move(payload)});
    first = false;
    at = end;
  }
  return parts;
}

void ContainerWriter::start_code(uint32_t code) {
  for (int shift = 24; shift >= 0; shift -= 8) bytes_.push_back(static_cast<uint8_t>(code >> shift));
}

void ContainerWriter::object(std::span<const uint8_t> payload) {
  start_code(kMesh3dObjectStartCode);
  const std::vector<uint8_t> escaped = escape_payload(payload);
  bytes_.insert(bytes_.end(), escaped.begin(), escaped.end());
}

ContainerPrefix container_prefix(const ContainerParts& parts, uint64_t stream_size, uint64_t max_bytes) {
  if (stream_size <= max_bytes) return {stream_size, parts.units.size()};
  ContainerPrefix prefix;
  for (size_t k = 0; k < parts.units.size(); ++k) {
    const uint64_t end = k + 1 < parts.units.size() ? parts.units[k + 1].byte_offset : stream_size - (parts.has_end_code ? 4 : 0);
    if (end > max_bytes) break;
    prefix = {end, k + 1};
  }
  return prefix;
}

size_t whole_payloads_size(std::span<const uint8_t> received) {
  for (size_t at = received.size() < 3 ? 0 : received.size() - 3; at > 0; --at)
    if (received[at] == 0 && received[at + 1] == 0 && received[at + 2] == 1) return at;
  return 0;
}

uint64_t ContainerWriter::unit_size(std::span<const uint8_t> payload) { return 4 + escape_payload(payload).size(); }

void ContainerWriter::unit(std::span<const uint8_t> payload) {
  start_code(kMesh3dUnitStartCode);
  const std::vector<uint8_t> escaped = escape_payload(payload);
  bytes_.insert(bytes_.end(), escaped.begin(), escaped.end());
}

std::vector<uint8_t> ContainerWriter::finish(bool with_end_code) {
  if (with_end_code) start_code(kMeshObjectEndCode);
  return std::move(bytes_);
}

}  // namespace m4mesh
