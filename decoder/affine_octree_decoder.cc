// Affine-Octree (codec_id 2) decoding (docs/codec_affine_octree.md): the
// octree of the previous frame's vertices, each leaf moved by its affine
// matrix or by its vertices' direct motion.
#include "bitstream/bit_reader.h"
#include "decoder/codec3d.h"
#include "mesh3d/octree.h"
#include "syntax/affine_octree.h"

namespace m4mesh {

namespace {

// The bins and raw bits of one frame, read through AffineCellCoder::describe.
class CellReader {
 public:
  CellReader(std::span<const uint8_t> bins, std::span<const uint8_t> raw) : bins_(bins), raw_(raw.data(), raw.size()) {}

  void bin(BinContext& context, bool& value, const char*) { value = bins_.decode(context) != 0; }
  void residual(ResidualCoder<kAffineChannels>& coder, int channel, int32_t& value, const char* element) {
    if (!coder.decode(bins_, raw_, channel, value)) fail(ErrorKind::kInvalidCode, element, "a residual longer than 32 bits");
  }
  [[noreturn]] void fail(ErrorKind kind, const char* element, const std::string& message) { frame_data_error(kind, element, message); }
  bool overrun() const { return bins_.overrun() != 0 || raw_.overrun(); }

 private:
  ArithmeticDecoder bins_;
  BitReader raw_;
};

class AffineOctreeDecoder final : public CodecDecoder3d {
 public:
  explicit AffineOctreeDecoder(const AffineOctreeHeader& header) : header_(header) {
    for (int axis = 0; axis < 3; ++axis) {
      grid_.origin[axis] = header.origin_value(axis);
      grid_.step[axis] = header.step_value();
    }
  }

  const Grid& grid() const override { return grid_; }
  void start(std::span<const Triangle>, uint32_t) override {}

  void decode_frame(std::span<const uint8_t> data, std::vector<IntPoint3>& positions) override {
    BitReader fields(data.data(), data.size());
    syntax::ReadIO io(fields);
    AffineFrameHeader frame;
    syntax::describe(io, frame);
    const uint32_t shift = frame.direct_shift;
    data = data.subspan(kAffineFrameHeaderBytes);
    if (frame.arithmetic_bytes > data.size()) io.fail(ErrorKind::kOutOfRange, "arithmetic_bytes", "longer than the frame's data");
    CellReader reader(data.first(frame.arithmetic_bytes), data.subspan(frame.arithmetic_bytes));
    AffineCellCoder coder(header_);
    const RootCube cube = root_cube(positions);
    const int fraction_bits = header_.fraction_bits();
    next_.resize(positions.size());  // every vertex lies in exactly one leaf, which sets it
    auto store = [&](uint32_t v, const std::array<int64_t, 3>& q) {
      for (int axis = 0; axis < 3; ++axis) {
        if (q[axis] > kMaxQuantized || q[axis] < -kMaxQuantized)
          frame_data_error(ErrorKind::kOutOfRange, cell_.direct ? "direct_motion" : "matrix_residual",
                           "vertex " + std::to_string(v) + " leaves ±2^26 grid steps");
        next_[v][axis] = static_cast<int32_t>(q[axis]);
      }
    };
    partition_.walk(positions, cube, [&](const OctreeCell& cell) {
      coder.describe(reader, cell.depth, cell.vertices.size(), cell_);
      if (cell_.split) return true;
      if (cell_.direct) {
        for (size_t k = 0; k < cell.vertices.size(); ++k) {
          const IntPoint3& p = positions[cell.vertices[k]];
          std::array<int64_t, 3> q;
          for (int axis = 0; axis < 3; ++axis) q[axis] = p[axis] + (int64_t{cell_.motion[k][axis]} << shift);
          store(cell.vertices[k], q);
        }
      } else {
        for (uint32_t v : cell.vertices) store(v, apply_affine(cell_.matrix, fraction_bits, cell.corner, cube.side, positions[v]));
      }
      return false;
    });
    if (reader.overrun()) frame_data_error(ErrorKind::kTruncated, "matrix_residual", "the frame's data ends early");
    positions.swap(next_);
  }

 private:
  AffineOctreeHeader header_;
  Grid grid_;
  OctreePartition partition_;
  AffineCell cell_;
  std::vector<IntPoint3> next_;
};

}  // namespace

std::unique_ptr<CodecDecoder3d> read_affine_octree_header(syntax::ReadIO& io) {
  AffineOctreeHeader header;
  syntax::describe(io, header);
  return std::make_unique<AffineOctreeDecoder>(header);
}

}  // namespace m4mesh
