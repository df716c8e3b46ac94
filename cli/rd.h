// `m4mesh rd`: rate–distortion sweeps of the 3D codecs, each over its
// quality parameter (its registry row, coarse to fine), one row per point.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "mesh3d/sequence.h"

namespace m4mesh {

struct RdPoint {
  std::string codec, parameter;  // parameter: "--bits 12"
  uint64_t bytes = 0;            // the whole stream, without hash units
  double bpvf = 0;               // bits over vertices × frames
  double kg = 0, psnr = 0, rmse = 0, sted = 0;
  double encode_s = 0, decode_s = 0;
};

// Every point of every codec named (all registered ones when empty), in
// order, `threads` points at once (0: every core; the points do not
// depend on it, their times do); `each` hears each point in order once
// measured.
std::vector<RdPoint> rd_sweep(const MeshSequence& sequence, const std::vector<std::string>& codecs, unsigned threads,
                              const std::function<void(const RdPoint&)>& each);

// The points as CSV (a header, then a row per point) or as a JSON array.
std::string rd_csv(const std::vector<RdPoint>& points);
std::string rd_json(const std::vector<RdPoint>& points);

struct RdArgs {
  std::string input;
  std::string output;  // .csv or .json; "-": CSV on standard output
  std::vector<std::string> codecs;  // empty: every codec
  bool json = false;
  unsigned threads = 0;  // points at once; 0: every core
};
int run_rd(const RdArgs& args);

}  // namespace m4mesh
