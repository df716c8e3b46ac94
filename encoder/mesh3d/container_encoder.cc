#include "encoder/mesh3d/container_encoder.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <optional>

#include "codecs3d/registry.h"
#include "common/error.h"
#include "encoder/mesh3d/base_mesh.h"
#include "encoder/mesh3d/codec_encoders.h"
#include "mesh3d/frame_hash.h"
#include "mesh3d/metrics.h"

namespace m4mesh {

namespace {

class ContainerSink final : public UnitSink {
 public:
  ContainerSink(ContainerWriter& container, const Encode3dOptions& options, Encode3dResult& result, const FrameSource& frames)
      : container_(container), options_(options), result_(result), frame_count_(frames.frame_count()) {
    if (options.measure) meter_.emplace(frames);
  }

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
    decoded_end_ = std::max(decoded_end_, frame + 1);
    if (options_.keep_decoded) {
      std::vector<Vec3>& kept = result_.decoded.frames.at(frame);
      kept.resize(positions.size());
      for (size_t v = 0; v < positions.size(); ++v) kept[v] = {positions[v][0], positions[v][1], positions[v][2]};
    }
    if (meter_) meter_->add(frame, positions);
    if (!options_.hashes) return;
    const Digest digest = frame_digest(positions);
    if (options_.hash_group <= 1) {
      unit(UnitType::kFrameHash, frame, [&](syntax::WriteIO& io) {
        FrameHash hash{digest};
        syntax::describe(io, hash);
      });
      return;
    }
    // The frame's group (groups count from the segment's first frame), once every frame of it is decoded.
    pending_[frame] = digest;
    const uint32_t first = frame - (frame - group_origin_) % options_.hash_group;
    const uint32_t count = std::min(options_.hash_group, frame_count_ - first);
    for (uint32_t f = first; f < first + count; ++f)
      if (!pending_.count(f)) return;
    group_hash(first, count);
  }

  void end_segment() override {
    while (!pending_.empty()) {
      const uint32_t first = pending_.begin()->first;
      uint32_t count = 0;
      while (count < options_.hash_group && pending_.count(first + count)) ++count;
      group_hash(first, count);
    }
    group_origin_ = decoded_end_;
  }

  void progress(size_t done, size_t total) override {
    if (options_.progress) options_.progress(done, total);
  }

  uint64_t stream_bytes() const override { return container_.size(); }

  // With measure: the decoder's output's figures, once every frame is decoded.
  void measured(Encode3dResult& result) const {
    if (!meter_) return;
    result.kg = meter_->kg();
    result.psnr = meter_->psnr();
    result.max_error = meter_->max_error();
  }

 private:
  ContainerWriter& container_;
  const Encode3dOptions& options_;
  Encode3dResult& result_;
  uint32_t frame_count_;
  uint64_t units_ = 0;
  // The group hash unit of frames first … first + count − 1, all pending.
  void group_hash(uint32_t first, uint32_t count) {
    std::vector<Digest> frames;
    for (uint32_t f = first; f < first + count; ++f) {
      frames.push_back(pending_.at(f));
      pending_.erase(f);
    }
    const Digest group = group_digest(frames);
    unit(UnitType::kGroupHash, first, [&](syntax::WriteIO& io) {
      GroupHash hash{count, group};
      syntax::describe(io, hash);
    });
  }

  std::map<uint32_t, Digest> pending_;  // digests of decoded frames whose group is not complete
  uint32_t group_origin_ = 0;           // the first frame of the segment: groups count from it
  uint32_t decoded_end_ = 0;            // one past the last frame decoded
  std::optional<QualityMeter> meter_;
};

}  // namespace

void check_sequence(const MeshSequence& input) { SequenceSource(input).scan(); }

Encode3dResult encode_mesh3d(const FrameSource& input, const Encode3dOptions& options) {
  input.scan();
  if (options.reorder && options.codec_options.count("reference"))
    throw usage_error("--reorder and --reference: the rest shape's vertices would keep the input's numbers");
  BaseMeshPlan plan = plan_base_mesh(input.faces(), input.vertex_count(), options.reorder);
  const RenumberedSource s(input, options.reorder ? plan.input_of : std::vector<uint32_t>{}, std::move(plan.faces));
  const Codec3d& codec = codec3d_by_name(options.codec);
  const CodecEncoding& encoding = codec_encoding(codec);
  const BaseMeshCoding base_mesh{options.position_blend, options.reorder};
  CodecSettings settings(codec.name, encoding.options, options.codec_options, base_mesh, options.threads);
  // The codec's frames in coding order: the plan's, or with --reorder their own numbers.
  std::vector<uint32_t> coding_order = plan.input_of;
  if (options.reorder) std::iota(coding_order.begin(), coding_order.end(), 0u);
  settings.set_coding_order(coding_order);
  std::unique_ptr<CodecEncoder3d> encoder = encoding.make_encoder(s, settings);

  ContainerWriter container(options.output);
  Encode3dResult result;
  if (options.reorder) result.input_of = std::move(plan.input_of);
  {
    if (options.trace) options.trace->begin_payload(-1, "object", "mesh3d_object_start_code", kMesh3dObjectStartCode);
    BitWriter writer;
    syntax::WriteIO io(writer, options.trace);
    ObjectHeader header{kFormatVersion,          codec.id, s.vertex_count(), static_cast<uint32_t>(s.faces().size()), s.frame_count(),
                        options.frame_rate_num, options.frame_rate_den};
    syntax::describe(io, header);
    encoder->write_header(io);
    container.object(writer.take_bytes());
  }
  if (options.keep_decoded)
    result.decoded = {s.vertex_count(), {s.faces().begin(), s.faces().end()}, std::vector<std::vector<Vec3>>(s.frame_count())};
  ContainerSink sink(container, options, result, s);
  encoder->encode(s, sink);
  sink.measured(result);
  if (options.trace) options.trace->begin_payload(Trace::kEndPart, "end", "mesh_object_end_code", kMeshObjectEndCode);
  result.stream = container.finish();
  result.stream_bytes = container.size();
  result.other_bytes = result.stream_bytes;
  for (uint64_t bytes : result.unit_bytes) result.other_bytes -= bytes;
  result.statistics = encoder->statistics();
  return result;
}

Encode3dResult encode_mesh3d(const MeshSequence& sequence, const Encode3dOptions& options) {
  return encode_mesh3d(SequenceSource(sequence), options);
}

}  // namespace m4mesh
