// `m4mesh check`: every violation of the specification in a stream (§11;
// §12 for 3D streams), each with its plane (3D: unit and frame), element
// and bit offset, plus the warnings.
#pragma once

#include <cstdint>
#include <optional>
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
  bool mesh3d = false;          // plane is then the frame
  std::optional<size_t> unit;   // 3D: the unit's index in the stream
};

struct CheckReport {
  std::vector<Finding> findings;
  int64_t planes = 0;
  bool conformant() const;
  size_t errors() const;
};

CheckReport check_stream(std::span<const uint8_t> stream);
// A 3D stream: every unit is decoded, and after an error in one the check
// carries on at the next; `planes` counts the units.
CheckReport check_mesh3d(std::span<const uint8_t> stream);

// "error: plane K, ELEMENT at bit N: MESSAGE" (or "warning: …"); 3D:
// "error: unit U, frame F, ELEMENT at bit N: MESSAGE".
std::string format_finding(const Finding& finding);

// Bit offsets of every 23 zero bits followed by a '1' whose '1' lies in [from, to) (§2.3).
std::vector<uint64_t> start_code_emulations(std::span<const uint8_t> stream, uint64_t from, uint64_t to);

}  // namespace m4mesh
