#include "syntax/vlc.h"

#include <algorithm>
#include <stdexcept>

namespace m4mesh {

// §4.1, the sprite dmv_length table restricted to L ≤ 11.
const std::array<std::string_view, 12> kDeltaLengthCodeStrings = {
    "00",     "010",     "011",      "100",       "101",        "110",
    "1110",   "11110",   "111110",   "1111110",   "11111110",   "111111110",
};

// §4.2, the motion_code prefixes for |m| = 0 … 32; a sign bit follows for m ≠ 0.
const std::array<std::string_view, 33> kMotionCodePrefixStrings = {
    "1",           "01",          "001",          "0001",         "000011",
    "0000101",     "0000100",     "0000011",      "000001011",    "000001010",
    "000001001",   "0000010001",  "0000010000",   "0000001111",   "0000001110",
    "0000001101",  "0000001100",  "0000001011",   "0000001010",   "0000001001",
    "0000001000",  "0000000111",  "0000000110",   "0000000101",   "0000000100",
    "00000000111", "00000000110", "00000000101",  "00000000100",  "00000000011",
    "00000000010", "000000000011", "000000000010",
};

VlcCode parse_code_string(std::string_view bits) {
  VlcCode code{0, 0};
  for (char c : bits) {
    if (c != '0' && c != '1') throw std::logic_error("VLC string with a character other than 0/1");
    code.bits = (code.bits << 1) | static_cast<uint32_t>(c == '1');
    ++code.length;
  }
  return code;
}

VlcTable::VlcTable(std::vector<VlcRow> rows) : rows_(std::move(rows)) {
  auto [lo, hi] = std::minmax_element(rows_.begin(), rows_.end(),
                                      [](const VlcRow& a, const VlcRow& b) { return a.symbol < b.symbol; });
  min_symbol_ = lo->symbol;
  max_symbol_ = hi->symbol;
  if (static_cast<size_t>(max_symbol_ - min_symbol_ + 1) != rows_.size())
    throw std::logic_error("VLC symbols are not a contiguous range");
  if (min_symbol_ < INT8_MIN || max_symbol_ > INT8_MAX) throw std::logic_error("VLC symbols outside int8_t");
  codes_.resize(rows_.size());
  for (const VlcRow& row : rows_) {
    codes_[row.symbol - min_symbol_] = row.code;
    max_length_ = std::max(max_length_, row.code.length);
  }
  lookup_.assign(size_t{1} << max_length_, Match{0, 0});
  for (const VlcRow& row : rows_) {
    int free_bits = max_length_ - row.code.length;
    uint32_t first = row.code.bits << free_bits;
    for (uint32_t tail = 0; tail < (1u << free_bits); ++tail) {
      Match& slot = lookup_[first | tail];
      if (slot.length != 0) throw std::logic_error("VLC table is not prefix-free");
      slot = Match{static_cast<int8_t>(row.symbol), static_cast<uint8_t>(row.code.length)};
    }
  }
}

const VlcTable& delta_length_table() {
  static const VlcTable table = [] {
    std::vector<VlcRow> rows;
    for (size_t length = 0; length < kDeltaLengthCodeStrings.size(); ++length)
      rows.push_back({static_cast<int>(length), parse_code_string(kDeltaLengthCodeStrings[length])});
    return VlcTable(std::move(rows));
  }();
  return table;
}

const VlcTable& motion_code_table() {
  static const VlcTable table = [] {
    std::vector<VlcRow> rows;
    rows.push_back({0, parse_code_string(kMotionCodePrefixStrings[0])});
    for (int magnitude = 1; magnitude <= 32; ++magnitude) {
      VlcCode prefix = parse_code_string(kMotionCodePrefixStrings[magnitude]);
      for (int negative = 0; negative <= 1; ++negative) {
        VlcCode code{(prefix.bits << 1) | static_cast<uint32_t>(negative), prefix.length + 1};
        rows.push_back({negative ? -magnitude : magnitude, code});
      }
    }
    return VlcTable(std::move(rows));
  }();
  return table;
}

}  // namespace m4mesh
