#include "cli/rd.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "cli/commands3d.h"
#include "cli/console.h"
#include "codecs3d/registry.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "decoder/mesh3d/container_decoder.h"
#include "encoder/mesh3d/container_encoder.h"
#include "mesh3d/metrics.h"

namespace m4mesh {

namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The registry rows of the codecs named, or every row.
std::vector<const Codec3d*> codec_rows(const std::vector<std::string>& names) {
  std::vector<const Codec3d*> rows;
  if (names.empty())
    for (const Codec3d& c : codecs3d()) rows.push_back(&c);
  else
    for (const std::string& name : names) rows.push_back(&codec3d_by_name(name));
  return rows;
}

}  // namespace

std::vector<RdPoint> rd_sweep(const MeshSequence& s, const std::vector<std::string>& codecs, const std::function<void(const RdPoint&)>& each) {
  const std::vector<const Codec3d*> rows = codec_rows(codecs);
  const MetricsReference reference(s);
  const double vertex_frames = static_cast<double>(s.vertex_count) * static_cast<double>(s.frames.size());
  std::vector<RdPoint> points;
  for (const Codec3d* codec : rows)
    for (const std::string& value : codec->quality.coarse_to_fine) {
      Encode3dOptions options;
      options.codec = codec->name;
      options.codec_options[codec->quality.option] = value;
      options.hashes = false;
      RdPoint p{codec->name, "--" + codec->quality.option + " " + value};
      auto start = std::chrono::steady_clock::now();
      std::vector<uint8_t> stream;
      try {
        stream = encode_mesh3d(s, options).stream;
      } catch (const Error& e) {
        // A setting that cannot code this sequence is left out, and the sweep goes on.
        if (e.kind() != ErrorKind::kInput && e.kind() != ErrorKind::kLimit) throw;
        console::say("note: %s %s cannot code this sequence, left out: %s", codec->name.c_str(), p.parameter.c_str(), e.what());
        continue;
      }
      p.encode_s = seconds_since(start);
      start = std::chrono::steady_clock::now();
      const MeshSequence decoded = decode_mesh3d(stream);
      p.decode_s = seconds_since(start);
      const SequenceMetrics m = reference.compare(decoded);
      p.bytes = stream.size();
      p.bpvf = 8.0 * static_cast<double>(stream.size()) / vertex_frames;
      p.kg = m.kg_error;
      p.psnr = m.psnr;
      p.rmse = m.rmse;
      p.sted = m.sted;
      each(p);
      points.push_back(p);
    }
  return points;
}

std::string rd_csv(const std::vector<RdPoint>& points) {
  std::string out = "codec,parameter,bytes,bpvf,kg_percent,psnr_db,rmse,sted,encode_s,decode_s\n";
  char row[512];
  for (const RdPoint& p : points) {
    std::snprintf(row, sizeof row, "%s,%s,%llu,%.9g,%.9g,%.9g,%.9g,%.9g,%.6f,%.6f\n", p.codec.c_str(), p.parameter.c_str(),
                  static_cast<unsigned long long>(p.bytes), p.bpvf, p.kg, p.psnr, p.rmse, p.sted, p.encode_s, p.decode_s);
    out += row;
  }
  return out;
}

std::string rd_json(const std::vector<RdPoint>& points) {
  // JSON has no infinity: a lossless point's PSNR is null.
  auto finite = [](double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); };
  nlohmann::json out = nlohmann::json::array();
  for (const RdPoint& p : points)
    out.push_back({{"codec", p.codec}, {"parameter", p.parameter}, {"bytes", p.bytes}, {"bpvf", p.bpvf}, {"kg_percent", p.kg},
                   {"psnr_db", finite(p.psnr)}, {"rmse", p.rmse}, {"sted", p.sted}, {"encode_s", p.encode_s}, {"decode_s", p.decode_s}});
  return out.dump(2) + "\n";
}

int run_rd(const RdArgs& args) {
  namespace fs = std::filesystem;
  const std::string extension = args.output == "-" ? "" : fs::path(args.output).extension().string();
  if (args.output != "-" && extension != ".csv" && extension != ".json")
    throw Error(ErrorKind::kUsage, "", kNoPlane, kNoOffset, args.output + ": rd writes .csv or .json (or - for CSV on standard output)");
  const bool json = args.json || extension == ".json";
  refuse_overwriting(args.input, args.output);
  const MeshSequence sequence = load_sequence(args.input, !console::quiet());
  size_t total = 0;
  for (const Codec3d* codec : codec_rows(args.codecs)) total += codec->quality.coarse_to_fine.size();
  console::Progress progress("rate-distortion point", total);
  size_t done = 0;
  const auto start = std::chrono::steady_clock::now();
  const std::vector<RdPoint> points = rd_sweep(sequence, args.codecs, [&](const RdPoint& p) {
    progress.update(++done);
    console::detail("%s %s: %llu bytes, %.4f bpvf, KG %.5f", p.codec.c_str(), p.parameter.c_str(), static_cast<unsigned long long>(p.bytes),
                    p.bpvf, p.kg);
  });
  progress.finish();
  const std::string text = json ? rd_json(points) : rd_csv(points);
  write_file_atomically(args.output, text);
  console::say("%s: %zu points in %.1f s", args.output.c_str(), points.size(), seconds_since(start));
  return 0;
}

}  // namespace m4mesh
