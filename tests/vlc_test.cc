#include <gtest/gtest.h>

#include "bitstream/bit_reader.h"
#include "bitstream/bit_writer.h"
#include "syntax/io.h"
#include "syntax/values.h"
#include "syntax/vlc.h"

namespace m4mesh {
namespace {

bool prefix_free(const std::vector<VlcRow>& rows) {
  for (const VlcRow& a : rows) {
    for (const VlcRow& b : rows) {
      if (&a == &b || a.code.length > b.code.length) continue;
      if ((b.code.bits >> (b.code.length - a.code.length)) == a.code.bits) return false;
    }
  }
  return true;
}

TEST(Vlc, TablesArePrefixFree) {
  EXPECT_TRUE(prefix_free(delta_length_table().rows()));
  EXPECT_TRUE(prefix_free(motion_code_table().rows()));
  std::vector<VlcRow> broken = delta_length_table().rows();
  broken[3].code = parse_code_string("0101");  // '010' is a prefix of it
  EXPECT_FALSE(prefix_free(broken));
  EXPECT_THROW(VlcTable{broken}, std::logic_error);
}

TEST(Vlc, TablesHoldTheSpecificationsSymbols) {
  EXPECT_EQ(delta_length_table().min_symbol(), 0);
  EXPECT_EQ(delta_length_table().max_symbol(), 11);
  EXPECT_EQ(delta_length_table().max_length(), 9);
  EXPECT_EQ(motion_code_table().min_symbol(), -32);
  EXPECT_EQ(motion_code_table().max_symbol(), 32);
  EXPECT_EQ(motion_code_table().max_length(), 13);
  // Spot checks against §4.2: m = 0 is '1'; m = −4 is 000011 then sign 1; m = 32 is 000000000010 then 0.
  EXPECT_EQ(motion_code_table().code(0).bits, 1u);
  EXPECT_EQ(motion_code_table().code(0).length, 1);
  EXPECT_EQ(motion_code_table().code(-4).bits, 0b0000111u);
  EXPECT_EQ(motion_code_table().code(-4).length, 7);
  EXPECT_EQ(motion_code_table().code(32).bits, 0b0000000000100u);
  EXPECT_EQ(motion_code_table().code(32).length, 13);
  EXPECT_EQ(delta_length_table().code(11).bits, 0b111111110u);
}

// Every symbol written then read back, in exactly its code's bit count.
void round_trip_every_symbol(const VlcTable& table) {
  for (int symbol = table.min_symbol(); symbol <= table.max_symbol(); ++symbol) {
    BitWriter w;
    syntax::WriteIO out(w);
    int value = symbol;
    out.vlc("symbol", table, value);
    ASSERT_EQ(static_cast<int>(w.position()), table.code(symbol).length);
    w.write(0, static_cast<int>((8 - w.position() % 8) % 8));
    const std::vector<uint8_t> bytes = w.bytes();
    BitReader r(bytes.data(), bytes.size());
    syntax::ReadIO in(r);
    int decoded = 99;
    in.vlc("symbol", table, decoded);
    EXPECT_EQ(decoded, symbol);
    EXPECT_EQ(static_cast<int>(r.position()), table.code(symbol).length);
  }
}

TEST(Vlc, EverySymbolRoundTrips) {
  round_trip_every_symbol(delta_length_table());
  round_trip_every_symbol(motion_code_table());
}

TEST(Vlc, CodesOutsideTheTablesAreErrors) {
  // Nine '1's: dmv_length 12 … 14, not part of this syntax (§4.1).
  const uint8_t lengths[2] = {0xFF, 0x80};
  BitReader r1(lengths, 2);
  syntax::ReadIO io1(r1);
  int l = 0;
  try {
    io1.vlc("delta_x_len_vlc", delta_length_table(), l);
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kInvalidCode);
    EXPECT_EQ(e.element(), "delta_x_len_vlc");
  }
  // Eleven zeros then anything: no motion code starts like that.
  const uint8_t motion[2] = {0x00, 0x1F};
  BitReader r2(motion, 2);
  syntax::ReadIO io2(r2);
  int8_t m = 0;
  EXPECT_THROW(io2.vlc("delta_mv_x_vlc", motion_code_table(), m), Error);
}

// §4.1 examples.
TEST(Values, DeltaCodesOfTheSpecification) {
  EXPECT_EQ(delta_value({1, 0b0}), -1);
  EXPECT_EQ(delta_value({1, 0b1}), 1);
  EXPECT_EQ(delta_value({2, 0b00}), -3);
  EXPECT_EQ(delta_value({2, 0b01}), -2);
  EXPECT_EQ(delta_value({2, 0b10}), 2);
  EXPECT_EQ(delta_value({2, 0b11}), 3);
  EXPECT_EQ(delta_value({0, 0}), 0);
  for (int v = -2047; v <= 2047; ++v) {
    const DeltaCode code = delta_code(v);
    ASSERT_EQ(delta_value(code), v);
    ASSERT_LE(code.length, 11);
    if (v != 0) {
      ASSERT_EQ(code.bits >> code.length, 0u);
    }
  }
  EXPECT_EQ(delta_code(1023).length, 10);
  EXPECT_EQ(delta_code(-1024).length, 11);
}

// §4.2: every difference of every range codes and decodes to itself.
TEST(Values, MotionDifferencesRoundTripInEveryRange) {
  for (uint32_t code = 1; code <= 3; ++code) {
    const MotionRange range(code);
    EXPECT_EQ(range.low, -32 << (code - 1));
    EXPECT_EQ(range.high, (32 << (code - 1)) - 1);
    for (int d = range.low; d <= range.high; ++d) {
      int16_t m;
      uint16_t res;
      range.code(d, m, res);
      ASSERT_GE(m, -32);
      ASSERT_LE(m, 32);
      ASSERT_LT(res, range.f);
      ASSERT_EQ(range.difference(m, res), d) << "code " << code << " d " << d;
    }
  }
}

TEST(Values, WrappingBothWays) {
  const MotionRange range(2);  // [−64, 63]
  EXPECT_EQ(range.wrap(-65), 63);
  EXPECT_EQ(range.wrap(64), -64);
  EXPECT_EQ(range.wrap(-64), -64);
  EXPECT_EQ(range.wrap(63), 63);
  EXPECT_EQ(smallest_motion_range_code(-32, 31), 1u);
  EXPECT_EQ(smallest_motion_range_code(-33, 0), 2u);
  EXPECT_EQ(smallest_motion_range_code(0, 64), 3u);
  EXPECT_EQ(smallest_motion_range_code(-129, 0), 0u);
}

}  // namespace
}  // namespace m4mesh
