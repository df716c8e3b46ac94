#include "bitstream/emulation.h"

namespace m4mesh {

std::vector<uint8_t> escape_payload(std::span<const uint8_t> payload) {
  std::vector<uint8_t> out;
  out.reserve(payload.size() + payload.size() / 64 + 2);
  int zeros = 0;
  for (uint8_t byte : payload) {
    if (zeros >= 2 && byte <= 0x03) {
      out.push_back(0x03);
      zeros = 0;
    }
    out.push_back(byte);
    zeros = byte == 0 ? zeros + 1 : 0;
  }
  if (zeros >= 2) out.push_back(0x03);
  return out;
}

std::vector<uint8_t> unescape_payload(std::span<const uint8_t> escaped) {
  std::vector<uint8_t> out;
  out.reserve(escaped.size());
  int zeros = 0;
  for (uint8_t byte : escaped) {
    if (zeros >= 2 && byte == 0x03) {
      zeros = 0;
      continue;
    }
    out.push_back(byte);
    zeros = byte == 0 ? zeros + 1 : 0;
  }
  return out;
}

}  // namespace m4mesh
