#include "mesh3d/frame_hash.h"

#include <cstring>

#include "common/md5.h"

namespace m4mesh {

std::vector<uint8_t> frame_bytes(std::span<const Float3> positions) {
  std::vector<uint8_t> bytes(positions.size() * 12);
  uint8_t* out = bytes.data();
  for (const Float3& p : positions)
    for (float f : p) {
      uint32_t bits;
      std::memcpy(&bits, &f, 4);
      *out++ = static_cast<uint8_t>(bits);
      *out++ = static_cast<uint8_t>(bits >> 8);
      *out++ = static_cast<uint8_t>(bits >> 16);
      *out++ = static_cast<uint8_t>(bits >> 24);
    }
  return bytes;
}

Digest frame_digest(std::span<const Float3> positions) {
  const std::vector<uint8_t> bytes = frame_bytes(positions);
  Md5 md5;
  md5.update(bytes.data(), bytes.size());
  return md5.digest();
}

Digest group_digest(std::span<const Digest> frame_digests) {
  Md5 md5;
  for (const Digest& d : frame_digests) md5.update(d.data(), d.size());
  return md5.digest();
}

}  // namespace m4mesh
