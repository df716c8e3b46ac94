#include "encoder/mesh3d_encoder.h"

#include <bit>

#include "common/error.h"
#include "mesh3d/quantization.h"
#include "mesh3d/traversal3d.h"
#include "syntax/bfs3d.h"

namespace m4mesh {

namespace {

Error encode_error(const std::string& message) { return Error(ErrorKind::kInput, "", kNoPlane, kNoOffset, message); }

std::vector<uint8_t> unit_payload(UnitType type, uint32_t frame, std::span<const uint8_t> data) {
  BitWriter writer;
  syntax::WriteIO io(writer);
  UnitHeader header{static_cast<uint32_t>(type), frame};
  syntax::describe(io, header);
  std::vector<uint8_t> payload = writer.take_bytes();
  payload.insert(payload.end(), data.begin(), data.end());
  return payload;
}

// arithmetic_bytes u(32) × 3, the three bin streams, the raw bits.
std::vector<uint8_t> frame_data(std::array<ArithmeticEncoder, 3>& coders, BitWriter& raw) {
  std::array<std::vector<uint8_t>, 3> bins;
  BitWriter lengths;
  for (int axis = 0; axis < 3; ++axis) {
    bins[axis] = coders[axis].finish();
    lengths.write(static_cast<uint32_t>(bins[axis].size()), 32);
  }
  std::vector<uint8_t> data = lengths.take_bytes();
  for (const std::vector<uint8_t>& b : bins) data.insert(data.end(), b.begin(), b.end());
  raw.write(0, static_cast<int>((8 - raw.position() % 8) % 8));
  const std::vector<uint8_t> bits = raw.take_bytes();
  data.insert(data.end(), bits.begin(), bits.end());
  return data;
}

std::vector<uint8_t> hash_payload(uint32_t frame, std::span<const Float3> positions) {
  const std::string hex = frame_md5(positions);
  std::vector<uint8_t> digest;
  for (size_t i = 0; i < 32; i += 2) digest.push_back(static_cast<uint8_t>(std::stoul(hex.substr(i, 2), nullptr, 16)));
  return unit_payload(UnitType::kFrameHash, frame, digest);
}

}  // namespace

Encode3dResult encode_mesh3d(const MeshSequence& s, const Encode3dOptions& options) {
  if (options.codec_id != kCodecBfs3d)
    throw Error(ErrorKind::kUsage, "", kNoPlane, kNoOffset, "codec_id " + std::to_string(options.codec_id) + " is not implemented yet");
  if (s.frames.empty() || s.vertex_count < 3 || s.faces.empty()) throw encode_error("a sequence needs frames, vertices and faces");
  if (s.vertex_count > kMaxVertices3d || s.faces.size() > kMaxFaces3d) throw encode_error("the mesh exceeds the container's limits");
  if (options.bits < 4 || options.bits > 24) throw Error(ErrorKind::kUsage, "", kNoPlane, kNoOffset, "bits must be 4 … 24");

  // The grid, rounded to binary32 as the header carries it, and every frame on it.
  const Grid grid = Grid::over(s.frames[0], options.bits);
  Bfs3dHeader codec;
  codec.bits = static_cast<uint32_t>(options.bits);
  codec.prediction = options.parallelogram ? kPredictParallelogram : kPredictAverage;
  for (int axis = 0; axis < 3; ++axis) {
    codec.origin[axis] = std::bit_cast<uint32_t>(grid.origin[axis]);
    codec.step[axis] = std::bit_cast<uint32_t>(grid.step[axis]);
  }
  const size_t V = s.vertex_count;
  std::vector<IntPoint3> previous(V), current(V);
  auto quantize_frame = [&](size_t f, std::vector<IntPoint3>& q) {
    for (size_t i = 0; i < V; ++i)
      if (!grid.quantize(s.frames[f][i], q[i]))
        throw encode_error("frame " + std::to_string(f) + ", vertex " + std::to_string(i) +
                           " lies too far outside the first frame's box for the quantization grid");
  };
  auto dequantize = [&](const std::vector<IntPoint3>& q) {
    std::vector<Float3> p(V);
    for (size_t i = 0; i < V; ++i)
      for (int axis = 0; axis < 3; ++axis) p[i][axis] = grid.position(axis, q[i][axis]);
    return p;
  };

  ContainerWriter container;
  {
    BitWriter writer;
    syntax::WriteIO io(writer);
    ObjectHeader header{1, kCodecBfs3d, static_cast<uint32_t>(V), static_cast<uint32_t>(s.faces.size()),
                        static_cast<uint32_t>(s.frames.size()), options.frame_rate_num, options.frame_rate_den};
    syntax::describe(io, header);
    syntax::describe(io, codec);
    container.object(writer.take_bytes());
  }
  Encode3dResult result;
  auto add_unit = [&](const std::vector<uint8_t>& payload, uint64_t& counter) {
    const size_t before = container.size();
    container.unit(payload);
    counter += container.size() - before;
  };

  quantize_frame(0, previous);
  add_unit(unit_payload(UnitType::kBaseMesh, 0, encode_base_mesh(s.faces, previous)), result.base_bytes);
  if (options.hashes) add_unit(hash_payload(0, dequantize(previous)), result.other_bytes);

  // Closed loop: each frame's motion is taken from the decoded previous
  // frame, which the lossless residuals make equal to the quantized one.
  const MotionOrder3d order = bfs3d_order(s.faces, V);
  std::vector<std::array<int64_t, 3>> motion(V + 1, {0, 0, 0});
  for (size_t f = 1; f < s.frames.size(); ++f) {
    quantize_frame(f, current);
    std::array<ArithmeticEncoder, 3> coders;
    BitWriter raw;
    ResidualModel model;
    for (size_t k = 0; k < order.node.size(); ++k) {
      const NodeIndex n = order.node[k];
      const auto &a = motion[order.pred_a[k]], &b = motion[order.pred_b[k]], &c = motion[order.pred_c[k]];
      const bool parallelogram = options.parallelogram && order.pred_c[k] != order.zero_slot;
      for (int axis = 0; axis < 3; ++axis) {
        const int64_t v = int64_t{current[n][axis]} - previous[n][axis];
        const int64_t w = parallelogram ? a[axis] + b[axis] - c[axis] : (a[axis] + b[axis] + 1) >> 1;
        model.encode(coders[axis], raw, axis, static_cast<int32_t>(v - w));
        motion[n][axis] = v;
      }
    }
    add_unit(unit_payload(UnitType::kFrame, static_cast<uint32_t>(f), frame_data(coders, raw)), result.frame_bytes);
    if (options.hashes) add_unit(hash_payload(static_cast<uint32_t>(f), dequantize(current)), result.other_bytes);
    std::swap(previous, current);
    if (options.progress) options.progress(f + 1, s.frames.size());
  }
  result.stream = container.finish();
  result.other_bytes = result.stream.size() - result.base_bytes - result.frame_bytes;
  return result;
}

}  // namespace m4mesh
