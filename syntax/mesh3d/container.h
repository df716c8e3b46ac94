// The 3D container of §12 (docs/container3d.md): an object with its header,
// units with theirs, each payload between start codes with emulation
// prevention. Headers are described once and read and written through the
// I/O policies of syntax/io.h.
#pragma once

#include <cstdint>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "syntax/io.h"

namespace m4mesh {

enum class UnitType : uint32_t { kBaseMesh = 0, kFrame = 1, kRefinement = 2, kFrameHash = 3, kGroupHash = 4 };
inline constexpr uint32_t kUnitTypes = 5;
// Hash units: checked by the container, never handed to a codec.
inline bool is_hash_unit(UnitType type) { return type == UnitType::kFrameHash || type == UnitType::kGroupHash; }
const char* unit_type_name(UnitType type);

// The object header's `version`: the format's major version in the high
// four bits, its minor in the low four. 0x10 is format 1.0, the one this
// decoder reads (docs/container3d.md, "Compatibility").
inline constexpr uint32_t kFormatVersion = 0x10;

struct ObjectHeader {
  uint32_t version = kFormatVersion;
  uint32_t codec_id = 0;
  uint32_t vertex_count = 0;
  uint32_t face_count = 0;
  uint32_t frame_count = 0;  // 0: unknown (streaming)
  uint32_t frame_rate_num = 25;
  uint32_t frame_rate_den = 1;
};

struct UnitHeader {
  uint32_t unit_type = 0;
  uint32_t frame_index = 0;

  UnitType type() const { return static_cast<UnitType>(unit_type); }
};

// A frame hash unit's data: the MD5 of the decoded frame's canonical bytes.
struct FrameHash {
  std::span<const uint8_t> md5;
};
inline constexpr uint64_t kFrameMd5Bytes = 16;

// A frame group hash unit's data: the MD5 of the per-frame MD5 digests of
// frames frame_index … frame_index + group_frames − 1, concatenated in
// display order.
struct GroupHash {
  uint32_t group_frames = 1;
  std::span<const uint8_t> md5;
};

// Limits m4mesh enforces before allocating (docs/container3d.md).
inline constexpr uint32_t kMaxVertices3d = 1u << 24;
inline constexpr uint32_t kMaxFaces3d = 1u << 25;

namespace syntax {

template <class IO>
void describe(IO& io, ObjectHeader& h) {
  io.field("version", 8, h.version);
  io.require(h.version == kFormatVersion, ErrorKind::kReservedValue, "version", "this decoder reads format 1.0 (version 16) only");
  io.field("codec_id", 8, h.codec_id);  // checked against the registry (codecs3d/registry.h)
  io.field_in("vertex_count", 32, h.vertex_count, 3, kMaxVertices3d);
  io.field_in("face_count", 32, h.face_count, 1, kMaxFaces3d);
  io.field("frame_count", 32, h.frame_count);
  io.field_in("frame_rate_num", 16, h.frame_rate_num, 1, 65535);
  io.field_in("frame_rate_den", 16, h.frame_rate_den, 1, 65535);
}

template <class IO>
void describe(IO& io, UnitHeader& h) {
  io.field_in("unit_type", 8, h.unit_type, 0, kUnitTypes - 1);
  io.field("frame_index", 32, h.frame_index);
}

template <class IO>
void describe(IO& io, FrameHash& h) {
  io.require_remaining_bytes("frame_md5", kFrameMd5Bytes, "frame_index");
  io.section("frame_md5", kFrameMd5Bytes, h.md5);
}

template <class IO>
void describe(IO& io, GroupHash& h) {
  io.field_in("group_frames", 16, h.group_frames, 1, 65535);
  io.require_remaining_bytes("group_md5", kFrameMd5Bytes);
  io.section("group_md5", kFrameMd5Bytes, h.md5);
}

// The bit offset of the unit's data after its start code and header.
inline uint64_t unit_data_offset() {
  CountIO count;
  UnitHeader header;
  describe(count, header);
  return 32 + count.bits();
}
// The bit offset of a unit header's element after the unit's start code.
inline uint64_t unit_header_offset(const char* element) {
  CountIO count(element);
  UnitHeader header;
  describe(count, header);
  return 32 + count.offset_of_watched();
}

}  // namespace syntax

// One payload of a container with where it starts (byte offset of its start code).
struct ContainerUnit {
  uint32_t start_code;
  uint64_t byte_offset;
  std::vector<uint8_t> payload;  // unescaped
};

// Splits a container into the object payload and the unit payloads; checks
// the start codes, the end code (a missing one is a warning) and trailing
// data. Errors name the element and the bit offset.
struct ContainerParts {
  std::vector<uint8_t> object_payload;
  std::vector<ContainerUnit> units;
  bool has_end_code = false;
};
ContainerParts split_container(std::span<const uint8_t> stream);

// A container's payloads as a decoder takes them, read from its bytes in
// memory or from a file: one pass checks the framing (split_container's
// errors, in its order) and finds the units; a unit's payload is read and
// unescaped when asked for, and kept until dropped, so that a decoder
// holds the units it works on, not the stream.
class ContainerSource {
 public:
  // The bytes must outlive the source.
  explicit ContainerSource(std::span<const uint8_t> stream);
  static ContainerSource open_file(const std::string& path);

