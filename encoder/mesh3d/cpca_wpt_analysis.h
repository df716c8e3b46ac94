// cpca-wpt's analysis of a sequence (docs/codec_cpca_wpt.md, not
// normative): k-means on the vertices' trajectories, and the principal
// components of a cluster's motion.
#pragma once

#include <Eigen/Dense>
#include <chrono>
#include <cstdint>
#include <cstddef>
#include <vector>

#include "mesh3d/sequence.h"

namespace m4mesh::cpca_wpt {

double seconds_since(std::chrono::steady_clock::time_point start);

// Vertex v's trajectory is row v: x, y, z of frame 0, then of frame 1, …
// (at most `most_frames` frames, evenly spaced).
Eigen::MatrixXd trajectories(const MeshSequence& s, size_t most_frames = SIZE_MAX);

// Sequences of more vertex-frames than this cluster their vertices by
// trajectories of fewer frames (16, or as many as this holds), evenly spaced.
inline constexpr uint64_t kClusteringVertexFrames = uint64_t{1} << 20;

// k-means on the trajectories, deterministic: the first center is the
// trajectory farthest from the mean, each next the one farthest from the
// centers so far (ties: the lowest vertex); then Lloyd iterations (ties:
// the lowest cluster) until no vertex moves, at most 50. Clusters are
// numbered by their first vertex; none is empty.
std::vector<uint32_t> cluster_trajectories(const Eigen::MatrixXd& x, int k);

// The clusters of k-means asked for `requested` clusters (on trajectories
// of at most kClusteringVertexFrames), and its seconds: computed once per
// count and shared by a search's candidates.
struct Clustering {
  int requested = 0;
  std::vector<uint32_t> cluster_of;
  double seconds = 0;
};

Clustering clustering(const MeshSequence& s, int requested);

// A principal component of a cluster's motion matrix D (3M × N):
// D ≈ Σ sigma · basis · coefficientsᵀ, basis and coefficients unit vectors.
struct Component {
  double sigma;
  Eigen::VectorXd basis, coefficients;
};

// The components in decreasing sigma, at most `count`, those with sigma
// above 10^−6 of the first: from the eigenvectors of the smaller Gram
// matrix (DᵀD or DDᵀ), all of them or, when few are asked of a large one,
// the leading ones by block power iteration. The largest coefficient of
// each is positive.
std::vector<Component> principal_components(const Eigen::MatrixXd& d, size_t count);

// A motion matrix (3M × N) as the members' trajectories (M × 3N): row i,
// column 3n + a holds axis a of member i in frame n.
Eigen::MatrixXd as_trajectories(const Eigen::MatrixXd& d);

}  // namespace m4mesh::cpca_wpt
