#include "cli/metrics.h"

#include <nlohmann/json.hpp>
#include <cmath>
#include <cstdio>
#include <iostream>

#include "cli/console.h"
#include "cli/sequence_files.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "decoder/mesh3d/container_decoder.h"
#include "encoder/mesh3d/base_mesh.h"
#include "mesh3d/metrics.h"

namespace m4mesh {

namespace {

using console::say;

}  // namespace

int run_metrics(const MetricsArgs& args) {
  if (args.json && args.csv) throw usage_error("--json or --csv, not both");
  console::set_input(args.original);
  const MeshSequence given_original = load_frames(args.original);
  // The stream is checked against the sequence before anything is printed.
  struct Rate {
    const char* key;
    const char* label;
    double value;
  };
  std::vector<Rate> rates;
  bool stream_in_coding_order = false;  // frames decoded from it are numbered so too
  if (!args.stream.empty()) {
    console::set_input(args.stream);
    const std::vector<uint8_t> stream = read_file(args.stream);
    const Mesh3dDecoder headers(stream);
    const ObjectHeader h = headers.header();
    stream_in_coding_order = headers.vertex_order() == kVertexOrderCoding;
    if (h.vertex_count != given_original.vertex_count || h.face_count != given_original.faces.size() || h.frame_count != given_original.frames.size())
      throw Error(ErrorKind::kInput, "", kNoPlane, kNoOffset,
                  args.stream + ": a stream of " + std::to_string(h.vertex_count) + " vertices, " + std::to_string(h.face_count) + " faces, " +
                      std::to_string(h.frame_count) + " frames, not of the sequence compared (" + std::to_string(given_original.vertex_count) +
                      ", " + std::to_string(given_original.faces.size()) + ", " + std::to_string(given_original.frames.size()) + ")");
    const UnitSizes sizes = unit_sizes(split_container(stream), stream.size());
    const double v = static_cast<double>(given_original.vertex_count), f = static_cast<double>(given_original.frames.size());
    const uint64_t frame_bytes = sizes.bytes[static_cast<uint32_t>(UnitType::kFrame)];
    const uint64_t refinement_bytes = sizes.bytes[static_cast<uint32_t>(UnitType::kRefinement)];
    // The same columns for every codec: the whole stream first (rd's bpvf), a part a codec lacks empty (JSON: null).
    constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
    rates.push_back({"stream_rate_bpvf", "(the whole stream over vertices × frames, as rd's bpvf)", 8.0 * static_cast<double>(stream.size()) / (v * f)});
    rates.push_back({"frame_rate_bpvf", "(frame units over vertices × (frames − 1))",
                     frame_bytes > 0 && f > 1 ? 8.0 * static_cast<double>(frame_bytes) / (v * (f - 1)) : kNone});
    rates.push_back({"refinement_rate_bpvf", "(refinement units over vertices × frames)",
                     refinement_bytes > 0 ? 8.0 * static_cast<double>(refinement_bytes) / (v * f) : kNone});
  }
  StreamFacts facts;
  const MeshSequence decoded = load_sequence_or_stream(args.decoded, &facts);
  const MeshSequence original = original_as_decoded(given_original, decoded, facts.coding_order || (facts.codec.empty() && stream_in_coding_order),
                                                    args.decoded);
  for (const std::string& warning : metrics_warnings(original)) say("warning: %s", warning.c_str());
  const SequenceMetrics m = compare_sequences(original, decoded);
  const std::vector<FrameMetrics> frames = args.per_frame ? per_frame_metrics(original, decoded) : std::vector<FrameMetrics>{};
  const std::pair<const char*, double> figures[] = {{"kg_error_percent", m.kg_error}, {"rmse", m.rmse},
                                                    {"max_error", m.max_error},       {"psnr_db", m.psnr},
                                                    {"sted_spatial", m.sted_spatial}, {"sted_temporal", m.sted_temporal},
                                                    {"sted", m.sted}};
  auto number = [](double x) {
    char text[32];
    std::snprintf(text, sizeof text, "%.9g", x);
    return std::string(text);
  };
  if (args.json) {
    // JSON has no infinity: a lossless frame's PSNR is null.
    auto value = [](double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); };
    nlohmann::json out;
    for (const auto& [key, figure] : figures) out[key] = value(figure);
    for (const Rate& r : rates) out[r.key] = value(r.value);
    if (args.per_frame)
      for (size_t f = 0; f < frames.size(); ++f)
        out["frames"].push_back({{"frame", f}, {"rmse", frames[f].rmse}, {"max_error", frames[f].max_error}, {"psnr_db", value(frames[f].psnr)}});
    std::printf("%s\n", out.dump(2).c_str());
  } else if (args.csv && args.per_frame) {
    std::printf("frame,rmse,max_error,psnr_db\n");
    for (size_t f = 0; f < frames.size(); ++f)
      std::printf("%zu,%.9g,%.9g,%.9g\n", f, frames[f].rmse, frames[f].max_error, frames[f].psnr);
  } else if (args.csv) {
    std::string header, row;
    for (const auto& [key, value] : figures) {
      header += std::string(header.empty() ? "" : ",") + key;
      row += std::string(row.empty() ? "" : ",") + number(value);
    }
    for (const Rate& r : rates) {
      header += std::string(",") + r.key;
      row += "," + (std::isnan(r.value) ? std::string() : number(r.value));
    }
    std::printf("%s\n%s\n", header.c_str(), row.c_str());
  } else {
    std::printf("KG error      %.6f %%\n", m.kg_error);
    std::printf("RMSE          %.9g\n", m.rmse);
    std::printf("max error     %.9g\n", m.max_error);
    std::printf("PSNR          %.3f dB\n", m.psnr);
    std::printf("STED spatial  %.9g\n", m.sted_spatial);
    std::printf("STED temporal %.9g\n", m.sted_temporal);
    std::printf("STED          %.9g\n", m.sted);
    for (const Rate& r : rates)
      if (!std::isnan(r.value)) std::printf("%-13s %.4f bits/vertex/frame %s\n", r.key[0] == 's' ? "stream" : "rate", r.value, r.label);
    if (args.per_frame) {
      std::printf("%6s %16s %16s %10s\n", "frame", "RMSE", "max error", "PSNR dB");
      for (size_t f = 0; f < frames.size(); ++f) std::printf("%6zu %16.9g %16.9g %10.3f\n", f, frames[f].rmse, frames[f].max_error, frames[f].psnr);
    }
  }
  return 0;
}

