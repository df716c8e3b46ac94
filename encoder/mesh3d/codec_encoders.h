// The encoding halves of the registered 3D codecs (codecs3d/registry.h):
// each codec's options, its quality parameter and its encoder's factory.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "codecs3d/codec_encoder.h"
#include "codecs3d/registry.h"
#include "encoder/mesh3d/codec_options.h"

namespace m4mesh {

// The option that sets a codec's quality, and its values from the coarsest
// to the finest: what a quality target (encoder/mesh3d/quality_target.h)
// searches.
struct QualityKnob {
  std::string option;
  std::vector<std::string> coarse_to_fine;
  CodecOptionValues beside;  // set with the knob in sweeps and searches, unless given
};

using MakeEncoder3d = std::function<std::unique_ptr<CodecEncoder3d>(const FrameSource&, const CodecSettings&)>;

struct CodecEncoding {
  std::vector<CodecOption> options;
  QualityKnob quality;
  MakeEncoder3d make_encoder;
};

// A codec's encoding half; a usage error for a codec without one.
const CodecEncoding& codec_encoding(const Codec3d& codec);
// The encoder of a codec registered at run time (register_codec3d()).
void register_encoder3d(uint32_t codec_id, CodecEncoding encoding);

}  // namespace m4mesh
