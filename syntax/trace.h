// Run-time trace of syntax elements: one line per element with its bit
// offset, name, bit count and value. The reader and the writer print the
// same lines for the same stream, so `diff` finds the first divergence.
// 3D lines start with their location ("unit 7 frame 3") and count offsets
// from the unit's start code; symbols of an arithmetic-coded section are
// placed by section and index ("bins_x:17"), raw bits by section and bit.
#pragma once

#include <cstdint>
#include <optional>
#include <ostream>
#include <span>
#include <string>
#include <string_view>

namespace m4mesh {

class Trace {
 public:
  explicit Trace(std::ostream& out) : out_(out) {}
  // A trace into `out` with the location and selection of `like`.
  Trace(std::ostream& out, const Trace& like)
      : out_(out),
        location_(like.location_),
        offset_base_(like.offset_base_),
        part_(like.part_),
        only_part_(like.only_part_),
        symbols_(like.symbols_) {}

  // A stream's parts, traced one at a time: the 3D object header (−1) and
  // unit k (k), the end code (kEndPart); the 2D mesh object (−1) and plane
  // k, which runs to the next plane start code. Prints only part `part`.
  static constexpr int64_t kEndPart = INT64_MAX;
  void only_part(int64_t part) { only_part_ = part; }
  // The part the decoder or encoder is in.
  int64_t part() const { return part_; }
  // Prints fixed fields and byte sections only, no bins and raw bits.
  void without_symbols() { symbols_ = false; }

  // Starts a 3D payload (or the end code, with no payload): its part, its
  // location and its start code at offset 0; the payload's offsets count from bit 32.
  void begin_payload(int64_t part, std::string location, std::string_view start_code_name, uint32_t code) {
    part_ = part;
    location_ = std::move(location);
    offset_base_ = 0;
    start_code(0, start_code_name, code);
    offset_base_ = 32;
  }
  std::ostream& stream() { return out_; }
  // A trace into the same output placed in the 3D object payload, for a
  // header's section read while a unit is decoded.
  Trace in_object() {
    Trace t(out_, *this);
    t.part_ = -1;
    t.location_ = "object";
    t.offset_base_ = 32;
    return t;
  }

  void element(uint64_t offset, std::string_view name, int bits, int64_t value);
  // A binary32 field: its bit pattern, then its value in parentheses.
  void binary32(uint64_t offset, std::string_view name, uint32_t bits);
  void start_code(uint64_t offset, std::string_view name, uint32_t value);
  void bit_string(uint64_t offset, std::string_view name, int bits, uint32_t value);
  // A byte section: its length, and its bytes in hex when it holds at most 16.
  void bytes(uint64_t offset, std::string_view name, std::span<const uint8_t> data);
  // An arithmetic-coded bin: its section, index there, context number and value.
  void bin(std::string_view section, uint64_t index, std::string_view name, int context, int value);
  // Raw bits: the section, the bit offset in it, the count and the value.
  void raw(std::string_view section, uint64_t bit, std::string_view name, int bits, int64_t value);

 private:
  bool shown() const { return !only_part_ || *only_part_ == part_; }
  void prefix(std::string_view position, std::string_view name, std::string_view size);
  void prefix(uint64_t offset, std::string_view name, int bits);
  std::ostream& out_;
  std::string location_;
  uint64_t offset_base_ = 0;
  int64_t part_ = -1;
  std::optional<int64_t> only_part_;
  bool symbols_ = true;
};

// One line of a trace read back (tools and tests): for a 3D line its unit
// (−1 for the object and the end code) and frame (−1 outside a unit), then
// the position ("144", or "bins:17" inside a section), the name, the size
// ("32", "b" for a bin, "B" for a byte section) and the value as printed;
// for a bin, its context.
struct TraceLine {
  int64_t unit = -1;
  int64_t frame = -1;
  std::string position;
  std::string name;
  std::string size;
  std::string value;
  int context = -1;

  bool bin() const { return size == "b"; }
  // Whether `value` is a number (not a start code, a bit string or bytes).
  bool numeric() const { return size != "B" && !value.starts_with("0x") && !value.starts_with("'"); }
};

// Nothing for a line that is not one Trace printed.
std::optional<TraceLine> parse_trace_line(const std::string& line);

}  // namespace m4mesh
