// MD5, the conformance hash: RFC 1321 by hand (the web build's) against
// OpenSSL's digests.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <string_view>

#include "common/md5.h"
#include "common/md5_rfc1321.h"
#include "common/random.h"

namespace m4mesh {
namespace {

// The web build's MD5 (no OpenSSL there) gives OpenSSL's digests: RFC 1321's
// examples, and every length across the 64-byte block and its padding.
TEST(Md5, Rfc1321AgreesWithOpenSsl) {
  const auto rfc = [](std::string_view data, size_t split) {
    Md5Rfc1321 md5;
    md5.update(data.data(), std::min(split, data.size()));
    md5.update(data.data() + std::min(split, data.size()), data.size() - std::min(split, data.size()));
    std::string hex;
    for (uint8_t b : md5.digest()) hex += "0123456789abcdef"[b >> 4], hex += "0123456789abcdef"[b & 15];
    return hex;
  };
  EXPECT_EQ(rfc("", 0), "d41d8cd98f00b204e9800998ecf8427e");
  EXPECT_EQ(rfc("message digest", 3), "f96b697d7cb7938d525a2f31aaf161d0");
  EXPECT_EQ(rfc("12345678901234567890123456789012345678901234567890123456789012345678901234567890", 70), "57edf4a22be3c955ac49da2e2107b67a");
  SplitMix64 random(7);
  std::string data;
  for (size_t length = 0; length <= 300; ++length) {
    EXPECT_EQ(rfc(data, static_cast<size_t>(random.uniform(0, static_cast<int32_t>(length)))), md5_hex(data)) << length;
    data += static_cast<char>(random.uniform(-128, 127));
  }
}

}  // namespace
}  // namespace m4mesh
