#include "mesh3d/frame_hash.h"

#include <bit>
#include <cstring>

#include "common/bit_cast.h"
#include "common/md5.h"
#include "common/md5_lanes.h"

namespace m4mesh {

// On a little-endian machine a frame's floats are its canonical bytes already.
constexpr bool kCanonicalInMemory = std::endian::native == std::endian::little;

void append_frame_bytes(std::span<const Float3> positions, std::vector<uint8_t>& out) {
  if constexpr (kCanonicalInMemory) {
    // Copied as they are, with no zeros written first.
    const auto* first = reinterpret_cast<const uint8_t*>(positions.data());
    out.insert(out.end(), first, first + positions.size() * sizeof(Float3));
    return;
  }
  const size_t at = out.size();
  out.resize(at + positions.size() * 12);
  uint8_t* bytes = out.data() + at;
  for (const Float3& p : positions)
    for (float f : p) {
      const uint32_t bits = bit_cast<uint32_t>(f);
      *bytes++ = static_cast<uint8_t>(bits);
      *bytes++ = static_cast<uint8_t>(bits >> 8);
      *bytes++ = static_cast<uint8_t>(bits >> 16);
      *bytes++ = static_cast<uint8_t>(bits >> 24);
    }
}

std::vector<uint8_t> frame_bytes(std::span<const Float3> positions) {
  std::vector<uint8_t> bytes;
  append_frame_bytes(positions, bytes);
  return bytes;
}

Digest frame_digest(std::span<const Float3> positions) {
  Md5 md5;
  if constexpr (kCanonicalInMemory) {
    md5.update(positions.data(), positions.size() * sizeof(Float3));
  } else {
    const std::vector<uint8_t> bytes = frame_bytes(positions);
    md5.update(bytes.data(), bytes.size());
  }
  return md5.digest();
}

void frame_digests(std::span<const std::span<const Float3>> frames, std::span<Digest> out) {
  if constexpr (!kCanonicalInMemory) {
    for (size_t k = 0; k < frames.size(); ++k) out[k] = frame_digest(frames[k]);
    return;
  }
  std::vector<const uint8_t*> starts;
  for (const std::span<const Float3> frame : frames) starts.push_back(reinterpret_cast<const uint8_t*>(frame.data()));
  md5_of_equal_lengths(starts, frames.empty() ? 0 : frames[0].size() * sizeof(Float3), out);
}

Digest group_digest(std::span<const Digest> frame_digests) {
  Md5 md5;
  for (const Digest& d : frame_digests) md5.update(d.data(), d.size());
  return md5.digest();
}

}  // namespace m4mesh
