// Incremental MD5 (OpenSSL EVP) for the conformance hashes of §9.
#pragma once

#include <memory>
#include <string>
#include <string_view>

struct evp_md_ctx_st;

namespace m4mesh {

class Md5 {
 public:
  Md5();
  ~Md5();
  Md5(const Md5&) = delete;
  Md5& operator=(const Md5&) = delete;

  void update(std::string_view data);
  void update(const void* data, size_t size);
  // Lower-case hex digest; the object cannot be updated afterwards.
  std::string hex_digest();

 private:
  evp_md_ctx_st* ctx_;
};

std::string md5_hex(std::string_view data);

}  // namespace m4mesh
