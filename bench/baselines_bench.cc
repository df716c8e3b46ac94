// The reference coders the rate tables set m4mesh beside, run on the same
// sequences (benchmark-only: nothing of them is in a stream m4mesh writes):
// - a connectivity-driven PCA coder in the style of Váša & Skala's Coddyac
//   (2007): PCA over the vertices' trajectories (the mean trajectory
//   removed), the basis quantized, each vertex's coefficients predicted by
//   the parallelograms of the base mesh's traversal, the residuals counted
//   at their ideal (order-0 entropy) cost per component; no connectivity
//   and no vertex order;
// - Draco coding every frame with edgebreaker at 8 … 16 bits (its sizes;
//   its errors from its own decoder).
// Each reports the bits per vertex and frame at KG 0.5 % and 0.1 %, read
// on its lower convex hull of (bpvf, KG) (linear between its points), and
// writes that hull with STED as CSV rows to the file named by
// M4MESH_BASELINES_CSV, if set (`python3 -m m4mesh.plot rd.csv that.csv
// --sequence NAME` draws them beside a sweep). M4MESH_BASELINES_SEQUENCES,
// if set, lists other sequences to run instead (paths, ':' between).
#include <benchmark/benchmark.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "anchors/draco_reference.h"
#include "bench/sequences.h"
#include "encoder/mesh3d/base_mesh.h"
#include "mesh3d/base_mesh.h"
#include "mesh3d/metrics.h"