int run_progressive(const ProgressiveArgs& args) {
  console::set_input(args.original);
  const MeshSequence given_original = load_frames(args.original);
  console::set_input(args.stream);
  const std::vector<uint8_t> stream = read_file(args.stream);
  const bool coding_order = Mesh3dDecoder(stream).vertex_order() == kVertexOrderCoding;
  const uint64_t step = args.step > 0 ? args.step : std::max<uint64_t>(1, stream.size() / 40);
  // Set up at the first unit, whose faces the original is matched to
  // (for_each_prefix refuses a stream that is not progressive before).
  std::optional<MeshSequence> original;
  std::optional<MetricsReference> reference;  // of *original
  uint64_t next_report = 0;
  for_each_prefix(stream, [&](size_t units, uint64_t bytes, const MeshSequence& decoded) {
    const bool first = !reference;
    if (first) {
      original = original_as_decoded(given_original, decoded, coding_order, args.stream);
      reference.emplace(*original);
    }
    if (bytes < next_report && bytes < stream.size()) return;
    next_report = bytes + step;
    const SequenceMetrics m = reference->compare(decoded);
    // Units: the base mesh and refinements (hash units count in the bytes).
    if (first) std::printf("%6s %10s %10s %10s %12s\n", "units", "bytes", "KG %", "PSNR dB", "STED");
    std::printf("%6zu %10llu %10.5f %10.3f %12.9f\n", units, static_cast<unsigned long long>(bytes), m.kg_error, m.psnr, m.sted);
  });
  return 0;
}

}  // namespace m4mesh
