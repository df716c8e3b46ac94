// Affine-Octree (codec_id 2) encoding (docs/codec_affine_octree.md): per
// cell the least-squares affine map from the previous decoded frame to
// the current one, quantized; a cell splits while a vertex misses by more
// than ME, and a cell of at most 4 vertices codes their motion directly.
#include <Eigen/Dense>
#include <cmath>

#include "common/bit_cast.h"
#include "encoder/mesh3d/codec_options.h"
#include "encoder/mesh3d/grid_frame_encoder.h"
#include "mesh3d/affine_octree.h"
#include "syntax/mesh3d/affine_octree.h"
#include "syntax/mesh3d/entropy_io.h"

namespace m4mesh {

namespace {

int32_t clamp_to(double value, int32_t lo, int32_t hi) {
  const double rounded = std::nearbyint(value);
  return rounded < lo ? lo : rounded > hi ? hi : static_cast<int32_t>(rounded);
}

class AffineOctreeEncoder final : public GridFrameEncoder {
 public:
  AffineOctreeEncoder(const FrameSource& s, const CodecSettings& settings)
      : GridFrameEncoder(Grid::covering(s, settings.integer("bits"), true), settings.integer("intra-period"), settings.base_mesh()),
        max_error_(settings.number("me") / 100) {
    header_.bits = static_cast<uint32_t>(settings.integer("bits"));
    for (int axis = 0; axis < 3; ++axis) header_.origin[axis] = bit_cast<uint32_t>(grid_.origin[axis]);
    header_.step = bit_cast<uint32_t>(grid_.step[0]);
    header_.matrix_bits = static_cast<uint32_t>(settings.integer("matrix-bits"));
    header_.matrix_range_log2 = static_cast<uint32_t>(settings.integer("matrix-range-log2"));
    header_.max_depth = static_cast<uint32_t>(settings.integer("max-depth"));
    if (header_.matrix_range_log2 >= header_.matrix_bits)
      throw usage_error("--matrix-range-log2 must be below --matrix-bits (affine-octree)");
  }

  void write_header(syntax::WriteIO& io) override { syntax::describe(io, header_); }
  std::vector<CodecStatistic> statistics() const override {
    return {{"matrices", static_cast<double>(matrices_)}, {"vertices coded directly", static_cast<double>(direct_vertices_)}};
  }

 private:
  void encode_frame(syntax::WriteIO& io, std::span<const Vec3> frame, size_t frame_index, std::vector<IntPoint3>& positions) override {
    const syntax::SectionPlace place{"bins", "raw", 0, 0, io.plane()};
    if (io.trace()) {
      syntax::EntropyWriteIO<true> cells(place, io.trace());
      encode_cells(io, cells, frame, frame_index, positions);
    } else {
      syntax::EntropyWriteIO<false> cells(place);
      encode_cells(io, cells, frame, frame_index, positions);
    }
  }

