// `m4mesh check`: every violation of the specification in a stream (§11),
// each with its plane, element and bit offset, plus the warnings.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "common/error.h"

namespace m4mesh {

struct Finding {
  bool error;  // false: a warning
  ErrorKind kind;
  int64_t plane;
  std::string element;
  int64_t bit_offset;
  std::string message;
};

struct CheckReport {
  std::vector<Finding> findings;
  int64_t planes = 0;
  bool conformant() const;
  size_t errors() const;
};

CheckReport check_stream(std::span<const uint8_t> stream);

// "error: plane K, ELEMENT at bit N: MESSAGE" (or "warning: …").
std::string format_finding(const Finding& finding);

// Bit offsets of every 23 zero bits followed by a '1' whose '1' lies in [from, to) (§2.3).
std::vector<uint64_t> start_code_emulations(std::span<const uint8_t> stream, uint64_t from, uint64_t to);

}  // namespace m4mesh
