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

Mesh3dDecoder::Mesh3dDecoder(std::span<const uint8_t> stream, bool verify)
    : parts_(split_container(stream)), verify_(verify) {
  BitReader reader(parts_.object_payload.data(), parts_.object_payload.size());
  syntax::ReadIO io(reader);
  try {
    syntax::describe(io, header_);
    if (header_.codec_id != kCodecBfs3d)
      io.fail(ErrorKind::kLimit, "codec_id", "codec " + std::to_string(header_.codec_id) + " is registered but this decoder does not implement it yet");
    syntax::describe(io, codec_);
  } catch (const Error& e) {
    throw Error(e.kind(), e.element(), kNoPlane, 32 + e.bit_offset(), e.message());
  }
  for (int axis = 0; axis < 3; ++axis) {
    grid_.origin[axis] = codec_.origin_value(axis);
    grid_.step[axis] = codec_.step_value(axis);
  }
}

void Mesh3dDecoder::fail(ErrorKind kind, const ContainerUnit& unit, const char* element, const std::string& message) const {
  throw Error(kind, element, frame_index_, static_cast<int64_t>(unit.byte_offset * 8), message);
}

void Mesh3dDecoder::decode_base(const ContainerUnit& unit) {
  size_t offset = 0;
  const UnitHeader h = read_unit_header(unit, 0, offset);
  if (h.unit_type != static_cast<uint32_t>(UnitType::kBaseMesh) || h.frame_index != 0)
    fail(ErrorKind::kStructure, unit, "unit_type", "the first unit must be the base mesh of frame 0");
  BaseMesh base;
  try {
    base = decode_base_mesh(std::span(unit.payload).subspan(offset), header_.vertex_count, header_.face_count);
  } catch (const Error& e) {
    fail(ErrorKind::kInput, unit, "base_mesh", e.message());
  }
  faces_ = std::move(base.faces);
  quantized_ = std::move(base.positions);
  for (const IntPoint3& q : quantized_)
    for (int32_t c : q)
      if (c > kMaxQuantized || c < -kMaxQuantized) fail(ErrorKind::kOutOfRange, unit, "base_mesh", "a position leaves ±2^26 grid steps");
  order_ = bfs3d_order(faces_, header_.vertex_count);
  motion_.assign(header_.vertex_count + size_t{1}, {0, 0, 0});
}

void Mesh3dDecoder::decode_frame(const ContainerUnit& unit, uint32_t frame) {
  std::span<const uint8_t> data = std::span<const uint8_t>(unit.payload).subspan(kUnitHeaderBytes);
  if (data.size() < 3 * kArithmeticLengthBytes) fail(ErrorKind::kTruncated, unit, "arithmetic_bytes", "the frame's data ends early");
  std::array<uint32_t, 3> lengths;
  for (int axis = 0; axis < 3; ++axis) {
    const uint8_t* p = data.data() + axis * kArithmeticLengthBytes;
    lengths[axis] = uint32_t{p[0]} << 24 | uint32_t{p[1]} << 16 | uint32_t{p[2]} << 8 | p[3];
  }
  data = data.subspan(3 * kArithmeticLengthBytes);
  std::array<ArithmeticDecoder, 3> bins{ArithmeticDecoder({}), ArithmeticDecoder({}), ArithmeticDecoder({})};
  for (int axis = 0; axis < 3; ++axis) {
    if (lengths[axis] > data.size()) fail(ErrorKind::kOutOfRange, unit, "arithmetic_bytes", "longer than the frame's data");
    bins[axis] = ArithmeticDecoder(data.first(lengths[axis]));
    data = data.subspan(lengths[axis]);
  }
  BitReader raw(data.data(), data.size());
  ResidualModel model;
  const bool parallelogram = codec_.prediction == kPredictParallelogram;
  for (size_t k = 0; k < order_.node.size(); ++k) {
    const NodeIndex n = order_.node[k];
    const auto &a = motion_[order_.pred_a[k]], &b = motion_[order_.pred_b[k]], &c = motion_[order_.pred_c[k]];
    const bool use_parallelogram = parallelogram && order_.pred_c[k] != order_.zero_slot;
    for (int axis = 0; axis < 3; ++axis) {
      int32_t r;
      if (!model.decode(bins[axis], raw, axis, r)) fail(ErrorKind::kInvalidCode, unit, "motion_residual", "a residual longer than 32 bits");
      const int64_t w = use_parallelogram ? a[axis] + b[axis] - c[axis] : (a[axis] + b[axis] + 1) >> 1;
      const int64_t v = w + r;
      const int64_t q = quantized_[n][axis] + v;
      if (q > kMaxQuantized || q < -kMaxQuantized)
        fail(ErrorKind::kOutOfRange, unit, "motion_residual", "vertex " + std::to_string(n) + " leaves ±2^26 grid steps");
      motion_[n][axis] = v;
      quantized_[n][axis] = static_cast<int32_t>(q);
    }
  }
  if (bins[0].overrun() + bins[1].overrun() + bins[2].overrun() != 0 || raw.overrun()) fail(ErrorKind::kTruncated, unit, "motion_residual", "the frame's data ends early");
  frame_index_ = frame;
}

void Mesh3dDecoder::check_hash() {
  hash_matches_.reset();
  if (next_unit_ >= parts_.units.size()) return;
  const ContainerUnit& unit = parts_.units[next_unit_];
  size_t offset = 0;
  const UnitHeader h = read_unit_header(unit, frame_index_, offset);
  if (h.unit_type != static_cast<uint32_t>(UnitType::kFrameHash)) return;
  ++next_unit_;
  if (h.frame_index != frame_index_) fail(ErrorKind::kStructure, unit, "frame_index", "a hash unit for another frame");
  if (unit.payload.size() != offset + 16) fail(ErrorKind::kOutOfRange, unit, "frame_md5", "a hash unit holds 16 bytes");
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
  if (!started_) {
    decode_base(unit);
    started_ = true;
  } else {
    size_t offset = 0;
    const UnitHeader h = read_unit_header(unit, frame_index_ + 1, offset);
    if (h.unit_type != static_cast<uint32_t>(UnitType::kFrame))
      fail(ErrorKind::kStructure, unit, "unit_type", "expected a frame unit, found unit_type " + std::to_string(h.unit_type));
    if (h.frame_index != frame_index_ + 1)
      fail(ErrorKind::kStructure, unit, "frame_index", "frame " + std::to_string(h.frame_index) + " where frame " +
                                                            std::to_string(frame_index_ + 1) + " was expected");
    if (header_.frame_count != 0 && h.frame_index >= header_.frame_count)
      fail(ErrorKind::kStructure, unit, "frame_index", "more frames than the object header's frame_count");
    decode_frame(unit, h.frame_index);
  }
  positions_.resize(quantized_.size());
  for (size_t i = 0; i < quantized_.size(); ++i)
    for (int axis = 0; axis < 3; ++axis) positions_[i][axis] = grid_.position(axis, quantized_[i][axis]);
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
