#include "encoder/mesh3d/container_encoder.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "codecs3d/registry.h"
#include "common/error.h"
#include "encoder/mesh3d/base_mesh.h"
#include "encoder/mesh3d/codec_encoders.h"
#include "mesh3d/frame_hash.h"

namespace m4mesh {

namespace {

Error encode_error(const std::string& message) { return Error(ErrorKind::kInput, "", kNoPlane, kNoOffset, message); }

class ContainerSink final : public UnitSink {
 public:
  ContainerSink(ContainerWriter& container, const Encode3dOptions& options, Encode3dResult& result, uint32_t frame_count)
      : container_(container), options_(options), result_(result), frame_count_(frame_count) {}

  void unit(UnitType type, uint32_t frame, const std::function<void(syntax::WriteIO&)>& write) override {
    if (options_.trace)
      options_.trace->begin_payload(static_cast<int64_t>(units_), "unit " + std::to_string(units_) + " frame " + std::to_string(frame), "mesh3d_unit_start_code",
                                    kMesh3dUnitStartCode);
    BitWriter writer;
    syntax::WriteIO io(writer, options_.trace);
    io.set_plane(frame);
    UnitHeader header{static_cast<uint32_t>(type), frame};
    syntax::describe(io, header);
    write(io);
    const size_t before = container_.size();
    container_.unit(writer.take_bytes());
    result_.unit_bytes[static_cast<uint32_t>(type)] += container_.size() - before;
    ++result_.unit_count[static_cast<uint32_t>(type)];
    ++units_;
  }

  void decoded(uint32_t frame, std::span<const Float3> positions) override {
    if (options_.keep_decoded) {
      std::vector<Vec3>& kept = result_.decoded.frames.at(frame);
      kept.resize(positions.size());
      for (size_t v = 0; v < positions.size(); ++v) kept[v] = {positions[v][0], positions[v][1], positions[v][2]};
    }
    if (!options_.hashes) return;
    const Digest digest = frame_digest(positions);
    if (options_.hash_group <= 1) {
      unit(UnitType::kFrameHash, frame, [&](syntax::WriteIO& io) {
        FrameHash hash{digest};
        syntax::describe(io, hash);
      });
      return;
    }
    // The frame's group, once every frame of it is decoded (again).
    pending_[frame] = digest;
    const uint32_t first = frame - frame % options_.hash_group;
    const uint32_t count = std::min(options_.hash_group, frame_count_ - first);
    for (uint32_t f = first; f < first + count; ++f)
      if (!pending_.count(f)) return;
    std::vector<Digest> frames;
    for (uint32_t f = first; f < first + count; ++f) {
      frames.push_back(pending_[f]);
      pending_.erase(f);
    }
    const Digest group = group_digest(frames);
    unit(UnitType::kGroupHash, first, [&](syntax::WriteIO& io) {
      GroupHash hash{count, group};
      syntax::describe(io, hash);
    });
  }

  void progress(size_t done, size_t total) override {
    if (options_.progress) options_.progress(done, total);
  }

  uint64_t stream_bytes() const override { return container_.size(); }

 private:
  ContainerWriter& container_;
  const Encode3dOptions& options_;
  Encode3dResult& result_;
  uint32_t frame_count_;
  uint64_t units_ = 0;
  std::map<uint32_t, Digest> pending_;  // digests of decoded frames whose group is not complete
};

}  // namespace

void check_sequence(const MeshSequence& input) {
  if (input.frames.empty() || input.vertex_count < 3 || input.faces.empty()) throw encode_error("a sequence needs frames, vertices and faces");
  if (input.vertex_count > kMaxVertices3d || input.faces.size() > kMaxFaces3d) throw encode_error("the mesh exceeds the container's limits");
  for (size_t f = 0; f < input.frames.size(); ++f) {
    const std::vector<Vec3>& frame = input.frames[f];
    if (frame.size() != input.vertex_count)
      throw encode_error("frame " + std::to_string(f) + " has " + std::to_string(frame.size()) + " vertices, not " + std::to_string(input.vertex_count));
    for (size_t v = 0; v < frame.size(); ++v)
      if (!std::isfinite(frame[v].x) || !std::isfinite(frame[v].y) || !std::isfinite(frame[v].z))
        throw encode_error("frame " + std::to_string(f) + ", vertex " + std::to_string(v) + ": a position that is not a finite number (" +
                           std::to_string(frame[v].x) + ", " + std::to_string(frame[v].y) + ", " + std::to_string(frame[v].z) + ")");
  }
  for (size_t k = 0; k < input.faces.size(); ++k)
    for (NodeIndex v : input.faces[k].v)
      if (v >= input.vertex_count)
        throw encode_error("face " + std::to_string(k) + " names vertex " + std::to_string(v) + " of " + std::to_string(input.vertex_count));
}

Encode3dResult encode_mesh3d(const MeshSequence& input, const Encode3dOptions& options) {
  check_sequence(input);
  if (options.reorder && options.codec_options.count("reference"))
    throw usage_error("--reorder and --reference: the rest shape's vertices would keep the input's numbers");
  const BaseMeshPlan plan = plan_base_mesh(input.faces, input.vertex_count, options.reorder);
  const MeshSequence s = in_coding_order(input, plan, options.reorder);
  const Codec3d& codec = codec3d_by_name(options.codec);
  const CodecEncoding& encoding = codec_encoding(codec);
  const BaseMeshCoding base_mesh = BaseMeshCoding::of(options.version, options.position_blend);
  const CodecSettings settings(codec.name, encoding.options, options.codec_options, base_mesh, options.threads);
  std::unique_ptr<CodecEncoder3d> encoder = encoding.make_encoder(s, settings);

  ContainerWriter container;
  Encode3dResult result;
  if (options.reorder) result.input_of = plan.input_of;
  {
    if (options.trace) options.trace->begin_payload(-1, "object", "mesh3d_object_start_code", kMesh3dObjectStartCode);
    BitWriter writer;
    syntax::WriteIO io(writer, options.trace);
    ObjectHeader header{base_mesh.version, codec.id, s.vertex_count, static_cast<uint32_t>(s.faces.size()), static_cast<uint32_t>(s.frames.size()),
                        options.frame_rate_num, options.frame_rate_den};
    syntax::describe(io, header);
    encoder->write_header(io);
    container.object(writer.take_bytes());
  }
  if (options.keep_decoded) result.decoded = {s.vertex_count, s.faces, std::vector<std::vector<Vec3>>(s.frames.size())};
  ContainerSink sink(container, options, result, static_cast<uint32_t>(s.frames.size()));
  encoder->encode(s, sink);
  if (options.trace) options.trace->begin_payload(Trace::kEndPart, "end", "mesh_object_end_code", kMeshObjectEndCode);
  result.stream = container.finish();
  result.other_bytes = result.stream.size();
  for (uint64_t bytes : result.unit_bytes) result.other_bytes -= bytes;
  result.statistics = encoder->statistics();
  return result;
}

}  // namespace m4mesh