namespace m4mesh {
namespace {

const char *const kSequences[] = {
    "pcow", "horse-gallop", "openfamc_testdata/dance_mesh", "openfamc_testdata/dog_mesh", "openfamc_testdata/handstand_mesh", "cloth/flag/flag.pc2"};

struct RatePoint {
  double bpvf = 0, kg = 0, sted = 0;
  std::string setting;
  MeshSequence decoded;
};

// Order-0 entropy of a list of integers, in bits per symbol.
double entropy(const std::vector<int64_t> &values) {
  std::map<int64_t, double> counts;
  for (int64_t v : values) counts[v] += 1;
  double bits = 0;
  const double n = static_cast<double>(values.size());
  for (const auto &[value, count] : counts) bits -= count * std::log2(count / n);
  return n > 0 ? bits / n : 0;
}

MeshSequence from_trajectories(const MeshSequence &s, const Eigen::MatrixXd &t) {
  MeshSequence out{s.vertex_count, s.faces, std::vector<std::vector<Vec3>>(s.frames.size())};
  for (size_t f = 0; f < s.frames.size(); ++f)
    for (Eigen::Index v = 0; v < t.rows(); ++v) {
      const auto c = static_cast<Eigen::Index>(3 * f);
      out.frames[f].push_back({static_cast<float>(t(v, c)), static_cast<float>(t(v, c + 1)), static_cast<float>(t(v, c + 2))});
    }
  return out;
}

// The Coddyac-style coder at every count of components and coefficient step
// tried.
std::vector<RatePoint> coddyac_points(const MeshSequence &s) {
  const auto vertices = static_cast<Eigen::Index>(s.vertex_count), columns = static_cast<Eigen::Index>(3 * s.frames.size());
  Eigen::MatrixXd t(vertices, columns);
  for (size_t f = 0; f < s.frames.size(); ++f)
    for (Eigen::Index v = 0; v < vertices; ++v) {
      const Vec3 &p = s.frames[f][static_cast<size_t>(v)];
      t(v, static_cast<Eigen::Index>(3 * f)) = p.x;
      t(v, static_cast<Eigen::Index>(3 * f + 1)) = p.y;
      t(v, static_cast<Eigen::Index>(3 * f + 2)) = p.z;
    }
  const Eigen::RowVectorXd mean = t.colwise().mean();
  const Eigen::MatrixXd x = t.rowwise() - mean;
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(x.transpose() * x);
  const Eigen::Index most = std::min<Eigen::Index>({256, columns, vertices});
  Eigen::MatrixXd basis(columns, most);
  for (Eigen::Index k = 0; k < most; ++k) basis.col(k) = eigen.eigenvectors().col(columns - 1 - k);
  const BaseMeshPlan plan = plan_base_mesh(s.faces, s.vertex_count, false);
  const MeshPredictor predictor(plan.faces, s.vertex_count);
  std::vector<uint32_t> rank(s.vertex_count);
  for (uint32_t i = 0; i < plan.input_of.size(); ++i) rank[plan.input_of[i]] = i;
  double extent = 0;
  for (int axis = 0; axis < 3; ++axis) extent = std::max(extent, x.col(axis).maxCoeff() - x.col(axis).minCoeff());

  std::vector<RatePoint> points;
  const double vertex_frames = static_cast<double>(s.vertex_count) * static_cast<double>(s.frames.size());
  // The basis (vectors of norm 1) in steps of 2^−basis_bits; the coefficients
  // projected on it.
  for (const int basis_bits_log2 : {12, 16}) {
    const double basis_step = std::ldexp(1.0, -basis_bits_log2);
    const Eigen::MatrixXd quantized_basis = (basis / basis_step).array().round() * basis_step;
    const Eigen::MatrixXd coefficients = x * quantized_basis;
    for (const Eigen::Index components : {4, 8, 12, 16, 24, 32, 48, 64, 96, 128, 192, 256}) {
      if (components > most) break;
      std::vector<int64_t> basis_values;
      for (Eigen::Index k = 0; k < components; ++k)
        for (Eigen::Index j = 0; j < columns; ++j) basis_values.push_back(std::llround(quantized_basis(j, k) / basis_step));
      const double basis_bits = static_cast<double>(basis_values.size()) * entropy(basis_values) + 32.0 * static_cast<double>(columns);
      for (int step_log2 = 5; step_log2 <= 13; ++step_log2) {
        const double step = extent * std::ldexp(1.0, -step_log2);
        std::vector<int32_t> q(s.vertex_count);
        double coefficient_bits = 0;
        Eigen::MatrixXd decoded_coefficients(vertices, components);
        for (Eigen::Index k = 0; k < components; ++k) {
          for (Eigen::Index v = 0; v < vertices; ++v) q[static_cast<size_t>(v)] = static_cast<int32_t>(std::lround(coefficients(v, k) / step));
          std::vector<int64_t> residuals;
          int64_t previous = 0;
          for (const uint32_t v : plan.input_of) {
            std::array<int64_t, 1> p{previous};
            predictor.predict(
                v, [&](uint32_t u) { return rank[u] < rank[v]; }, [&](uint32_t u) { return std::array<int32_t, 1>{q[u]}; }, p);
            residuals.push_back(q[v] - p[0]);
            previous = q[v];
          }
          coefficient_bits += static_cast<double>(residuals.size()) * entropy(residuals);
          for (Eigen::Index v = 0; v < vertices; ++v) decoded_coefficients(v, k) = step * q[static_cast<size_t>(v)];
        }
        const Eigen::MatrixXd decoded = (decoded_coefficients * quantized_basis.leftCols(components).transpose()).rowwise() + mean;
        RatePoint point;
        point.decoded = from_trajectories(s, decoded);
        point.kg = kg_error(s, point.decoded);
        point.bpvf = (basis_bits + coefficient_bits) / vertex_frames;
        point.setting = std::to_string(components) + " components step 2^-" + std::to_string(step_log2) + " of the extent basis 2^-" +
                        std::to_string(basis_bits_log2);
        points.push_back(std::move(point));
      }
    }
  }
  return points;
}

std::vector<RatePoint> draco_points(const MeshSequence &s) {
  std::vector<RatePoint> points;
  const double vertex_frames = static_cast<double>(s.vertex_count) * static_cast<double>(s.frames.size());
  for (int bits = 8; bits <= 16; ++bits) {
    RatePoint point{0, 0, 0, std::to_string(bits) + " bits", MeshSequence{s.vertex_count, s.faces, {}}};
    double total = 0;
    for (const std::vector<Vec3> &frame : s.frames) {
      std::vector<std::array<float, 3>> p;
      for (const Vec3 &v : frame) p.push_back({static_cast<float>(v.x), static_cast<float>(v.y), static_cast<float>(v.z)});
      total += 8.0 * static_cast<double>(draco_frame_size(s.faces, p, bits));
      std::vector<Vec3> decoded;
      for (const std::array<float, 3> &d : draco_frame_decoded(s.faces, p, bits)) decoded.push_back({d[0], d[1], d[2]});
      point.decoded.frames.push_back(std::move(decoded));
    }
    point.kg = kg_error(s, point.decoded);
    point.bpvf = total / vertex_frames;
    points.push_back(std::move(point));
  }
  return points;
}

// The lower convex hull of the points, by increasing rate.
std::vector<RatePoint> lower_hull(std::vector<RatePoint> points) {
  std::sort(points.begin(), points.end(), [](const RatePoint &a, const RatePoint &b) { return a.bpvf < b.bpvf; });
  std::vector<RatePoint> hull;
  for (RatePoint &p : points) {
    if (!hull.empty() && p.kg >= hull.back().kg) continue;  // no better than a cheaper point
    while (hull.size() >= 2) {
      const RatePoint &a = hull[hull.size() - 2], &b = hull.back();
      const double cross = (b.bpvf - a.bpvf) * (p.kg - a.kg) - (b.kg - a.kg) * (p.bpvf - a.bpvf);
      if (cross > 0) break;
      hull.pop_back();
    }
    hull.push_back(std::move(p));
  }
  return hull;
}

// The rate at which the hull reaches a KG error (NAN: never).
double rate_at(const std::vector<RatePoint> &hull, double kg) {
  for (size_t k = 0; k < hull.size(); ++k) {
    if (hull[k].kg > kg) continue;
    if (k == 0) return hull[0].bpvf;
    const double t = (hull[k - 1].kg - kg) / (hull[k - 1].kg - hull[k].kg);
    return hull[k - 1].bpvf + t * (hull[k].bpvf - hull[k - 1].bpvf);
  }
  return NAN;
}

// The CSV file M4MESH_BASELINES_CSV names, opened once with its header; null when unset.
std::FILE* csv_output() {
  static std::FILE* file = [] {
    const char* path = std::getenv("M4MESH_BASELINES_CSV");
    std::FILE* f = path ? std::fopen(path, "w") : nullptr;
    if (path && !f) std::fprintf(stderr, "cannot write %s\n", path);
    if (f) std::fprintf(f, "sequence,codec,parameter,bpvf,kg_percent,sted\n");
    return f;
  }();
  return file;
}

void report(benchmark::State& state, const std::string& name, const char* coder, std::vector<RatePoint> points) {
  std::vector<RatePoint> hull = lower_hull(std::move(points));
  for (RatePoint& p : hull) {
    p.sted = compare_sequences(bench::sequence(name), p.decoded).sted;
    if (std::FILE* csv = csv_output()) {
      std::fprintf(csv, "%s,%s,%s,%.4f,%.5f,%.6f\n", bench::label(name).c_str(), coder, p.setting.c_str(), p.bpvf, p.kg, p.sted);
      std::fflush(csv);
    }
  }
  state.counters[std::string(coder) + "_bpvf_kg0.5"] = rate_at(hull, 0.5);
  state.counters[std::string(coder) + "_bpvf_kg0.1"] = rate_at(hull, 0.1);
}

void BM_Coddyac(benchmark::State &state, const std::string& name) {
  std::vector<RatePoint> points;
  for (auto _ : state) points = coddyac_points(bench::sequence(name));
  state.SetLabel(bench::label(name));
  report(state, name, "coddyac-style", std::move(points));
}

void BM_DracoEveryFrame(benchmark::State &state, const std::string& name) {
  std::vector<RatePoint> points;
  for (auto _ : state) points = draco_points(bench::sequence(name));
  state.SetLabel(bench::label(name));
  report(state, name, "draco-every-frame", std::move(points));
}

// ../shared/data's sequences, or those M4MESH_BASELINES_SEQUENCES lists.
std::vector<std::string> sequence_names() {
  const char* list = std::getenv("M4MESH_BASELINES_SEQUENCES");
  if (!list) return {std::begin(kSequences), std::end(kSequences)};
  std::vector<std::string> names;
  std::string text = list;
  for (size_t start = 0; start <= text.size();) {
    const size_t end = std::min(text.find(':', start), text.size());
    if (end > start) names.push_back(text.substr(start, end - start));
    start = end + 1;
  }
  return names;
}

}  // namespace
}  // namespace m4mesh

int main(int argc, char** argv) {
  const std::vector<std::string> names = m4mesh::sequence_names();
  for (const auto& [coder, run] : {std::pair{"BM_Coddyac", &m4mesh::BM_Coddyac}, std::pair{"BM_DracoEveryFrame", &m4mesh::BM_DracoEveryFrame}})
    for (size_t i = 0; i < names.size(); ++i)
      benchmark::RegisterBenchmark((std::string(coder) + "/" + std::to_string(i)).c_str(), run, names[i])
          ->Unit(benchmark::kSecond)
          ->Iterations(1)
          ->UseRealTime();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
