#include "encoder/mesh3d/cpca_wpt_options.h"

#include <cmath>

#include "common/error.h"
#include "mesh3d/cpca_wpt.h"

namespace m4mesh {

namespace cpca_wpt {

namespace {

// A whole number least … most written in `text`, else a usage error naming the option.
size_t parse_count(const std::string& text, const char* option, size_t most, size_t least = 1) {
  size_t used = 0;
  unsigned long value = 0;
  try {
    value = std::stoul(text, &used);
  } catch (const std::exception&) {
  }
  if (used == 0 || used != text.size() || text[0] == '-' || value < least || value > most)
    throw usage_error(std::string(option) + " is auto or an integer in " + std::to_string(least) + " … " + std::to_string(most) + " (cpca-wpt)");
  return value;
}

// --noise: auto, or a multiple of 0.5 in the search's range.
std::optional<int> parse_noise(const std::string& text) {
  if (text == "auto") return std::nullopt;
  size_t used = 0;
  double value = NAN;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
  }
  if (used != text.size() || !(2 * value >= kMinNoise && 2 * value <= kMaxNoise) || 2 * value != std::floor(2 * value))
    throw usage_error("--noise is auto or a multiple of 0.5 in " + std::to_string(kMinNoise / 2) + " … " + std::to_string(kMaxNoise / 2) +
                      " (cpca-wpt)");
  return static_cast<int>(2 * value);
}

}  // namespace

Options parse_options(const CodecSettings& settings) {
  Options o;
  o.base_mesh = settings.base_mesh();
  o.threads = settings.threads();
  o.model = settings.text("model");
  if (o.model != "shape" && o.model != "trajectory" && o.model != "auto") throw usage_error("--model is shape, trajectory or auto (cpca-wpt)");
  if (settings.text("bits") != "auto") o.bits = static_cast<int>(parse_count(settings.text("bits"), "--bits", kMaxBits, kMinBits));
  if (settings.text("clusters") != "auto")
    o.clusters = static_cast<int>(parse_count(settings.text("clusters"), "--clusters", kCpcaMaxClusters));
  o.max_bytes = static_cast<uint64_t>(settings.number("max-bytes"));
  o.target_kg = settings.number("target-kg");
  if (settings.text("order") != "wpt" && settings.text("order") != "rpt") throw usage_error("--order is wpt or rpt (cpca-wpt)");
  o.round_robin = settings.text("order") == "rpt";
  o.basis = settings.text("basis");
  if (o.basis != "index" && o.basis != "mesh" && o.basis != "auto") throw usage_error("--basis is index, mesh or auto (cpca-wpt)");
  o.components = settings.text("components") == "auto" ? (o.max_bytes > 0 || o.target_kg > 0 ? kMaxComponents : kPaperComponents)
                                                       : parse_count(settings.text("components"), "--components", kMaxComponents);
  o.noise = parse_noise(settings.text("noise"));
  o.group_bytes = static_cast<uint64_t>(settings.number("group-bytes"));
  o.group_growth = settings.number("group-growth");
  if (settings.text("segment-frames") != "auto")
    o.segment_frames = static_cast<uint32_t>(parse_count(settings.text("segment-frames"), "--segment-frames", UINT32_MAX));
  return o;
}

}  // namespace cpca_wpt

std::vector<CodecOption> cpca_wpt_options() {
  return {{"bits", "cpca-wpt: quantization bits of the mean shape (the base mesh), 4 … 24, or auto (12; with --target-kg, from 12 "
                   "towards the neighbour whose planned stream is smaller while it shrinks, then half a bit either side)",
           OptionKind::kText, "auto", 0, 0},
          {"clusters", "cpca-wpt: k, the clusters of k-means on the vertices' trajectories, 1 … 255, or auto (10, the paper's; with "
                       "--target-kg the one of 5, 10, 20 and 40 whose planned stream is smallest, then 0.7 and 1.4 times it, then 2^(±1/4) "
                       "and 2^(±1/8) times it, each if smaller)",
           OptionKind::kText, "auto", 0, 0},
          {"components", "cpca-wpt: at most this many principal components per cluster, 1 … 4096, or auto (40, the paper's, or every "
                         "one for --max-bytes or --target-kg)",
           OptionKind::kText, "auto", 0, 0},
          {"noise", "cpca-wpt: log2 of the quantization step of the coded values in grid units, −4 … 12 in steps of 0.5, or auto (4, "
                    "or the best for --max-bytes or --target-kg)",
           OptionKind::kText, "auto", 0, 0},
          {"basis", "cpca-wpt: how a component's basis values are predicted: index (from the member before in index order, the "
                    "paper's), mesh (by the base mesh's parallelograms, along its traversal) or auto (per component the smaller unit)",
           OptionKind::kText, "auto", 0, 0},
          {"model", "cpca-wpt: the components' space: shape (3 basis values per vertex, 1 coefficient per frame: the paper's), "
                    "trajectory (1 value per vertex, 3 per frame, predicted over the base mesh) or auto (trajectory; with --target-kg the "
                    "one whose planned stream is smallest)",
           OptionKind::kText, "auto", 0, 0},
          {"order", "cpca-wpt: wpt (by squared error removed per bit) or rpt (round robin over the clusters)", OptionKind::kText, "wpt", 0, 0},
          {"max-bytes", "cpca-wpt: the stream's size at most (0: every operator)", OptionKind::kNumber, "0", 0, 1e15},
          {"group-bytes", "cpca-wpt: refinements are sent in groups (unit_kind 4), the first of about this many bytes, the granularity "
                          "of progressive decoding (0: each refinement in a unit of its own)",
           OptionKind::kNumber, "1024", 0, 1e9},
          {"group-growth", "cpca-wpt: each group this many times the bytes of the one before, up to 4 × --group-bytes (1: every group "
                           "of about --group-bytes); later refinements remove less error per byte, so coarser steps cost little",
           OptionKind::kNumber, "1.5", 1, 16},
          {"target-kg", "cpca-wpt: stop at the first operator whose decoded KG error is at most this (0: off)", OptionKind::kNumber, "0", 0,
           100},
          {"segment-frames", "cpca-wpt: frames per segment, each refined by its own units and its components continuing the previous "
                             "segment's, or auto (every frame in one segment up to 2^22 vertex-frames, else as many frames as 2^22 "
                             "vertex-frames hold)",
           OptionKind::kText, "auto", 0, 0}};
}

}  // namespace m4mesh
