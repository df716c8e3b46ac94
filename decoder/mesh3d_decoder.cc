#include "decoder/mesh3d_decoder.h"

#include "bitstream/bit_reader.h"

namespace m4mesh {

namespace {

// The unit header and where the unit's data starts.
UnitHeader read_unit_header(const ContainerUnit& unit, int64_t frame, size_t& data_offset) {
  BitReader reader(unit.payload.data(), unit.payload.size());
  syntax::ReadIO io(reader);
  io.set_plane(frame);
  UnitHeader header;
  try {
    syntax::describe(io, header);
  } catch (const Error& e) {
    throw Error(e.kind(), e.element(), frame, static_cast<int64_t>(unit.byte_offset * 8 + 32) + e.bit_offset(), e.message());
  }
  data_offset = static_cast<size_t>(reader.position() / 8);
  return header;
}

}  // namespace

void frame_data_error(ErrorKind kind, const char* element, const std::string& message) {
  throw Error(kind, element, kNoPlane, kNoOffset, message);
}

Mesh3dDecoder::Mesh3dDecoder(std::span<const uint8_t> stream, bool verify)
    : parts_(split_container(stream)), verify_(verify) {
  BitReader reader(parts_.object_payload.data(), parts_.object_payload.size());
  syntax::ReadIO io(reader);
  try {
    syntax::describe(io, header_);
    if (header_.codec_id == kCodecBfs3d)
      codec_ = read_bfs3d_header(io);
    else if (header_.codec_id == kCodecAffineOctree)
      codec_ = read_affine_octree_header(io);
    else
      io.fail(ErrorKind::kLimit, "codec_id", "codec " + std::to_string(header_.codec_id) + " is registered but this decoder does not implement it yet");
  } catch (const Error& e) {
    throw Error(e.kind(), e.element(), kNoPlane, 32 + e.bit_offset(), e.message());
  }
}

void Mesh3dDecoder::fail(ErrorKind kind, const ContainerUnit& unit, uint32_t frame, const char* element, const std::string& message) const {
  throw Error(kind, element, frame, static_cast<int64_t>(unit.byte_offset * 8), message);
}

void Mesh3dDecoder::decode_base(const ContainerUnit& unit, uint32_t frame) {
  BaseMesh base;
  try {
    base = decode_base_mesh(std::span(unit.payload).subspan(kUnitHeaderBytes), header_.vertex_count, header_.face_count);
  } catch (const Error& e) {
    fail(ErrorKind::kInput, unit, frame, "base_mesh", e.message());
  }
  for (const IntPoint3& q : base.positions)
    for (int32_t c : q)
      if (c > kMaxQuantized || c < -kMaxQuantized) fail(ErrorKind::kOutOfRange, unit, frame, "base_mesh", "a position leaves ±2^26 grid steps");
  if (frame == 0) {
    faces_ = std::move(base.faces);
    codec_->start(faces_, header_.vertex_count);
  } else if (base.faces != faces_) {
    fail(ErrorKind::kStructure, unit, frame, "base_mesh", "an intra base mesh with other faces than frame 0's");
  }
  quantized_ = std::move(base.positions);
}

void Mesh3dDecoder::decode_frame(const ContainerUnit& unit, uint32_t frame) {
  try {
    codec_->decode_frame(std::span<const uint8_t>(unit.payload).subspan(kUnitHeaderBytes), quantized_);
  } catch (const Error& e) {
    // A codec's fixed fields carry their offset in the frame data; bins do not.
    const int64_t unit_start = static_cast<int64_t>(unit.byte_offset * 8);
    const int64_t at = e.bit_offset() == kNoOffset ? unit_start : unit_start + 32 + 8 * static_cast<int64_t>(kUnitHeaderBytes) + e.bit_offset();
    throw Error(e.kind(), e.element(), frame, at, e.message());
  }
}

void Mesh3dDecoder::check_hash() {
  hash_matches_.reset();
  if (next_unit_ >= parts_.units.size()) return;
  const ContainerUnit& unit = parts_.units[next_unit_];
  size_t offset = 0;
  const UnitHeader h = read_unit_header(unit, frame_index_, offset);
  if (h.unit_type != static_cast<uint32_t>(UnitType::kFrameHash)) return;
  ++next_unit_;
  if (h.frame_index != frame_index_) fail(ErrorKind::kStructure, unit, frame_index_, "frame_index", "a hash unit for another frame");
  if (unit.payload.size() != offset + 16) fail(ErrorKind::kOutOfRange, unit, frame_index_, "frame_md5", "a hash unit holds 16 bytes");
  if (!verify_) return;
  static const char kHex[] = "0123456789abcdef";
  std::string expected;
  for (size_t i = offset; i < offset + 16; ++i) {
    expected += kHex[unit.payload[i] >> 4];
    expected += kHex[unit.payload[i] & 15];
  }
  hash_matches_ = expected == frame_md5(positions_);
}

bool Mesh3dDecoder::next_frame() {
  if (next_unit_ >= parts_.units.size()) {
    if (!started_) throw Error(ErrorKind::kTruncated, "base_mesh", 0, kNoOffset, "the stream has no base mesh unit");
    if (header_.frame_count != 0 && frame_index_ + 1 != header_.frame_count)
      throw Error(ErrorKind::kTruncated, "mesh3d_unit_start_code", frame_index_ + 1, kNoOffset,
                  "the stream ends after frame " + std::to_string(frame_index_) + " of " + std::to_string(header_.frame_count));
    return false;
  }
  const ContainerUnit& unit = parts_.units[next_unit_++];
  const uint32_t frame = started_ ? frame_index_ + 1 : 0;
  size_t offset = 0;
  const UnitHeader h = read_unit_header(unit, frame, offset);
  if (!started_ && h.unit_type != static_cast<uint32_t>(UnitType::kBaseMesh))
    fail(ErrorKind::kStructure, unit, frame, "unit_type", "the first unit must be the base mesh of frame 0");
  if (h.unit_type != static_cast<uint32_t>(UnitType::kFrame) && h.unit_type != static_cast<uint32_t>(UnitType::kBaseMesh))
    fail(ErrorKind::kStructure, unit, frame, "unit_type", "expected a frame or base mesh unit, found unit_type " + std::to_string(h.unit_type));
  if (h.frame_index != frame)
    fail(ErrorKind::kStructure, unit, frame, "frame_index", "frame " + std::to_string(h.frame_index) + " where frame " +
                                                          std::to_string(frame) + " was expected");
  if (header_.frame_count != 0 && h.frame_index >= header_.frame_count)
    fail(ErrorKind::kStructure, unit, frame, "frame_index", "more frames than the object header's frame_count");
  if (h.unit_type == static_cast<uint32_t>(UnitType::kBaseMesh))
    decode_base(unit, frame);
  else
    decode_frame(unit, frame);
  started_ = true;
  frame_index_ = frame;
  positions_.resize(quantized_.size());
  const Grid grid = codec_->grid();  // a copy, which the stores below cannot alias
  for (size_t i = 0; i < quantized_.size(); ++i)
    for (int axis = 0; axis < 3; ++axis) positions_[i][axis] = grid.position(axis, quantized_[i][axis]);
  check_hash();
  return true;
}

MeshSequence decode_mesh3d(std::span<const uint8_t> stream) {
  Mesh3dDecoder decoder(stream, true);
  MeshSequence s;
  s.vertex_count = decoder.header().vertex_count;
  while (decoder.next_frame()) {
    if (decoder.hash_matches() == false)
      throw Error(ErrorKind::kStructure, "frame_md5", decoder.frame_index(), kNoOffset, "the decoded frame does not match its hash");
    std::vector<Vec3> frame;
    frame.reserve(decoder.positions().size());
    for (const Float3& p : decoder.positions()) frame.push_back({p[0], p[1], p[2]});
    s.frames.push_back(std::move(frame));
  }
  s.faces = decoder.faces();
  return s;
}

}  // namespace m4mesh
