// Variable-length code tables (§4.1, §4.2), kept as data copied from the
// specification. Decoding uses a lookup table built from the same rows the
// encoder writes from.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

namespace m4mesh {

struct VlcCode {
  uint32_t bits;   // the code, right-aligned
  int length;      // in bits
};

// One row of a VLC table: symbol value and code.
struct VlcRow {
  int symbol;
  VlcCode code;
};

class VlcTable {
 public:
  // rows must be prefix-free; symbols must be a contiguous range within int8_t.
  explicit VlcTable(std::vector<VlcRow> rows);

  int max_length() const { return max_length_; }
  int min_symbol() const { return min_symbol_; }
  int max_symbol() const { return max_symbol_; }
  const std::vector<VlcRow>& rows() const { return rows_; }

  bool has_symbol(int symbol) const { return symbol >= min_symbol_ && symbol <= max_symbol_; }
  // The code of a symbol; has_symbol(symbol) must hold.
  const VlcCode& code(int symbol) const { return codes_[symbol - min_symbol_]; }

  // Two bytes, so that the motion table's 8,192 entries stay in the L1 cache.
  struct Match {
    int8_t symbol;
    uint8_t length;  // 0: the bits are not a code of this table
  };
  // Matches the code at the top of `peeked`, which holds max_length() bits.
  Match match(uint32_t peeked) const { return lookup_[peeked]; }

 private:
  std::vector<VlcRow> rows_;
  std::vector<VlcCode> codes_;
  std::vector<Match> lookup_;
  int max_length_ = 0;
  int min_symbol_ = 0;
  int max_symbol_ = 0;
};

// §4.1: delta_x_len_vlc / delta_y_len_vlc, symbols L = 0 … 11.
const VlcTable& delta_length_table();
// §4.2: delta_mv_x_vlc / delta_mv_y_vlc, symbols m = −32 … 32 (sign included).
const VlcTable& motion_code_table();

// The bit strings of the specification's tables, as printed there.
extern const std::array<std::string_view, 12> kDeltaLengthCodeStrings;
extern const std::array<std::string_view, 33> kMotionCodePrefixStrings;

VlcCode parse_code_string(std::string_view bits);

}  // namespace m4mesh
