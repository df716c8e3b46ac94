// Affine-Octree (codec_id 2) decoding (docs/codec_affine_octree.md): the
// octree of the previous frame's vertices, each leaf moved by its affine
// matrix or by its vertices' direct motion.
#if !defined(M4MESH_NO_SIMD) && defined(__x86_64__) && !defined(__EMSCRIPTEN__)
#include <immintrin.h>
#define M4MESH_AFFINE_AVX2 1  // chosen at run time, where the processor has it
#endif

#include "common/cpu.h"
#include "decoder/mesh3d/grid_frame_decoder.h"
#include "mesh3d/affine_octree.h"
#include "mesh3d/quantization.h"
#include "syntax/mesh3d/affine_octree.h"
#include "syntax/mesh3d/entropy_io.h"

namespace m4mesh {

namespace {

#ifdef M4MESH_AFFINE_AVX2
// apply_affine on a leaf's vertices in binary64 lanes, an axis a lane, in
// order up to the first result beyond ±kMaxQuantized; returns how many it
// stored. Exact: |Q| ≤ 2^23 and |p − corner|, side ≤ 2^27 make every
// product and partial sum an integer below 2^53, and the shift a floor
// after an exact scaling by 2^−f. No FMA.
__attribute__((target("avx2"))) size_t apply_affine_avx2(const AffineMatrix& q, int fraction_bits, const std::array<int64_t, 3>& corner,
                                                         int64_t side, std::span<const IntPoint3> positions,
                                                         std::span<const uint32_t> vertices, std::span<IntPoint3> out) {
  __m256d columns[3];
  for (size_t j = 0; j < 3; ++j)
    columns[j] = _mm256_set_pd(0, static_cast<double>(q[8 + j]), static_cast<double>(q[4 + j]), static_cast<double>(q[j]));
  const int64_t half = int64_t{1} << fraction_bits >> 1;
  const __m256d translation = _mm256_set_pd(0, static_cast<double>(q[11] * side + half), static_cast<double>(q[7] * side + half),
                                            static_cast<double>(q[3] * side + half));
  const __m256d origin = _mm256_set_pd(0, static_cast<double>(corner[2]), static_cast<double>(corner[1]), static_cast<double>(corner[0]));
  const __m256d scale = _mm256_set1_pd(1.0 / static_cast<double>(int64_t{1} << fraction_bits));
  const __m256d limit = _mm256_set1_pd(static_cast<double>(kMaxQuantized));
  const __m256d magnitude = _mm256_castsi256_pd(_mm256_set1_epi64x(INT64_MAX));
  for (size_t k = 0; k < vertices.size(); ++k) {
    const uint32_t v = vertices[k];
    const int32_t* p = positions[v].data();
    const __m128i xyz = _mm_insert_epi32(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(p)), p[2], 2);
    const __m256d d = _mm256_sub_pd(_mm256_cvtepi32_pd(xyz), origin);
    __m256d sum = translation;
    sum = _mm256_add_pd(sum, _mm256_mul_pd(columns[0], _mm256_permute4x64_pd(d, 0x00)));
    sum = _mm256_add_pd(sum, _mm256_mul_pd(columns[1], _mm256_permute4x64_pd(d, 0x55)));
    sum = _mm256_add_pd(sum, _mm256_mul_pd(columns[2], _mm256_permute4x64_pd(d, 0xaa)));
    const __m256d moved = _mm256_add_pd(origin, _mm256_floor_pd(_mm256_mul_pd(sum, scale)));
    if (_mm256_movemask_pd(_mm256_cmp_pd(_mm256_and_pd(moved, magnitude), limit, _CMP_GT_OQ)) != 0) return k;
    const __m128i moved32 = _mm256_cvtpd_epi32(moved);
    int32_t* at = out[v].data();
    _mm_storel_epi64(reinterpret_cast<__m128i*>(at), moved32);
    at[2] = _mm_extract_epi32(moved32, 2);
  }
  return vertices.size();
}
#endif

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
        size_t k = 0;
#ifdef M4MESH_AFFINE_AVX2
        if (has_avx2()) k = apply_affine_avx2(cell_.matrix, fraction_bits, cell.corner, cube.side, positions, cell.vertices, next_);
#endif
        for (; k < cell.vertices.size(); ++k) {
          const uint32_t v = cell.vertices[k];
          store(v, apply_affine(cell_.matrix, fraction_bits, cell.corner, cube.side, positions[v]));
        }
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
