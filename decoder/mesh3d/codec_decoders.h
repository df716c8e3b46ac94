// The decoding halves of the registered 3D codecs (codecs3d/registry.h),
// by codec_id: what the container decoder makes a codec's decoder with.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>

#include "codecs3d/codec_decoder.h"

namespace m4mesh {

// Reads the codec header (after the object header) and makes the decoder.
using MakeDecoder3d = std::function<std::unique_ptr<CodecDecoder3d>(const ObjectHeader&, syntax::ReadIO&)>;

// nullptr for a codec without a decoder.
const MakeDecoder3d* find_decoder3d(uint32_t codec_id);
// The decoder of a codec registered at run time (register_codec3d()).
void register_decoder3d(uint32_t codec_id, MakeDecoder3d make);

}  // namespace m4mesh
