// The table of 3D codecs: one row per codec_id with what both directions
// know of a codec (name, document, unit types). Each direction keeps its
// own factories beside it: decoder/mesh3d/codec_decoders.h and
// encoder/mesh3d/codec_encoders.h, so that a decode-only program links no
// encoder. Nothing else compares codec ids. Adding a codec:
// docs/architecture.md.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "syntax/mesh3d/container.h"

namespace m4mesh {

// The codec_id of each codec m4mesh implements.
enum Codec3dId : uint32_t { kBfs3dId = 1, kAffineOctreeId = 2, kLccId = 3, kCpcaWptId = 4 };

struct Codec3d {
  uint32_t id = 0;  // codec_id
  std::string name;
  std::string summary;
  std::string doc;  // its specification, under docs/
  // The unit types it uses besides frame hash units (any other is an error).
  std::vector<UnitType> unit_types;

  bool uses(UnitType type) const;
};

std::span<const Codec3d> codecs3d();
// nullptr for an unregistered id.
const Codec3d* find_codec3d(uint32_t id);
// A usage error lists the registered names.
const Codec3d& codec3d_by_name(const std::string& name);
// Adds a row at run time (a codec of a test); its id must be free. Its
// halves are registered with register_decoder3d() and register_encoder3d().
void register_codec3d(Codec3d codec);

}  // namespace m4mesh
