#include "encoder/mesh3d_encoder.h"

#include "common/error.h"
#include "encoder/codec3d.h"
#include "syntax/affine_octree.h"

namespace m4mesh {

namespace {

Error encode_error(const std::string& message) { return Error(ErrorKind::kInput, "", kNoPlane, kNoOffset, message); }
Error usage_error(const std::string& message) { return Error(ErrorKind::kUsage, "", kNoPlane, kNoOffset, message); }

std::vector<uint8_t> unit_payload(UnitType type, uint32_t frame, std::span<const uint8_t> data) {
  BitWriter writer;
  syntax::WriteIO io(writer);
  UnitHeader header{static_cast<uint32_t>(type), frame};
  syntax::describe(io, header);
  std::vector<uint8_t> payload = writer.take_bytes();
  payload.insert(payload.end(), data.begin(), data.end());
  return payload;
}

std::vector<uint8_t> hash_payload(uint32_t frame, const Grid& grid, std::span<const IntPoint3> positions) {
  std::vector<Float3> decoded(positions.size());
  for (size_t i = 0; i < positions.size(); ++i)
    for (int axis = 0; axis < 3; ++axis) decoded[i][axis] = grid.position(axis, positions[i][axis]);
  const std::string hex = frame_md5(decoded);
  std::vector<uint8_t> digest;
  for (size_t i = 0; i < 32; i += 2) digest.push_back(static_cast<uint8_t>(std::stoul(hex.substr(i, 2), nullptr, 16)));
  return unit_payload(UnitType::kFrameHash, frame, digest);
}

void check_options(const Encode3dOptions& options) {
  if (options.bits < 4 || options.bits > 24) throw usage_error("bits must be 4 … 24");
  if (options.intra_period < 0) throw usage_error("the intra period must be 0 (none) or a frame count");
  if (options.codec_id == kCodecAffineOctree) {
    if (!(options.max_error > 0 && options.max_error <= 1)) throw usage_error("ME must lie in (0, 1] (a fraction of the root cube)");
    if (options.matrix_bits < 4 || options.matrix_bits > 24) throw usage_error("matrix bits must be 4 … 24");
    if (options.matrix_range_log2 < 1 || options.matrix_range_log2 > 8 || options.matrix_range_log2 >= options.matrix_bits)
      throw usage_error("the matrix range log2 must be 1 … 8 and below the matrix bits");
    if (options.max_depth < 1 || options.max_depth > static_cast<int>(kMaxOctreeDepth))
      throw usage_error("the octree depth must be 1 … " + std::to_string(kMaxOctreeDepth));
  }
}

}  // namespace

void quantize_frame(const Grid& grid, std::span<const Vec3> frame, size_t frame_index, std::vector<IntPoint3>& positions) {
  positions.resize(frame.size());
  for (size_t i = 0; i < frame.size(); ++i)
    if (!grid.quantize(frame[i], positions[i]))
      throw encode_error("frame " + std::to_string(frame_index) + ", vertex " + std::to_string(i) +
                         " lies too far outside the first frame's box for the quantization grid");
}

Encode3dResult encode_mesh3d(const MeshSequence& s, const Encode3dOptions& options) {
  if (s.frames.empty() || s.vertex_count < 3 || s.faces.empty()) throw encode_error("a sequence needs frames, vertices and faces");
  if (s.vertex_count > kMaxVertices3d || s.faces.size() > kMaxFaces3d) throw encode_error("the mesh exceeds the container's limits");
  check_options(options);
  std::unique_ptr<CodecEncoder3d> codec;
  if (options.codec_id == kCodecBfs3d)
    codec = make_bfs3d_encoder(s, options);
  else if (options.codec_id == kCodecAffineOctree)
    codec = make_affine_octree_encoder(s, options);
  else
    throw usage_error("codec_id " + std::to_string(options.codec_id) + " is not implemented yet");
  const Grid& grid = codec->grid();

  ContainerWriter container;
  {
    BitWriter writer;
    syntax::WriteIO io(writer);
    ObjectHeader header{1, options.codec_id, s.vertex_count, static_cast<uint32_t>(s.faces.size()),
                        static_cast<uint32_t>(s.frames.size()), options.frame_rate_num, options.frame_rate_den};
    syntax::describe(io, header);
    codec->write_header(io);
    container.object(writer.take_bytes());
  }
  Encode3dResult result;
  auto add_unit = [&](const std::vector<uint8_t>& payload, uint64_t& counter) {
    const size_t before = container.size();
    container.unit(payload);
    counter += container.size() - before;
  };

  // Frame 0 and every intra frame: a base mesh. Other frames: the codec,
  // closed loop on the decoded previous frame.
  std::vector<IntPoint3> positions;
  for (size_t f = 0; f < s.frames.size(); ++f) {
    const uint32_t frame = static_cast<uint32_t>(f);
    if (f == 0 || (options.intra_period > 0 && f % static_cast<size_t>(options.intra_period) == 0)) {
      quantize_frame(grid, s.frames[f], f, positions);
      add_unit(unit_payload(UnitType::kBaseMesh, frame, encode_base_mesh(s.faces, positions)), result.base_bytes);
    } else {
      add_unit(unit_payload(UnitType::kFrame, frame, codec->encode_frame(s.frames[f], f, positions, result)), result.frame_bytes);
    }
    if (options.hashes) add_unit(hash_payload(frame, grid, positions), result.other_bytes);
    if (options.progress) options.progress(f + 1, s.frames.size());
  }
  result.stream = container.finish();
  result.other_bytes = result.stream.size() - result.base_bytes - result.frame_bytes;
  return result;
}

}  // namespace m4mesh
