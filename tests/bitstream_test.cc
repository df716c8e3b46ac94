#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "bitstream/bit_reader.h"
#include "bitstream/bit_writer.h"
#include "bitstream/start_codes.h"
#include "syntax/io.h"
#include "tests/test_util.h"

namespace m4mesh {
namespace {

TEST(BitWriter, WritesMsbFirst) {
  BitWriter w;
  w.write(0b101, 3);
  w.write(0b00001, 5);
  w.write(0xABCD1234, 32);
  EXPECT_EQ(test::bits_of(w.bytes()), "10100001" "10101011" "11001101" "00010010" "00110100");
}

TEST(BitWriter, RefusesUnalignedBytes) {
  BitWriter w;
  w.write(1, 1);
  EXPECT_THROW(w.bytes(), Error);
}

TEST(BitReader, ReadsFieldsOfEverySize) {
  test::Random random(1);
  BitWriter w;
  std::vector<std::pair<uint32_t, int>> fields;
  int total = 0;
  for (int i = 0; i < 2000; ++i) {
    const int n = static_cast<int>(random.next() % 33);
    const uint32_t v = n == 0 ? 0 : static_cast<uint32_t>(random.next()) >> (32 - n);
    fields.push_back({v, n});
    w.write(v, n);
    total += n;
  }
  w.write(0, (8 - total % 8) % 8);
  const std::vector<uint8_t> bytes = w.bytes();
  BitReader r(bytes.data(), bytes.size());
  for (const auto& [v, n] : fields) ASSERT_EQ(r.read(n), v);
  EXPECT_FALSE(r.overrun());
}

TEST(BitReader, OverrunIsStickyAndFeedsZeros) {
  const uint8_t data[2] = {0xFF, 0xFF};
  BitReader r(data, 2);
  EXPECT_EQ(r.read(12), 0xFFFu);
  EXPECT_FALSE(r.overrun());
  EXPECT_EQ(r.bits_left(), 4u);
  EXPECT_EQ(r.read(8), 0xF0u);  // 4 real bits then zeros
  EXPECT_TRUE(r.overrun());
  EXPECT_EQ(r.read(32), 0u);
  EXPECT_TRUE(r.overrun());
  EXPECT_EQ(r.bits_left(), 0u);
}

TEST(BitReader, PeekDoesNotConsumeAndSeekRepositions) {
  const std::vector<uint8_t> data = test::bytes_from_bits("11001010 01010101 11110000");
  BitReader r(data.data(), data.size());
  EXPECT_EQ(r.peek(4), 0b1100u);
  EXPECT_EQ(r.position(), 0u);
  r.skip(3);
  EXPECT_EQ(r.read(7), 0b0101001u);
  r.seek(16);
  EXPECT_EQ(r.read(4), 0b1111u);
  r.seek(1);
  EXPECT_EQ(r.read(2), 0b10u);
}

// §2.2: for every position inside a byte, the stuffing and its check.
TEST(Stuffing, AllEightCases) {
  for (int used = 0; used < 8; ++used) {
    BitWriter w;
    w.write(0, used);
    write_next_start_code(w);
    ASSERT_TRUE(w.byte_aligned());
    const int n = 8 - used;
    std::string expected = std::string(static_cast<size_t>(used), '0') + "0" + std::string(static_cast<size_t>(n - 1), '1');
    EXPECT_EQ(test::bits_of(w.bytes()), expected) << "after " << used << " bits";

    const std::vector<uint8_t> bytes = w.bytes();
    BitReader r(bytes.data(), bytes.size());
    r.skip(used);
    syntax::ReadIO io(r);
    EXPECT_NO_THROW(io.next_start_code());
    EXPECT_TRUE(r.byte_aligned());
  }
}

TEST(Stuffing, BadPatternsAreErrors) {
  for (const char* bits : {"11111111", "00111111", "01111110", "00000000"}) {
    const std::vector<uint8_t> bytes = test::bytes_from_bits(bits);
    BitReader r(bytes.data(), bytes.size());
    syntax::ReadIO io(r);
    try {
      io.next_start_code();
      FAIL() << bits << " accepted";
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::kBadStuffing) << bits;
      EXPECT_EQ(e.bit_offset(), 0);
    }
  }
  // Three stuffing bits after five data bits must be '011'.
  const std::vector<uint8_t> bytes = test::bytes_from_bits("00000 001");
  BitReader r(bytes.data(), bytes.size());
  r.skip(5);
  syntax::ReadIO io(r);
  EXPECT_THROW(io.next_start_code(), Error);
}

// An error names an element read earlier and is placed at its latest start,
// however many names were read (more than the table of recent names holds)
// and whichever copy of a name's text was used.
TEST(ReadIO, ErrorsArePlacedAtTheLatestFieldOfTheirName) {
  constexpr int kNames = 100, kReads = 350;
  std::vector<std::string> texts, copies;
  for (int i = 0; i < kNames; ++i) texts.push_back("field_" + std::to_string(i));
  copies = texts;  // the same texts at other addresses
  const std::vector<uint8_t> bytes(kReads / 8 + 1, 0);
  BitReader r(bytes.data(), bytes.size());
  syntax::ReadIO io(r);
  for (int i = 0; i < kReads; ++i) {
    uint32_t bit = 0;
    io.field((i / kNames % 2 ? copies : texts)[i % kNames].c_str(), 1, bit);
  }
  const auto placed = [&](const char* name) {
    try {
      io.fail(ErrorKind::kOutOfRange, name, "test");
    } catch (const Error& e) {
      return e.bit_offset();
    }
    return int64_t{-1};
  };
  for (int i = 0; i < kNames; ++i) {
    const int latest = (kReads - 1 - i) / kNames * kNames + i;
    EXPECT_EQ(placed(texts[i].c_str()), latest) << texts[i];
    EXPECT_EQ(placed(("field_" + std::to_string(i)).c_str()), latest) << texts[i];
  }
  EXPECT_EQ(placed("never_read"), kReads - 1);  // the element in hand
}

TEST(StartCodes, NextbitsBytealignedLooksAheadWithoutConsuming) {
  const std::vector<uint8_t> data = test::bytes_from_bits("01111111 00000000 00000000 00000001 10111101");
  BitReader r(data.data(), data.size());
  r.skip(8);
  EXPECT_EQ(nextbits_bytealigned(r), kMeshObjectPlaneStartCode);
  EXPECT_EQ(r.position(), 8u);
  r.skip(3);  // unaligned: looks from the next byte boundary
  EXPECT_EQ(nextbits_bytealigned(r), std::nullopt);
  BitReader short_reader(data.data(), 4);
  short_reader.skip(8);
  EXPECT_EQ(nextbits_bytealigned(short_reader), std::nullopt);
}

}  // namespace
}  // namespace m4mesh