  // The cells through `cells`, then the frame's data into `io`.
  template <class CellIO>
  void encode_cells(syntax::WriteIO& io, CellIO& cells, std::span<const Vec3> frame, size_t frame_index, std::vector<IntPoint3>& positions) {
    quantize_frame(grid_, frame, frame_index, next_);  // checks that the frame fits the grid
    target_.resize(frame.size());
    const double step = grid_.step[0];
    for (size_t i = 0; i < frame.size(); ++i)
      target_[i] = {(frame[i].x - grid_.origin[0]) / step, (frame[i].y - grid_.origin[1]) / step, (frame[i].z - grid_.origin[2]) / step};
    cube_ = root_cube(positions);
    limit_ = max_error_ * static_cast<double>(cube_.side);
    // Direct motion in steps of 2^shift grid units, at most a quarter of ME off.
    uint32_t shift = 0;
    while (shift < kMaxDirectShift && std::ldexp(std::sqrt(3.0) / 2, static_cast<int>(shift) + 1) <= limit_ / 4) ++shift;
    shift_ = static_cast<int>(shift);

    AffineCellCoder coder(header_);
    partition_.walk(positions, cube_, [&](const OctreeCell& cell) {
      const size_t n = cell.vertices.size();
      cell_.split = false;
      cell_.direct = n <= kMaxDirectCellVertices;
      if (!cell_.direct) {
        const double error = fit(cell, positions);
        if (error > limit_) {
          if (cell.depth < static_cast<int>(header_.max_depth))
            cell_.split = true;
          else
            cell_.direct = true;  // no deeper level left: the exact fallback
        }
      }
      if (cell_.direct) direct_motion(cell, positions);
      coder.describe(cells, cell.depth, n, cell_);
      if (cell_.split) return true;
      if (cell_.direct) {
        direct_vertices_ += n;
        for (size_t k = 0; k < n; ++k)
          for (int axis = 0; axis < 3; ++axis)
            next_[cell.vertices[k]][axis] = static_cast<int32_t>(positions[cell.vertices[k]][axis] + (int64_t{cell_.motion[k][axis]} << shift_));
      } else {
        ++matrices_;
        for (size_t k = 0; k < n; ++k)
          for (int axis = 0; axis < 3; ++axis) next_[cell.vertices[k]][axis] = static_cast<int32_t>(fitted_[k][axis]);
      }
      return false;
    });
    positions.swap(next_);
    AffineFrame data;
    data.direct_shift = shift;
    cells.finish(io, data);
  }

  // The least-squares affine map of the cell (in cell-local coordinates, as
  // a deviation from identity, so that a singular cell's pseudo-inverse
  // keeps identity along the directions it cannot see), quantized into
  // cell_.matrix; returns the largest vertex error after reconstruction.
  double fit(const OctreeCell& cell, std::span<const IntPoint3> positions) {
    const double scale = static_cast<double>(std::max<int64_t>(cube_.side >> cell.depth, 1));
    Eigen::Matrix4d moments = Eigen::Matrix4d::Zero();
    Eigen::Matrix<double, 3, 4> cross = Eigen::Matrix<double, 3, 4>::Zero();
    for (uint32_t v : cell.vertices) {
      Eigen::Vector4d x;
      Eigen::Vector3d y;
      for (int axis = 0; axis < 3; ++axis) {
        x(axis) = static_cast<double>(positions[v][axis] - cell.corner[axis]) / scale;
        y(axis) = (target_[v][axis] - static_cast<double>(cell.corner[axis])) / scale - x(axis);
      }
      x(3) = 1;
      moments += x * x.transpose();
      cross += y * x.transpose();
    }
    // The pseudo-inverse without the null directions (coplanar or collinear
    // points); when that still leaves the matrix range, the SVD keeps only
    // the components holding 95 % of the energy.
    Eigen::JacobiSVD<Eigen::Matrix4d> svd(moments, Eigen::ComputeFullU | Eigen::ComputeFullV);
    const Eigen::Vector4d& sigma = svd.singularValues();
    int rank = 1;
    while (rank < 4 && sigma(rank) > 1e-9 * sigma(0)) ++rank;
    Eigen::Matrix<double, 3, 4> deviation = solve(svd, cross, rank);
    const double range = std::ldexp(1.0, static_cast<int>(header_.matrix_range_log2) - 1);
    bool out_of_range = false;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 4; ++j) out_of_range |= std::abs(deviation(i, j) + (i == j)) >= range;
    if (out_of_range) {
      const double total = sigma.sum();
      int kept = 0;
      for (double energy = 0; kept < rank && energy < 0.95 * total; ++kept) energy += sigma(kept);
      deviation = solve(svd, cross, kept);
    }
    const int f = header_.fraction_bits();
    const double one = std::ldexp(1.0, f);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        cell_.matrix[static_cast<size_t>(4 * i + j)] = clamp_to((deviation(i, j) + (i == j)) * one, header_.matrix_min(), header_.matrix_max());
    // The translation again, for the quantized linear part: the mean remaining offset.
    for (int i = 0; i < 3; ++i) {
      double offset = 0;
      for (uint32_t v : cell.vertices) {
        double moved = 0;
        for (int j = 0; j < 3; ++j) moved += cell_.matrix[static_cast<size_t>(4 * i + j)] * static_cast<double>(positions[v][j] - cell.corner[j]);
        offset += target_[v][i] - static_cast<double>(cell.corner[i]) - moved / one;
      }
      offset /= static_cast<double>(cell.vertices.size());
      cell_.matrix[static_cast<size_t>(4 * i + 3)] = clamp_to(offset * one / static_cast<double>(cube_.side), header_.matrix_min(), header_.matrix_max());
    }
    fitted_.resize(cell.vertices.size());
    double worst = 0;
    for (size_t k = 0; k < cell.vertices.size(); ++k) {
      const uint32_t v = cell.vertices[k];
      fitted_[k] = apply_affine(cell_.matrix, f, cell.corner, cube_.side, positions[v]);
      double squared = 0;
      for (int axis = 0; axis < 3; ++axis) {
        const double d = static_cast<double>(fitted_[k][axis]) - target_[v][axis];
        squared += d * d;
      }
      // A reconstruction off the grid's range counts as a miss.
      for (int axis = 0; axis < 3; ++axis)
        if (fitted_[k][axis] > kMaxQuantized || fitted_[k][axis] < -kMaxQuantized) squared = HUGE_VAL;
      worst = std::max(worst, squared);
    }
    return std::sqrt(worst);
  }

