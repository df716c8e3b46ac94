#include "encoder/mesh3d/cpca_wpt_analysis.h"

#include <algorithm>
#include <cmath>

namespace m4mesh::cpca_wpt {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

Eigen::MatrixXd trajectories(const MeshSequence& s, size_t most_frames) {
  const size_t frames = std::min(s.frames.size(), most_frames);
  Eigen::MatrixXd x(s.vertex_count, 3 * static_cast<Eigen::Index>(frames));
  for (size_t k = 0; k < frames; ++k) {
    // Evenly spaced over the frames, the first and (with two or more) the last included.
    const size_t f = frames > 1 ? k * (s.frames.size() - 1) / (frames - 1) : 0;
    for (size_t v = 0; v < s.vertex_count; ++v) {
      const Vec3& p = s.frames[f][v];
      x(static_cast<Eigen::Index>(v), static_cast<Eigen::Index>(3 * k)) = p.x;
      x(static_cast<Eigen::Index>(v), static_cast<Eigen::Index>(3 * k + 1)) = p.y;
      x(static_cast<Eigen::Index>(v), static_cast<Eigen::Index>(3 * k + 2)) = p.z;
    }
  }
  return x;
}

std::vector<uint32_t> cluster_trajectories(const Eigen::MatrixXd& x, int k) {
  const Eigen::Index vertices = x.rows();
  const Eigen::RowVectorXd mean = x.colwise().mean();
  Eigen::VectorXd nearest = (x.rowwise() - mean).rowwise().squaredNorm();
  std::vector<Eigen::Index> seeds;
  for (int c = 0; c < k; ++c) {
    Eigen::Index far = 0;
    nearest.maxCoeff(&far);
    if (c > 0 && !(nearest(far) > 0)) break;  // fewer distinct trajectories than clusters
    seeds.push_back(far);
    nearest = nearest.cwiseMin((x.rowwise() - x.row(far)).rowwise().squaredNorm());
  }
  Eigen::MatrixXd centers(static_cast<Eigen::Index>(seeds.size()), x.cols());
  for (size_t c = 0; c < seeds.size(); ++c) centers.row(static_cast<Eigen::Index>(c)) = x.row(seeds[c]);
  std::vector<uint32_t> cluster(static_cast<size_t>(vertices), UINT32_MAX);
  for (int iteration = 0; iteration < 50; ++iteration) {
    const Eigen::MatrixXd cross = x * centers.transpose();
    const Eigen::VectorXd norms = centers.rowwise().squaredNorm();
    bool moved = false;
    for (Eigen::Index v = 0; v < vertices; ++v) {
      Eigen::Index best = 0;
      (norms.transpose() - 2 * cross.row(v)).minCoeff(&best);
      moved |= cluster[static_cast<size_t>(v)] != static_cast<uint32_t>(best);
      cluster[static_cast<size_t>(v)] = static_cast<uint32_t>(best);
    }
    if (!moved) break;
    Eigen::MatrixXd sums = Eigen::MatrixXd::Zero(centers.rows(), centers.cols());
    std::vector<double> counts(seeds.size(), 0);
    for (Eigen::Index v = 0; v < vertices; ++v) {
      sums.row(cluster[static_cast<size_t>(v)]) += x.row(v);
      counts[cluster[static_cast<size_t>(v)]] += 1;
    }
    for (size_t c = 0; c < seeds.size(); ++c)
      if (counts[c] > 0) centers.row(static_cast<Eigen::Index>(c)) = sums.row(static_cast<Eigen::Index>(c)) / counts[c];
  }
  std::vector<uint32_t> renumbered(seeds.size(), UINT32_MAX);
  uint32_t next = 0;
  for (uint32_t& c : cluster) {
    if (renumbered[c] == UINT32_MAX) renumbered[c] = next++;
    c = renumbered[c];
  }
  return cluster;
}

Clustering clustering(const MeshSequence& s, int requested) {
  const auto start = std::chrono::steady_clock::now();
  // A large sequence's trajectories are sampled: k-means' cost grows with their length.
  const size_t most_frames = uint64_t{s.vertex_count} * s.frames.size() > kClusteringVertexFrames
                                 ? std::max<size_t>(16, kClusteringVertexFrames / s.vertex_count)
                                 : s.frames.size();
  Clustering c{requested, cluster_trajectories(trajectories(s, most_frames), std::min<int>(requested, static_cast<int>(s.vertex_count))), 0};
  c.seconds = seconds_since(start);
  return c;
}

namespace {

// The leading eigenpairs of a symmetric positive semi-definite matrix, at
// least `count` of them (in increasing order, as the full solver gives
// them): every one, or for a large matrix and few asked for, those of its
// projection on the subspace that eight block power iterations from a
// fixed start settle on (with 16 more vectors than asked for).
std::pair<Eigen::VectorXd, Eigen::MatrixXd> leading_eigenpairs(const Eigen::MatrixXd& gram, size_t count) {
  const Eigen::Index n = gram.rows(), block = std::min<Eigen::Index>(n, static_cast<Eigen::Index>(count) + 16);
  if (10 * block >= n) {
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(gram);
    return {eigen.eigenvalues(), eigen.eigenvectors()};
  }
  // A fixed start of ±1 (a linear congruential sequence), the same on every platform.
  Eigen::MatrixXd q(n, block);
  uint64_t state = 1;
  for (Eigen::Index j = 0; j < block; ++j)
    for (Eigen::Index i = 0; i < n; ++i) {
      state = state * 6364136223846793005u + 1442695040888963407u;
      q(i, j) = (state >> 63) ? 1.0 : -1.0;
    }
  for (int iteration = 0; iteration < 8; ++iteration) {
    const Eigen::MatrixXd product = gram * q;
    q = Eigen::HouseholderQR<Eigen::MatrixXd>(product).householderQ() * Eigen::MatrixXd::Identity(n, block);
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> small(q.transpose() * gram * q);
  return {small.eigenvalues(), q * small.eigenvectors()};
}

}  // namespace

std::vector<Component> principal_components(const Eigen::MatrixXd& d, size_t count) {
  const bool by_frames = d.rows() >= d.cols();
  const Eigen::MatrixXd gram = by_frames ? Eigen::MatrixXd(d.transpose() * d) : Eigen::MatrixXd(d * d.transpose());
  const auto [values, vectors] = leading_eigenpairs(gram, count);
  std::vector<Component> components;
  const Eigen::Index n = values.size();
  const double largest = n > 0 ? values(n - 1) : 0;
  for (Eigen::Index i = n - 1; i >= 0 && components.size() < count; --i) {
    const double lambda = values(i);
    if (!(lambda > 1e-12 * largest)) break;
    Component c{std::sqrt(lambda), {}, {}};
    if (by_frames) {
      c.coefficients = vectors.col(i);
      c.basis = d * c.coefficients / c.sigma;
    } else {
      c.basis = vectors.col(i);
      c.coefficients = d.transpose() * c.basis / c.sigma;
    }
    Eigen::Index at = 0;
    c.coefficients.cwiseAbs().maxCoeff(&at);
    if (c.coefficients(at) < 0) {
      c.coefficients = -c.coefficients;
      c.basis = -c.basis;
    }
    components.push_back(std::move(c));
  }
  return components;
}

Eigen::MatrixXd as_trajectories(const Eigen::MatrixXd& d) {
  Eigen::MatrixXd t(d.rows() / 3, 3 * d.cols());
  for (Eigen::Index row = 0; row < d.rows(); ++row)
    for (Eigen::Index n = 0; n < d.cols(); ++n) t(row / 3, 3 * n + row % 3) = d(row, n);
  return t;
}

}  // namespace m4mesh::cpca_wpt
