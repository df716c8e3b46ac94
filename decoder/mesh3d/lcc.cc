// The cloth codec in local cylindrical coordinates (codec_id 3) decoding
// (docs/codec_lcc.md): the reference mesh from the base mesh, then every
// frame from its symbols, vertex after vertex along the coding order, in
// binary64 with IEEE operations only.
#include <optional>

#include "codecs3d/codec_decoder.h"
#include "mesh3d/lcc.h"
#include "mesh3d/quantization.h"
#include "syntax/mesh3d/entropy_io.h"
#include "syntax/mesh3d/lcc.h"

namespace m4mesh {

namespace {

class LccDecoder final : public CodecDecoder3d {
 public:
  LccDecoder(const ObjectHeader& object, const LccHeader& header) : object_(object), header_(header) {}

  void decode_unit(const UnitHeader& unit, syntax::ReadIO& io, std::vector<uint32_t>& decoded) override {
    if (unit.type() == UnitType::kBaseMesh) {
      if (model_) io.fail(ErrorKind::kStructure, "unit_type", "a second base mesh unit: the reference is sent once");
      start(read_base_mesh(io, object_));
      if (header_.reference == kLccReferenceIsFrame0) decoded.push_back(0);
      next_frame_ = header_.reference == kLccReferenceIsFrame0 ? 1 : 0;
      return;
    }
    if (!model_) io.fail(ErrorKind::kStructure, "unit_type", "a frame unit before the reference mesh was decoded");
    // The unit is the next frame even when it fails, so that a check carries on.
    const uint32_t expected = next_frame_++;
    decoded.push_back(expected);
    if (unit.frame_index != expected) {
      io.set_plane(expected);
      io.fail(ErrorKind::kStructure, "frame_index",
              "frame " + std::to_string(unit.frame_index) + " where frame " + std::to_string(expected) + " was expected");
    }
    LccFrameData data;
    syntax::describe(io, data);
    const uint8_t* payload = io.reader().data();
    const syntax::SectionPlace place{"bins", "raw", 8 * static_cast<uint64_t>(data.bins.data() - payload),
                                     8 * static_cast<uint64_t>(data.raw.data() - payload), io.plane()};
    if (header_.mode == kLccStreamMode) coder_.emplace();
    if (trace_) {
      syntax::EntropyReadIO<true> symbols(data.bins, data.raw, place, trace_);
      read_symbols(symbols);
    } else {
      syntax::EntropyReadIO<false> symbols(data.bins, data.raw, place);
      read_symbols(symbols);
    }
    reconstruct(io);
  }

  const std::vector<Triangle>& faces() const override { return faces_; }
  void frame(uint32_t, std::span<Float3> positions) const override {
    for (size_t i = 0; i < positions.size(); ++i)
      positions[i] = {static_cast<float>(positions_[i].x), static_cast<float>(positions_[i].y), static_cast<float>(positions_[i].z)};
  }

 private:
  void start(BaseMesh base) {
    faces_ = std::move(base.faces);
    reference_grid_ = std::move(base.positions);
    positions_.resize(reference_grid_.size());
    for (size_t i = 0; i < positions_.size(); ++i) positions_[i] = lcc_grid_position(header_, reference_grid_[i]);
    model_.emplace(faces_, positions_, static_cast<int>(header_.theta_bits), static_cast<int>(header_.rh_bits), header_.rh_range_value());
    previous_grid_ = reference_grid_;
    direct_.resize(3 * model_->order().direct.size());
    steps_.resize(3 * model_->order().steps.size());
    coder_.emplace();
  }

  template <class IO>
  void read_symbols(IO& io) {
    syntax::describe_symbols(io, *coder_, direct_, steps_, model_->theta_limit(), model_->rh_limit());
    io.finish("theta");
  }

  // Directly coded vertices from the reference (stream mode) or the
  // previous frame (download mode), then every step in order.
  void reconstruct(syntax::ReadIO& io) {
    const std::vector<NodeIndex>& direct = model_->order().direct;
    const std::vector<IntPoint3>& base = header_.mode == kLccStreamMode ? reference_grid_ : previous_grid_;
    for (size_t i = 0; i < direct.size(); ++i) {
      const NodeIndex v = direct[i];
      for (int axis = 0; axis < 3; ++axis) {
        const int64_t q = int64_t{base[v][axis]} + direct_[3 * i + static_cast<size_t>(axis)];
        if (q > kMaxQuantized || q < -kMaxQuantized)
          io.fail(ErrorKind::kOutOfRange, "direct_position", "vertex " + std::to_string(v) + " leaves ±2^26 grid steps");
        previous_grid_[v][axis] = static_cast<int32_t>(q);
      }
      positions_[v] = lcc_grid_position(header_, previous_grid_[v]);
    }
    for (size_t k = 0; k < model_->order().steps.size(); ++k)
      positions_[model_->order().steps[k].d] = model_->place(k, positions_, steps_[3 * k], steps_[3 * k + 1], steps_[3 * k + 2]);
  }

  ObjectHeader object_;
  LccHeader header_;
  std::vector<Triangle> faces_;
  std::optional<LccModel> model_;
  std::vector<IntPoint3> reference_grid_, previous_grid_;
  std::vector<Vec3> positions_;
  std::vector<int32_t> direct_, steps_;
  std::optional<syntax::ResidualCoder<syntax::kLccChannels>> coder_;
  uint32_t next_frame_ = 0;
};

}  // namespace

std::unique_ptr<CodecDecoder3d> make_lcc_decoder(const ObjectHeader& object, syntax::ReadIO& io) {
  LccHeader header;
  syntax::describe(io, header);
  return std::make_unique<LccDecoder>(object, header);
}

}  // namespace m4mesh
