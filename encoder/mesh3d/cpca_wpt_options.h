// cpca-wpt's encoder options (encode3d --NAME), declared for the command
// line and checked and typed here: several take "auto" or a number, which
// CodecSettings leaves to the codec.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include "encoder/mesh3d/codec_options.h"

namespace m4mesh::cpca_wpt {

// The noise step's log2 in half steps (2 log2 Δ): the default, and the
// range --noise and the search take.
constexpr int kDefaultNoise = 8, kMinNoise = -8, kMaxNoise = 24;

// Principal components per cluster: the paper's, and the most --components takes.
constexpr size_t kPaperComponents = 40, kMaxComponents = 4096;
// Clusters: the paper's.
constexpr int kPaperClusters = 10;
// The mean shape's quantization bits: the default, and the range --bits takes.
constexpr int kDefaultBits = 12, kMinBits = 4, kMaxBits = 24;

// The most a group grows, in units of --group-bytes: a long download
// keeps being refined at least every 4 first groups' worth of bytes.
constexpr double kMaxGroupGrowth = 4;

// The options as the encoder uses them; none where "auto" lets it choose.
struct Options {
  std::string model;  // shape, trajectory or auto
  std::optional<int> bits, clusters;
  bool round_robin = false;    // --order rpt, else wpt
  std::string basis;           // --basis: index, mesh or auto
  size_t components = 0;       // at most this many per cluster
  std::optional<int> noise;    // log2 of the noise step in half steps
  uint64_t max_bytes = 0;      // 0: every operator
  uint64_t group_bytes = 0;    // the first group's unit closes at about this many bytes; 0: a unit per refinement
  double group_growth = 1;     // each group's bytes this many times the one before's, up to kMaxGroupGrowth × group_bytes
  double target_kg = 0;        // 0: none
  std::optional<uint32_t> segment_frames;  // none: auto
  BaseMeshCoding base_mesh;    // the container's
  unsigned threads = 0;        // the search's candidates, a candidate's clusters at once (0: every core)
};

// The options given, each checked (a usage error names the option).
Options parse_options(const CodecSettings& settings);

}  // namespace m4mesh::cpca_wpt
