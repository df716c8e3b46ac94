// The encoder of §12 containers: the object header and the codec's header,
// the codec's units (codecs3d/registry.h finds the codec), hash units of
// the frames the codec reports decoded (one per frame, or one per group of
// frames once the group is decoded), the end code.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "codecs3d/codec_encoder.h"
#include "encoder/mesh3d/codec_options.h"
#include "mesh3d/frame_source.h"
#include "mesh3d/sequence.h"
#include "syntax/trace.h"

namespace m4mesh {

struct Encode3dOptions {
  std::string codec = "bfs3d";   // a name of the registry
  CodecOptionValues codec_options;  // the codec's own (encoder/mesh3d/codec_options.h)
  bool hashes = true;            // hash units of the decoded frames
  uint32_t hash_group = 16;      // frames per group hash unit; 1: a frame hash unit (MD5) per frame
  uint32_t frame_rate_num = 25;
  uint32_t frame_rate_den = 1;
  Trace* trace = nullptr;        // every element written, as `m4mesh trace` prints it
  bool keep_decoded = false;     // the decoder's output in the result (a sequence in memory)
  bool measure = false;          // the decoder's output's KG error and PSNR in the result
  bool reorder = false;          // vertices renumbered in coding order (docs/base_mesh.md)
  std::optional<uint32_t> position_blend;  // base meshes' blend (0 … 16); none: each mesh's smallest
  std::function<void(size_t done, size_t total)> progress;
  unsigned threads = 0;  // a search's trials at once (--codec auto, a codec's own search); 0: every core
  // The stream's bytes as they are written (then not kept in the result),
  // and how to drop them when a search codes the sequence again.
  std::function<void(std::span<const uint8_t>)> output;
  std::function<void()> restart_output;
};

struct Encode3dResult {
  std::vector<uint8_t> stream;           // unless written to an output
  uint64_t stream_bytes = 0;
  uint64_t unit_bytes[kUnitTypes] = {};  // per unit_type, start codes included
  uint64_t unit_count[kUnitTypes] = {};
  uint64_t other_bytes = 0;              // object payload and end code
  std::vector<CodecStatistic> statistics;  // the codec's own
  MeshSequence decoded;                    // with keep_decoded: every frame as the decoder outputs it
  double kg = 0, psnr = 0, max_error = 0;  // with measure: of the decoder's output against the input
  std::vector<uint32_t> input_of;          // with reorder: the input number of each output vertex

  uint64_t base_bytes() const { return unit_bytes[static_cast<uint32_t>(UnitType::kBaseMesh)]; }
  uint64_t frame_bytes() const { return unit_bytes[static_cast<uint32_t>(UnitType::kFrame)]; }
};

// An input error unless the sequence can be coded: frames, at least 3
// vertices and a face, within the container's limits, every frame of
// vertex_count finite positions, every face naming vertices that exist
// (FrameSource::scan).
void check_sequence(const MeshSequence& sequence);

// The frames are read as the codec needs them: memory depends on the mesh
// and the codec, not on the frame count (docs/rate_distortion.md, "Scale").
Encode3dResult encode_mesh3d(const FrameSource& frames, const Encode3dOptions& options = {});
Encode3dResult encode_mesh3d(const MeshSequence& sequence, const Encode3dOptions& options = {});

}  // namespace m4mesh