  const std::vector<uint8_t>& object_payload() const { return object_payload_; }
  size_t units() const { return offsets_.size(); }
  uint64_t unit_offset(size_t index) const { return offsets_.at(index); }
  bool has_end_code() const { return has_end_code_; }
  // The stream's size in bytes.
  uint64_t size() const { return size_; }
  const std::vector<uint8_t>& payload(size_t index) const;
  // Drops the payloads read before unit `index`.
  void drop_before(size_t index) const;
  // A stream in memory still arriving: `window` holds its bytes from
  // `window_start` (no unit before it is read any more) to all received so
  // far, cut where a start code begins (whole_payloads_size) or at the
  // stream's end. The units of the new bytes join.
  void extend(std::span<const uint8_t> window, uint64_t window_start);

 private:
  ContainerSource() = default;
  // Bytes first … first + count − 1 of the stream.
  std::vector<uint8_t> read(uint64_t first, uint64_t count) const;

  std::span<const uint8_t> memory_;
  uint64_t memory_start_ = 0;  // the stream offset of memory_[0]
  std::shared_ptr<std::ifstream> file_;
  uint64_t size_ = 0;
  std::vector<uint8_t> object_payload_;
  std::vector<uint64_t> offsets_;  // each unit's start code
  uint64_t units_end_ = 0;         // the end code's offset, or the stream's end
  bool has_end_code_ = false;
  mutable std::map<size_t, std::vector<uint8_t>> payloads_;
};

// The longest prefix of a container of at most `max_bytes` bytes that ends
// at a unit boundary (where a unit's start code or the end code begins; the
// whole stream when it fits), and the units it holds: 0 when not even the
// first unit fits.
struct ContainerPrefix {
  uint64_t bytes = 0;
  size_t units = 0;
};
ContainerPrefix container_prefix(const ContainerParts& parts, uint64_t stream_size, uint64_t max_bytes);

// Of a container still arriving, the bytes that hold only whole payloads:
// up to the last start code received (0 before the second start code).
size_t whole_payloads_size(std::span<const uint8_t> received);

// Assembles a container from payloads (escaped here): in memory, or handed
// to `output` payload by payload as they come.
class ContainerWriter {
 public:
  using Output = std::function<void(std::span<const uint8_t>)>;
  ContainerWriter() = default;
  explicit ContainerWriter(Output output) : output_(std::move(output)) {}

  void object(std::span<const uint8_t> payload);
  void unit(std::span<const uint8_t> payload);
  // The stream in memory (empty with an output); nothing is written after it.
  std::vector<uint8_t> finish(bool with_end_code = true);
  // The stream's bytes so far.
  uint64_t size() const { return written_ + bytes_.size(); }
  // The bytes a unit of this payload takes: its start code and the escaped payload.
  static uint64_t unit_size(std::span<const uint8_t> payload);

 private:
  void start_code(uint32_t code);
  void flush();
  Output output_;
  std::vector<uint8_t> bytes_;
  uint64_t written_ = 0;  // handed to the output
};

// A stream's object header and codec header, read from its object payload
// (the codec header's sections point into `parts`).
template <class CodecHeader>
std::pair<ObjectHeader, CodecHeader> read_headers(const ContainerParts& parts) {
  BitReader reader(parts.object_payload.data(), parts.object_payload.size());
  syntax::ReadIO in(reader);
  std::pair<ObjectHeader, CodecHeader> headers;
  // Unqualified: the codec header's describe() is found where this is used.
  using syntax::describe;
  describe(in, headers.first);
  describe(in, headers.second);
  return headers;
}

// Whether a stream starts with mesh3d_object_start_code.
bool is_mesh3d_stream(std::span<const uint8_t> stream);

}  // namespace m4mesh
