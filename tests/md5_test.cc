// MD5, the conformance hash: RFC 1321 by hand (the web build's) and the
// SIMD lanes' against OpenSSL's digests.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <string_view>
#include <vector>

#include "common/md5.h"
#include "common/md5_lanes.h"
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

// Digests side by side in SIMD lanes are each message's own, for every
// length across the block and its padding, any count of messages, and
// every width of vectors this processor has (a narrower one takes what a
// wider one leaves).
TEST(Md5, LanesAgreeWithOpenSsl) {
  SplitMix64 random(11);
  for (const int widest_bits : {512, 256, 128, 0}) {
    for (size_t length : {size_t{0}, size_t{1}, size_t{55}, size_t{56}, size_t{63}, size_t{64}, size_t{65}, size_t{119}, size_t{120},
                          size_t{1000}, size_t{12 * 8431}}) {
      for (size_t count = 0; count <= 2 * kMd5Batch + 1; ++count) {
        std::vector<std::string> messages(count);
        std::vector<const uint8_t*> starts;
        for (std::string& m : messages) {
          for (size_t i = 0; i < length; ++i) m += static_cast<char>(random.uniform(-128, 127));
          starts.push_back(reinterpret_cast<const uint8_t*>(m.data()));
        }
        std::vector<std::array<uint8_t, 16>> digests(count);
        md5_of_equal_lengths(starts, length, digests, widest_bits);
        for (size_t k = 0; k < count; ++k) {
          std::string hex;
          for (uint8_t b : digests[k]) hex += "0123456789abcdef"[b >> 4], hex += "0123456789abcdef"[b & 15];
          EXPECT_EQ(hex, md5_hex(messages[k])) << widest_bits << "-bit vectors, length " << length << ", message " << k << " of " << count;
        }
      }
    }
  }
}

}  // namespace
}  // namespace m4mesh
