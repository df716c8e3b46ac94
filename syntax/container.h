// The 3D container of §12 (docs/container3d.md): an object with its header,
// units with theirs, each payload between start codes with emulation
// prevention. Headers are described once and read and written through the
// I/O policies of syntax/io.h.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "syntax/io.h"

namespace m4mesh {

inline constexpr uint32_t kCodecBfs3d = 1;
inline constexpr uint32_t kCodecAffineOctree = 2;
inline constexpr uint32_t kCodecLcc = 3;
inline constexpr uint32_t kCodecCpcaWpt = 4;

enum class UnitType : uint32_t { kBaseMesh = 0, kFrame = 1, kRefinement = 2, kFrameHash = 3 };

struct ObjectHeader {
  uint32_t version = 1;
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
};

// unit_type u(8) and frame_index u(32).
inline constexpr size_t kUnitHeaderBytes = 5;

// Limits m4mesh enforces before allocating (docs/container3d.md).
inline constexpr uint32_t kMaxVertices3d = 1u << 24;
inline constexpr uint32_t kMaxFaces3d = 1u << 25;

namespace syntax {

template <class IO>
void describe(IO& io, ObjectHeader& h) {
  io.field("version", 8, h.version);
  io.require(h.version == 1, ErrorKind::kReservedValue, "version", "only version 1 is defined");
  io.field("codec_id", 8, h.codec_id);
  io.require(h.codec_id >= kCodecBfs3d && h.codec_id <= kCodecCpcaWpt, ErrorKind::kReservedValue, "codec_id",
             "unknown codec");
  io.field_in("vertex_count", 32, h.vertex_count, 3, kMaxVertices3d);
  io.field_in("face_count", 32, h.face_count, 1, kMaxFaces3d);
  io.field("frame_count", 32, h.frame_count);
  io.field_in("frame_rate_num", 16, h.frame_rate_num, 1, 65535);
  io.field_in("frame_rate_den", 16, h.frame_rate_den, 1, 65535);
}

template <class IO>
void describe(IO& io, UnitHeader& h) {
  io.field_in("unit_type", 8, h.unit_type, 0, 3);
  io.field("frame_index", 32, h.frame_index);
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

// Assembles a container from payloads (escaped here).
class ContainerWriter {
 public:
  void object(std::span<const uint8_t> payload);
  void unit(std::span<const uint8_t> payload);
  std::vector<uint8_t> finish(bool with_end_code = true);
  size_t size() const { return bytes_.size(); }

 private:
  void start_code(uint32_t code);
  std::vector<uint8_t> bytes_;
};

// Whether a stream starts with mesh3d_object_start_code.
bool is_mesh3d_stream(std::span<const uint8_t> stream);

}  // namespace m4mesh
