// Quality targets for every 3D codec: the smallest stream whose decoded
// output, measured exactly as `m4mesh metrics` measures it, reaches a KG
// error, a PSNR or a max error. The encoder searches the codec's quality knob (its
// registry row), or uses the codec's own KG search when it has one (an
// option named target-kg); `--codec auto` tries every codec.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "encoder/mesh3d/container_encoder.h"

namespace m4mesh {

// One of the three is set, to a finite number above 0 (check_target).
struct QualityTarget {
  std::optional<double> kg = std::nullopt;         // KG error at most this (percent)
  std::optional<double> psnr = std::nullopt;       // PSNR at least this (dB)
  std::optional<double> max_error = std::nullopt;  // no decoded vertex farther than this from its original (the model's units)
  bool set() const { return kg || psnr || max_error; }
  // Whether a decoding measured so meets the target.
  bool met_by(double trial_kg, double trial_psnr, double trial_max_error) const {
    return kg ? trial_kg <= *kg : psnr ? trial_psnr >= *psnr : trial_max_error <= *max_error;
  }
};

// A usage error unless exactly one target is set, finite and above 0.
void check_target(const QualityTarget& target);

// One encoding tried: the codec, its knob's value ("" for the codec's own
// search), the stream's size and the decoded quality.
struct TargetTrial {
  std::string codec, parameter;
  // Where it was tried ("on a sample of 96 frames", "the whole sequence"),
  // or why a codec was left out (bytes 0, not met).
  std::string note;
  uint64_t bytes = 0;
  double kg = 0, psnr = 0;
  bool meets = false;
  double vertex_frames = 0;  // of the frames coded (a sample's, or the whole sequence's)
  double max_error = 0;

  double bpvf() const { return vertex_frames > 0 ? 8.0 * static_cast<double>(bytes) / vertex_frames : 0; }
};
using TrialReport = std::function<void(const TargetTrial&)>;

// Sequences of more than this many vertex-frames search their setting on
// a sample of their frames (up to kSampleRuns runs of consecutive frames
// spread over the sequence, kSampleVertexFrames in all), then code the
// whole sequence at it once, again finer while the whole misses the
// target: time linear in the sequence's size.
inline constexpr uint64_t kWholeSearchVertexFrames = uint64_t{1} << 20;
inline constexpr uint64_t kSampleVertexFrames = uint64_t{1} << 19;
inline constexpr uint32_t kSampleRuns = 4;

// The frames a large sequence's setting is searched on: runs of at least
// 16 frames (unless fewer fit the sample) spread evenly, in order.
std::vector<uint32_t> sample_frames(uint32_t vertex_count, uint32_t frame_count);

// options.codec at the coarsest knob value that meets the target
// (bisection over the knob's values; the codec's other options as given),
// or at its own search's (an option named target-kg). A usage error when
// even the finest misses it. The stream goes to options.output when set.
Encode3dResult encode_to_target(const FrameSource& frames, const Encode3dOptions& options, const QualityTarget& target,
                                const TrialReport& report);
Encode3dResult encode_to_target(const MeshSequence& sequence, const Encode3dOptions& options, const QualityTarget& target,
                                const TrialReport& report);

// Every registered codec at the target (each codec's best trial reported
// with report_codec); the smallest stream, its codec in `chosen`. A large
// sequence compares the codecs on its sample and codes the whole with
// the smallest.
Encode3dResult encode_smallest(const FrameSource& frames, const Encode3dOptions& options, const QualityTarget& target,
                               const TrialReport& report_codec, std::string& chosen);
Encode3dResult encode_smallest(const MeshSequence& sequence, const Encode3dOptions& options, const QualityTarget& target,
                               const TrialReport& report_codec, std::string& chosen);

}  // namespace m4mesh
