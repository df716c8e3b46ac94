#include "common/md5.h"

#if M4MESH_OPENSSL
#include <openssl/evp.h>
#else
#include "common/md5_rfc1321.h"
#endif

#include "common/error.h"

namespace m4mesh {

#if M4MESH_OPENSSL
struct Md5::State {
  State() : ctx(EVP_MD_CTX_new()) {
    if (ctx == nullptr || EVP_DigestInit_ex(ctx, EVP_md5(), nullptr) != 1)
      throw Error(ErrorKind::kIo, "", kNoPlane, kNoOffset, "cannot initialise MD5");
  }
  ~State() { EVP_MD_CTX_free(ctx); }
  void update(const void* data, size_t size) { EVP_DigestUpdate(ctx, data, size); }
  std::array<uint8_t, 16> digest() {
    std::array<uint8_t, 16> out{};
    unsigned int length = 0;
    EVP_DigestFinal_ex(ctx, out.data(), &length);
    return out;
  }
  EVP_MD_CTX* ctx;
};
#else
struct Md5::State : Md5Rfc1321 {};
#endif

Md5::Md5() : state_(std::make_unique<State>()) {}

Md5::~Md5() = default;

void Md5::update(std::string_view data) { update(data.data(), data.size()); }

void Md5::update(const void* data, size_t size) { state_->update(data, size); }

std::array<uint8_t, 16> Md5::digest() { return state_->digest(); }

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
