// Affine-Octree (codec_id 2) decoding (docs/codec_affine_octree.md): the
// octree of the previous frame's vertices, each leaf moved by its affine
// matrix or by its vertices' direct motion.
#include "decoder/mesh3d/grid_frame_decoder.h"
#include "mesh3d/affine_octree.h"
#include "syntax/mesh3d/affine_octree.h"
#include "syntax/mesh3d/entropy_io.h"

namespace m4mesh {

namespace {

Grid grid_of(const AffineOctreeHeader& header) {
  Grid grid;
  for (int axis = 0; axis < 3; ++axis) {
    grid.origin[axis] = header.origin_value(axis);
    grid.step[axis] = header.step_value();
  }
  return grid;
}

class AffineOctreeDecoder final : public GridFrameDecoder {
 public:
  AffineOctreeDecoder(const ObjectHeader& object, const AffineOctreeHeader& header)
      : GridFrameDecoder(object, grid_of(header)), header_(header) {}

 private:
  void start(std::span<const Triangle>, uint32_t) override {}

  void decode_frame(syntax::ReadIO& io, std::vector<IntPoint3>& positions) override {
    AffineFrame frame;
    syntax::describe(io, frame);
    const uint8_t* payload = io.reader().data();
    const syntax::SectionPlace place{"bins", "raw", 8 * static_cast<uint64_t>(frame.bins.data() - payload),
                                     8 * static_cast<uint64_t>(frame.raw.data() - payload), io.plane()};
    if (trace_) {
      syntax::EntropyReadIO<true> cells(frame.bins, frame.raw, place, trace_);
      decode_cells(cells, frame.direct_shift, positions);
    } else {
      syntax::EntropyReadIO<false> cells(frame.bins, frame.raw, place);
      decode_cells(cells, frame.direct_shift, positions);
    }
  }

  template <class IO>
  void decode_cells(IO& io, uint32_t shift, std::vector<IntPoint3>& positions) {
    AffineCellCoder coder(header_);
    const RootCube cube = root_cube(positions);
    const int fraction_bits = header_.fraction_bits();
    next_.resize(positions.size());  // every vertex lies in exactly one leaf, which sets it
    auto store = [&](uint32_t v, const std::array<int64_t, 3>& q) {
      for (int axis = 0; axis < 3; ++axis) {
        if (q[axis] > kMaxQuantized || q[axis] < -kMaxQuantized)
          io.fail(ErrorKind::kOutOfRange, cell_.direct ? "direct_motion" : "matrix_residual",
                  "vertex " + std::to_string(v) + " leaves ±2^26 grid steps");
        next_[v][axis] = static_cast<int32_t>(q[axis]);
      }
    };
    partition_.walk(positions, cube, [&](const OctreeCell& cell) {
      coder.describe(io, cell.depth, cell.vertices.size(), cell_);
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
    io.finish("matrix_residual");
    positions.swap(next_);
  }

  AffineOctreeHeader header_;
  OctreePartition partition_;
  AffineCell cell_;
  std::vector<IntPoint3> next_;
};

}  // namespace

std::unique_ptr<CodecDecoder3d> make_affine_octree_decoder(const ObjectHeader& object, syntax::ReadIO& io) {
  AffineOctreeHeader header;
  syntax::describe(io, header);
  return std::make_unique<AffineOctreeDecoder>(object, header);
}

}  // namespace m4mesh
