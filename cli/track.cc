#include "cli/track.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <numeric>

#include "cli/console.h"
#include "cli/sequence_files.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "video/track.h"

namespace m4mesh {

namespace {

[[noreturn]] void usage(const std::string& message) { throw usage_error(message); }

std::pair<uint32_t, uint32_t> cell_size(const std::string& text) {
  const size_t x = text.find('x');
  uint32_t w = 0, h = 0;
  const char* end = text.data() + text.size();
  if (x == std::string::npos || std::from_chars(text.data(), text.data() + x, w).ptr != text.data() + x ||
      std::from_chars(text.data() + x + 1, end, h).ptr != end)
    usage("--uniform " + text + ": cells as WxH pixels (16x16)");
  return {w, h};
}

std::string decibels(double value) {
  if (std::isnan(value)) return "";
  if (std::isinf(value)) return "inf";
  char text[32];
  std::snprintf(text, sizeof text, "%.2f", value);
  return text;
}

// A measure over frames 1 … (the first has no motion, and its rendering is
// the texture itself), those that have it (an I-plane has no motion
// compensation): the PSNR of their mean squared error.
double later_psnr(const std::vector<TrackedFrame>& frames, double TrackedFrame::*measure) {
  double error = 0;  // in units of 255²
  size_t count = 0;
  for (size_t f = 1; f < frames.size(); ++f)
    if (!frames[f].intra && !std::isnan(frames[f].*measure)) error += std::pow(10.0, -(frames[f].*measure) / 10), ++count;
  return count == 0 ? std::nan("") : -10 * std::log10(error / static_cast<double>(count));
}

}  // namespace

int run_track(const TrackArgs& args) {
  TrackSettings settings;
  if (!args.uniform.empty() && args.nodes > 0) usage("--uniform and --nodes: one mesh or the other");
  if (!args.uniform.empty()) std::tie(settings.cell_width, settings.cell_height) = cell_size(args.uniform);
  settings.nodes = args.nodes;
  if (args.search < 1 || args.search > 48) usage("--search: 1 … 48 pixels");
  if (args.levels < -1 || args.levels > 4) usage("--levels: 0 … 4");
  settings.tracker.search = args.search;
  settings.tracker.levels = args.levels;
  settings.tracker.reference = args.reference == "previous" ? TrackingReference::kPrevious : TrackingReference::kFirst;
  settings.tracker.border_on_frame = args.border == "frame";
  if (args.remesh != 0 && args.remesh <= 1) usage("--remesh: 0 (never) or a factor above 1 (up to 4, the most a triangle may change)");
  settings.remesh_stretch = args.remesh;
  if (args.block != 0 && (args.block < 2 || args.block > 64)) usage("--block: 2 … 64 pixels");
  settings.block = args.block;
  const auto [first, last] = frame_range(args.frames);
  settings.first_frame = first;
  settings.end_frame = last == UINT32_MAX ? -1 : int64_t{last} + 1;
  for (const std::string* output : {&args.output, &args.texture, &args.report})
    if (!output->empty()) refuse_overwriting(args.input, *output);
  if (!args.mask.empty()) refuse_overwriting(args.mask, args.output);
  Image mask;
  if (!args.mask.empty()) {
    mask = read_png(args.mask);
    settings.mask = &mask;
  }
  console::Progress progress("tracking frame", 0);
  settings.progress = [&](int64_t done, int64_t total) { progress.update(static_cast<size_t>(done), static_cast<size_t>(std::max(done, total))); };

  const TrackResult result = track_video(args.input, settings);
  progress.finish();

  write_file_atomically(args.output, std::string_view(reinterpret_cast<const char*>(result.stream.data()), result.stream.size()));
  if (!args.texture.empty()) {
    char fps[32];
    std::snprintf(fps, sizeof fps, "%.10g", result.video.fps);
    std::vector<std::pair<std::string, std::string>> text;
    if (result.video.fps > 0) text.emplace_back(kFrameRateText, fps);
    if (result.remeshes.empty()) {
      write_png(result.texture, args.texture, text);
    } else {
      // Every I-plane's texture in the one file, tiles row by row (track keeps them within tile_grid()).
      std::vector<const Image*> tiles{&result.texture};
      std::string planes = "0";
      for (const Remesh& remesh : result.remeshes) {
        tiles.push_back(&remesh.texture);
        planes += " " + std::to_string(remesh.plane);
      }
      const TileGrid grid = *tile_grid(tiles.size(), result.texture.width, result.texture.height);
      if (grid.columns > 1) text.emplace_back(kIntraColumnsText, std::to_string(grid.columns));
      text.emplace_back(kIntraPlanesText, planes);
      write_png(tiled(tiles, grid), args.texture, text);
    }
  }
  if (!args.report.empty()) {
    std::string csv = "frame,bits,intra,coverage,stretch,render_psnr,mesh_mc_psnr,block_mc_psnr\n";
    for (const TrackedFrame& f : result.frames) {
      char line[200];
      std::snprintf(line, sizeof line, "%lld,%llu,%d,%.4f,%.3f,%s,%s,%s\n", static_cast<long long>(f.frame), static_cast<unsigned long long>(f.bits), f.intra,
                    f.coverage, f.stretch, decibels(f.render_psnr).c_str(), decibels(f.mesh_psnr).c_str(), decibels(f.block_psnr).c_str());
      csv += line;
    }
    write_file_atomically(args.report, csv);
  }

  for (const std::string& warning : result.warnings) console::say("warning: %s", warning.c_str());
  const VideoInfo& video = result.video;
  const size_t nodes = result.mesh.tracking.nodes.size(), frames = result.frames.size();
  if (video.width != video.coded_width || video.height != video.coded_height)
    console::say("note: %u × %u frames scaled to %u × %u (a mesh covers at most 512 × 512 pixels)", video.coded_width, video.coded_height, video.width,
                 video.height);
  const uint64_t later_bits = std::accumulate(result.frames.begin() + 1, result.frames.end(), uint64_t{0},
                                              [](uint64_t sum, const TrackedFrame& f) { return sum + f.bits; });
  console::say("%s: %zu planes, %zu nodes (%s), %zu bytes; I-plane %llu bits, later planes %.0f bits a frame", args.output.c_str(), frames, nodes,
               result.mesh.plane.info.kind == MeshKind::kUniform ? "uniform" : "content-based Delaunay", result.stream.size(),
               static_cast<unsigned long long>(result.frames.front().bits), frames > 1 ? static_cast<double>(later_bits) / static_cast<double>(frames - 1) : 0.0);
  if (!result.remeshes.empty()) {
    std::string at;
    for (const Remesh& r : result.remeshes) at += (at.empty() ? "" : ", ") + std::to_string(result.frames[r.plane].frame);
    console::say("%zu more I-planes, the mesh laid out again where it degraded: frames %s%s", result.remeshes.size(), at.c_str(),
                 args.texture.empty() ? "" : " (their textures follow the first's in the texture's PNG)");
  }
  double stretch = 1;
  for (const TrackedFrame& f : result.frames) stretch = std::max(stretch, f.stretch);
  console::say("largest change of a triangle's area since its I-plane: %.2f×", stretch);
  const size_t p_planes = static_cast<size_t>(std::count_if(result.frames.begin(), result.frames.end(), [](const TrackedFrame& f) { return !f.intra; }));
  if (frames > 1 && p_planes == 0) {
    console::say("no P-plane: every frame is an I-plane, its own texture");
  } else if (frames > 1) {
    console::say("texture warped by the mesh against the video: %s dB (luma PSNR of the mean squared error of the %zu P-planes of frames %lld … %lld)",
                 decibels(later_psnr(result.frames, &TrackedFrame::render_psnr)).c_str(), p_planes, static_cast<long long>(result.frames[1].frame),
                 static_cast<long long>(result.frames.back().frame));
    console::say("motion compensation from the previous frame: mesh %s dB (%zu vectors), %u × %u blocks %s dB (%u vectors)",
                 decibels(later_psnr(result.frames, &TrackedFrame::mesh_psnr)).c_str(), nodes, result.block, result.block,
                 decibels(later_psnr(result.frames, &TrackedFrame::block_psnr)).c_str(), result.blocks);
  } else {
    console::say("one frame: the mesh object is its texture, with no motion");
  }
  return 0;
}

}  // namespace m4mesh
