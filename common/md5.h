// Incremental MD5 for the conformance hashes of §9: OpenSSL's EVP, or
// RFC 1321 by hand where there is no OpenSSL (the web build).
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>

namespace m4mesh {

class Md5 {
 public:
  Md5();
  ~Md5();
  Md5(const Md5&) = delete;
  Md5& operator=(const Md5&) = delete;

  void update(std::string_view data);
  void update(const void* data, size_t size);
  // The 16-byte digest; the object cannot be updated afterwards.
  std::array<uint8_t, 16> digest();
  // The same as lower-case hex.
  std::string hex_digest();

 private:
  struct State;
  std::unique_ptr<State> state_;
};

std::string md5_hex(std::string_view data);
inline std::string md5_hex(std::span<const uint8_t> bytes) {
  return md5_hex(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

}  // namespace m4mesh
