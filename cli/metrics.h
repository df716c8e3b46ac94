// m4mesh metrics and progressive: the field's quality measures between
// two sequences, and after every unit of a progressive stream.
#pragma once

#include <cstdint>
#include <string>

namespace m4mesh {

struct MetricsArgs {
  std::string original;
  std::string decoded;
  std::string stream;  // optional: for bits per vertex per frame
  bool json = false;   // one JSON object on standard output
  bool csv = false;    // CSV on standard output
  bool per_frame = false;  // RMSE, max error and PSNR of every frame too
};
int run_metrics(const MetricsArgs& args);

struct ProgressiveArgs {
  std::string stream;
  std::string original;
  uint64_t step = 0;  // bytes between reports (0: a fortieth of the stream)
};
// The quality after every unit of a progressive stream.
int run_progressive(const ProgressiveArgs& args);

}  // namespace m4mesh
