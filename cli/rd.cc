#include "cli/rd.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "cli/console.h"
#include "cli/sequence_files.h"
#include "codecs3d/registry.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "common/parallel.h"
#include "decoder/mesh3d/container_decoder.h"
#include "encoder/mesh3d/codec_encoders.h"
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

std::vector<RdPoint> rd_sweep(const MeshSequence& s, const std::vector<std::string>& codecs, unsigned threads,
                              const std::function<void(const RdPoint&)>& each) {
  const MetricsReference reference(s);
  const double vertex_frames = static_cast<double>(s.vertex_count) * static_cast<double>(s.frames.size());
  std::vector<RdPoint> tried;
  std::vector<std::pair<const Codec3d*, std::string>> settings;  // per point: the codec and its knob's value
  for (const Codec3d* codec : codec_rows(codecs)) {
    const QualityKnob& knob = codec_encoding(*codec).quality;
    for (const std::string& value : knob.coarse_to_fine) {
      std::string parameter = "--" + knob.option + " " + value;
      for (const auto& [name, beside] : knob.beside) parameter += " --" + name + " " + beside;
      tried.push_back({codec->name, parameter});
      settings.emplace_back(codec, value);
    }
  }
  std::vector<std::string> left_out(tried.size());  // why a setting cannot code this sequence
  parallel_for(
      tried.size(), threads,
      [&](size_t k) {
        RdPoint& p = tried[k];
        const auto& [codec, value] = settings[k];
        Encode3dOptions options;
        options.codec = codec->name;
        const QualityKnob& knob = codec_encoding(*codec).quality;
        options.codec_options = knob.beside;
        options.codec_options[knob.option] = value;
        options.hashes = false;
        auto start = std::chrono::steady_clock::now();
        std::vector<uint8_t> stream;
        try {
          stream = encode_mesh3d(s, options).stream;
        } catch (const Error& e) {
          if (e.kind() != ErrorKind::kInput && e.kind() != ErrorKind::kLimit) throw;
          left_out[k] = e.what();
          return;
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
      },
      [&](size_t k) {
        // A setting that cannot code this sequence is left out, and the sweep goes on.
        if (!left_out[k].empty())
          console::say("note: %s %s cannot code this sequence, left out: %s", tried[k].codec.c_str(), tried[k].parameter.c_str(), left_out[k].c_str());
        else
          each(tried[k]);
      });
  std::vector<RdPoint> points;
  for (size_t k = 0; k < tried.size(); ++k)
    if (left_out[k].empty()) points.push_back(tried[k]);
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
    throw usage_error(args.output + ": rd writes .csv or .json (or - for CSV on standard output)");
  const bool json = args.json || extension == ".json";
  refuse_overwriting(args.input, args.output);
  const MeshSequence sequence = load_frames(args.input);
  size_t total = 0;
  for (const Codec3d* codec : codec_rows(args.codecs)) total += codec_encoding(*codec).quality.coarse_to_fine.size();
  console::Progress progress("rate-distortion point", total);
  size_t done = 0;
  const auto start = std::chrono::steady_clock::now();
  const std::vector<RdPoint> points = rd_sweep(sequence, args.codecs, args.threads, [&](const RdPoint& p) {
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
