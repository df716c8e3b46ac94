// Quality metrics for animated meshes (docs/metrics.md gives the formulas
// and how each source equation was read).
#pragma once

#include <span>
#include <string>
#include <vector>

#include <map>

#include "common/point3.h"
#include "mesh3d/frame_source.h"
#include "mesh3d/sequence.h"

namespace m4mesh {

struct StedParams {
  int d = 1;          // topological distance of the neighbourhood (Eq. 13)
  int w = 5;          // temporal window (Eq. 17)
  double dt = 0.0003; // temporal edge constant (Eq. 16)
  double c = 9.144e-5;  // weight of the temporal term (Eq. 20)
};

struct SequenceMetrics {
  double kg_error = 0;     // Karni–Gotsman, Váša & Skala Eq. 2 (percent)
  double rmse = 0;         // sqrt(mean over vertices and frames of |v' − v|²)
  double max_error = 0;    // max |v' − v|
  double psnr = 0;         // Affine-Octree Eq. 5 (dB)
  double sted_spatial = 0; // Eq. 14
  double sted_temporal = 0;// Eq. 19
  double sted = 0;         // Eq. 20
};

// What the metrics need of an original, computed once, for comparing it
// with many decoded versions (a progressive stream's prefixes): the STED
// neighbourhoods, the diameter and the original's temporal edges.
class MetricsReference {
 public:
  // `original` must outlive the reference.
  explicit MetricsReference(const MeshSequence& original, const StedParams& params = {});
  // `decoded` must have the original's vertex count, faces and frame count.
  SequenceMetrics compare(const MeshSequence& decoded) const;

 private:
  void sted(const MeshSequence& decoded, double& spatial, double& temporal, double& combined) const;

  const MeshSequence& original_;
  StedParams params_;
  std::vector<std::pair<NodeIndex, NodeIndex>> edges_;
  std::vector<std::vector<uint32_t>> neighbourhood_;  // per vertex, NE(i, d)
  double diameter_ = 1;                                // ld of Eq. 15
  std::vector<double> temporal_edges_, speeds_;        // per vertex and frame pair: tel, its window mean
};

// Both sequences must have the same vertex count, faces and frame count.
SequenceMetrics compare_sequences(const MeshSequence& original, const MeshSequence& decoded,
                                  const StedParams& sted = {});

// Per frame: RMSE, max error, and the PSNR of that frame's error against
// the whole sequence's dmax (so that frames compare with each other).
struct FrameMetrics {
  double rmse = 0, max_error = 0, psnr = 0;
};
std::vector<FrameMetrics> per_frame_metrics(const MeshSequence& original, const MeshSequence& decoded);

// What would make the figures mislead, as sentences: an axis along which
// the original hardly extends (errors along it barely count), or a few
// vertices far from the rest that set the bounding box (KG and PSNR are
// then relative to them).
std::vector<std::string> metrics_warnings(const MeshSequence& original);

double kg_error(const MeshSequence& original, const MeshSequence& decoded);

// The KG error, PSNR and max error of decoded frames against a source's frames,
// measured as the frames come (each once, in any order): a frame waits for
// the earlier ones, so that the sums run in frame order and give exactly
// what kg_error() and psnr() give for the whole sequences.
class QualityMeter {
 public:
  // `original` must outlive the meter.
  explicit QualityMeter(const FrameSource& original) : original_(original), reader_(original) {}
  void add(uint32_t frame, std::span<const Float3> decoded);
  // Once every frame is added.
  double kg() const;
  double psnr() const;
  double max_error() const { return max_error_; }

 private:
  void measure(uint32_t frame, std::span<const Float3> decoded);

  const FrameSource& original_;
  FrameReader reader_;
  std::map<uint32_t, std::vector<Float3>> waiting_;
  uint32_t next_ = 0;
  double error_ = 0, spread_ = 0, squared_distances_ = 0, max_error_ = 0;
};
// The largest distance between two points (exact; fast unless many points
// lie near the sphere about their box's centre that holds them all).
double diameter(std::span<const Vec3> points);
double psnr(const MeshSequence& original, const MeshSequence& decoded);
// Spatial and temporal STED and their combination.
void sted(const MeshSequence& original, const MeshSequence& decoded, const StedParams& params, double& spatial,
          double& temporal, double& combined);

}  // namespace m4mesh
