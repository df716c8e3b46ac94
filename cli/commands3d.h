// The 3D commands of the m4mesh tool.
#pragma once

#include <optional>
#include <string>
#include <utility>

#include "encoder/mesh3d/codec_options.h"
#include "mesh3d/sequence.h"

namespace CLI {
class App;
}

namespace m4mesh {

// What a stream tells besides its frames; an empty codec for a sequence.
struct StreamFacts {
  std::string codec;
  uint64_t bytes = 0;
  bool coding_order = false;  // its vertices numbered in coding order (encode3d --reorder)
};

// A sequence's frames, or a mesh3d stream's decoded frames (read once),
// with the stream's facts in `facts`.
MeshSequence load_sequence_or_stream(const std::string& path, StreamFacts* facts = nullptr);

// The original numbered as `decoded` numbers its vertices: when a stream
// of encode3d --reorder was decoded, in coding order (the encoder's plan of
// the original's faces); an input error when it is not this original's.
MeshSequence original_as_decoded(const MeshSequence& original, const MeshSequence& decoded, bool coding_order, const std::string& decoded_name);

// A usage error when the trace and the stream would share standard output.
void refuse_trace_to_output(bool trace, const std::string& output);
// Before anything is read, usage errors for an output that is an input,
// or that exists without -y (console::check_output).
void refuse_overwriting(const std::string& input, const std::string& output);

// --frames A:B (both included; "A:" to the end, ":B" from the first; empty: all).
std::pair<uint32_t, uint32_t> frame_range(const std::string& text);

struct Encode3dArgs {
  std::string input;
  std::string output;
  std::string codec = "bfs3d";       // or "auto": every codec at the target, the smallest kept
  CodecOptionValues codec_options;  // only those given
  std::optional<double> target_kg, target_psnr;  // a quality target
  bool no_hash = false;
  bool reorder = false;      // vertices renumbered in coding order
  uint32_t hash_group = 16;  // frames per group hash unit; 1: a frame hash unit per frame
  int fps = 25;
  bool trace = false;
  unsigned threads = 0;  // --codec auto: codecs searched at once; 0: every core
};
// Adds --codec, the quality targets and every registered codec's own
// options to `command`.
void add_codec_options(CLI::App& command, Encode3dArgs& args);
int run_encode3d(const Encode3dArgs& args);

struct Decode3dArgs {
  std::string input;
  std::string output;  // a folder of OBJ frames, a .m4seq, .pc2, .ply or .f32 file, or "-"
  std::string format;  // of "-": m4seq or f32
  bool verify = false;
  uint64_t max_bytes = 0;  // decode only the longest prefix of at most this many bytes (0: all)
  std::string frames;      // "A:B": write frames A … B only ("A:", ":B"); empty: all
  bool keep_going = false;  // on an error, keep the frames decoded before it
  bool md5 = false;         // print the MD5 of every frame's binary32 bytes (the output is then optional)
};
int run_decode3d(const Decode3dArgs& args);

int run_info3d(const std::string& input);
// Every element of a 3D stream, as `encode3d --trace` prints them.
int run_trace3d(const std::string& input);

struct MetricsArgs {
  std::string original;
  std::string decoded;
  std::string stream;  // optional: for bits per vertex per frame
  bool json = false;   // one JSON object on standard output
  bool csv = false;    // CSV on standard output
  bool per_frame = false;  // RMSE, max error and PSNR of every frame too
};
int run_metrics(const MetricsArgs& args);

int run_convert(const std::string& input, const std::string& output);

struct ProgressiveArgs {
  std::string stream;
  std::string original;
  uint64_t step = 0;  // bytes between reports (0: a fortieth of the stream)
};
// The quality after every unit of a progressive stream.
int run_progressive(const ProgressiveArgs& args);

}  // namespace m4mesh
