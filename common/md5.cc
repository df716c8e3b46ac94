#include "common/md5.h"

#include <openssl/evp.h>

#include "common/error.h"

namespace m4mesh {

Md5::Md5() : ctx_(EVP_MD_CTX_new()) {
  if (ctx_ == nullptr || EVP_DigestInit_ex(ctx_, EVP_md5(), nullptr) != 1)
    throw Error(ErrorKind::kIo, "", kNoPlane, kNoOffset, "cannot initialise MD5");
}

Md5::~Md5() { EVP_MD_CTX_free(ctx_); }

void Md5::update(std::string_view data) { update(data.data(), data.size()); }

void Md5::update(const void* data, size_t size) { EVP_DigestUpdate(ctx_, data, size); }

std::array<uint8_t, 16> Md5::digest() {
  std::array<uint8_t, 16> out{};
  unsigned int length = 0;
  EVP_DigestFinal_ex(ctx_, out.data(), &length);
  return out;
}

std::string Md5::hex_digest() {
  static const char kHex[] = "0123456789abcdef";
  std::string hex;
  for (uint8_t b : digest()) {
    hex += kHex[b >> 4];
    hex += kHex[b & 15];
  }
  return hex;
}

std::string md5_hex(std::string_view data) {
  Md5 md5;
  md5.update(data);
  return md5.hex_digest();
}

}  // namespace m4mesh
