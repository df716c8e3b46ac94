// MD5 as RFC 1321 defines it, for builds without OpenSSL (the web build);
// tests/md5_test.cc holds it to OpenSSL's digests.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

namespace m4mesh {

class Md5Rfc1321 {
 public:
  void update(const void* data, size_t size);
  // The 16-byte digest; the object cannot be updated afterwards.
  std::array<uint8_t, 16> digest();

 private:
  void compress(const uint8_t* block);

  std::array<uint32_t, 4> state_ = {0x67452301, 0xefcdab89, 0x98badcfe, 0x10325476};
  std::array<uint8_t, 64> pending_{};
  uint64_t length_ = 0;  // bytes so far
};

}  // namespace m4mesh
