// Run-time trace of syntax elements: one line per element with its bit
// offset, name, bit count and value. The reader and the writer print the
// same lines for the same stream, so `diff` finds the first divergence.
#pragma once

#include <cstdint>
#include <ostream>
#include <string_view>

namespace m4mesh {

class Trace {
 public:
  explicit Trace(std::ostream& out) : out_(out) {}

  void element(uint64_t offset, std::string_view name, int bits, int64_t value);
  void start_code(uint64_t offset, std::string_view name, uint32_t value);
  void bit_string(uint64_t offset, std::string_view name, int bits, uint32_t value);

 private:
  void prefix(uint64_t offset, std::string_view name, int bits);
  std::ostream& out_;
};

}  // namespace m4mesh
