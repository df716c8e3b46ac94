// The table of 3D codecs: one row per codec_id, with everything the rest
// of m4mesh needs to know of a codec. The container decoder and encoder,
// `info`, the command line's options and the conformance tooling read it;
// nothing else compares codec ids. Adding a codec: docs/architecture.md.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "codecs3d/codec_decoder.h"
#include "codecs3d/codec_encoder.h"
#include "codecs3d/options.h"

namespace m4mesh {

// The option that sets a codec's quality, and its values from the coarsest
// to the finest: what a quality target (encoder/mesh3d/quality_target.h)
// searches.
struct QualityKnob {
  std::string option;
  std::vector<std::string> coarse_to_fine;
  CodecOptionValues beside;  // set with the knob in sweeps and searches, unless given
};

struct Codec3d {
  uint32_t id = 0;  // codec_id
  std::string name;
  std::string summary;
  std::string doc;  // its specification, under docs/
  // The unit types it uses besides frame hash units (any other is an error).
  std::vector<UnitType> unit_types;
  std::vector<CodecOption> options;
  QualityKnob quality;
  // Reads the codec header (after the object header) and makes the decoder.
  std::function<std::unique_ptr<CodecDecoder3d>(const ObjectHeader&, syntax::ReadIO&)> make_decoder;
  std::function<std::unique_ptr<CodecEncoder3d>(const MeshSequence&, const CodecSettings&)> make_encoder;

  bool uses(UnitType type) const;
};

std::span<const Codec3d> codecs3d();
// nullptr for an unregistered id.
const Codec3d* find_codec3d(uint32_t id);
// A usage error lists the registered names.
const Codec3d& codec3d_by_name(const std::string& name);
// Adds a row at run time (a codec of a test); its id must be free.
void register_codec3d(Codec3d codec);

}  // namespace m4mesh
