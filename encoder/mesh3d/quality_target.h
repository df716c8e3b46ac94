// Quality targets for every 3D codec: the smallest stream whose decoded
// output, measured exactly as `m4mesh metrics` measures it, reaches a KG
// error or a PSNR. The encoder searches the codec's quality knob (its
// registry row), or uses the codec's own KG search when it has one (an
// option named target-kg); `--codec auto` tries every codec.
#pragma once

#include <functional>
#include <optional>
#include <string>

#include "encoder/mesh3d/container_encoder.h"

namespace m4mesh {

// One of the two is set, to a finite number above 0 (check_target).
struct QualityTarget {
  std::optional<double> kg = std::nullopt;    // KG error at most this (percent)
  std::optional<double> psnr = std::nullopt;  // PSNR at least this (dB)
  bool set() const { return kg || psnr; }
};

// A usage error unless exactly one target is set, finite and above 0.
void check_target(const QualityTarget& target);

// One encoding tried: the codec, its knob's value ("" for the codec's own
// search), the stream's size and the decoded quality.
struct TargetTrial {
  std::string codec, parameter;
  uint64_t bytes = 0;
  double kg = 0, psnr = 0;
  bool meets = false;
};
using TrialReport = std::function<void(const TargetTrial&)>;

// options.codec at the coarsest knob value that meets the target
// (bisection over the knob's values; the codec's other options as given).
// A usage error when even the finest misses it.
Encode3dResult encode_to_target(const MeshSequence& sequence, const Encode3dOptions& options, const QualityTarget& target,
                                const TrialReport& report);

// Every registered codec at the target (each codec's best trial reported
// with report_codec); the smallest stream, its codec in `chosen`.
Encode3dResult encode_smallest(const MeshSequence& sequence, const Encode3dOptions& options, const QualityTarget& target,
                               const TrialReport& report_codec, std::string& chosen);

}  // namespace m4mesh