  // cross · moments⁺ with the `kept` largest singular values.
  static Eigen::Matrix<double, 3, 4> solve(const Eigen::JacobiSVD<Eigen::Matrix4d>& svd, const Eigen::Matrix<double, 3, 4>& cross,
                                           int kept) {
    Eigen::Vector4d inverse = Eigen::Vector4d::Zero();
    for (int i = 0; i < kept; ++i)
      inverse(i) = 1 / svd.singularValues()(i);
    return cross * (svd.matrixV() * inverse.asDiagonal() * svd.matrixU().transpose());
  }

  void direct_motion(const OctreeCell& cell, std::span<const IntPoint3> positions) {
    cell_.motion.resize(cell.vertices.size());
    for (size_t k = 0; k < cell.vertices.size(); ++k)
      for (int axis = 0; axis < 3; ++axis) {
        const uint32_t v = cell.vertices[k];
        cell_.motion[k][axis] = static_cast<int32_t>(std::nearbyint(std::ldexp(target_[v][axis] - positions[v][axis], -shift_)));
      }
  }

  AffineOctreeHeader header_;
  double max_error_;
  OctreePartition partition_;
  RootCube cube_;
  double limit_ = 0;  // ME in grid units
  int shift_ = 0;
  AffineCell cell_;
  std::vector<std::array<double, 3>> target_;
  std::vector<std::array<int64_t, 3>> fitted_;
  std::vector<IntPoint3> next_;
  uint64_t matrices_ = 0;         // affine leaves in all frames
  uint64_t direct_vertices_ = 0;  // vertices coded by direct motion
};

}  // namespace

std::vector<CodecOption> affine_octree_options() {
  return {bits_option("quantization bits per coordinate"),
          {"me", "affine-octree: ME, the largest vertex error of an affine cell, in % of the root cube", OptionKind::kNumber, "1", 0.001, 100},
          {"matrix-bits", "affine-octree: k, bits per matrix element", OptionKind::kInteger, "16", 4, 24},
          {"matrix-range-log2", "affine-octree: matrix elements lie in [−2^(r−1), 2^(r−1))", OptionKind::kInteger, "2", 1, 8},
          {"max-depth", "affine-octree: the deepest octree level", OptionKind::kInteger, "16", 1, kMaxOctreeDepth},
          intra_period_option()};
}

std::unique_ptr<CodecEncoder3d> make_affine_octree_encoder(const FrameSource& sequence, const CodecSettings& settings) {
  return std::make_unique<AffineOctreeEncoder>(sequence, settings);
}

}  // namespace m4mesh
