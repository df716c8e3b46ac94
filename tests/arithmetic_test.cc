// The adaptive binary arithmetic coder and the sections of a 3D unit:
// bins and residuals round trip, and a section ends exactly.
#include <gtest/gtest.h>

#include "bitstream/arithmetic.h"
#include "common/error.h"
#include "syntax/mesh3d/bfs3d.h"
#include "syntax/mesh3d/entropy_io.h"
#include "syntax/mesh3d/residual.h"
#include "tests/test_util.h"

namespace m4mesh {
namespace {

TEST(Arithmetic, RoundTripsBins) {
  test::Random random(2);
  std::vector<std::pair<int, int>> bins;  // (context, value)
  ArithmeticEncoder encoder;
  std::vector<BinContext> contexts(4);
  for (int i = 0; i < 20000; ++i) {
    const int context = random.uniform(0, 3);
    const int bin = random.uniform(0, 9) < context * 3 ? 1 : 0;
    bins.push_back({context, bin});
    encoder.encode(contexts[context], bin);
  }
  const std::vector<uint8_t> data = encoder.finish();
  EXPECT_LT(data.size(), 20000u / 8);  // skewed bins cost less than a bit each
  ArithmeticDecoder decoder(data);
  std::vector<BinContext> decoding(4);
  for (const auto& [context, bin] : bins) ASSERT_EQ(decoder.decode(decoding[context]), bin);
  EXPECT_EQ(decoder.overrun(), 0u);
  EXPECT_EQ(decoder.position(), data.size());
  ArithmeticDecoder truncated(std::span<const uint8_t>(data).first(data.size() / 2));
  for (const auto& [context, bin] : bins) truncated.decode(decoding[context]);
  EXPECT_GT(truncated.overrun(), 0u);
}

// The decoder renormalizes by at most one byte per bin; the least likely
// bins at both probability limits (128 and 32640 of 32768) must still
// decode.
TEST(Arithmetic, LeastLikelyBinsAtTheProbabilityLimitsRoundTrip) {
  std::vector<int> bins;
  for (int run = 0; run < 40; ++run) {
    const int likely = run % 2;
    bins.insert(bins.end(), 300 + 7 * run, likely);
    bins.insert(bins.end(), 1 + run % 3, 1 - likely);
  }
  ArithmeticEncoder encoder;
  BinContext context;
  for (int bin : bins) encoder.encode(context, bin);
  const std::vector<uint8_t> data = encoder.finish();
  ArithmeticDecoder decoder(data);
  BinContext decoding;
  uint16_t lowest = decoding.p0, highest = decoding.p0;
  for (size_t i = 0; i < bins.size(); ++i) {
    lowest = std::min(lowest, decoding.p0);
    highest = std::max(highest, decoding.p0);
    ASSERT_EQ(decoder.decode(decoding), bins[i]) << "bin " << i;
  }
  EXPECT_EQ(lowest, 128);
  EXPECT_EQ(highest, 32640);
  EXPECT_EQ(decoder.overrun(), 0u);
  EXPECT_EQ(decoder.position(), data.size());
}

// A context moves by 1/8 of the way over its first 16 bins, then
// 1/16, 1/32, and 1/64 from its 49th bin on.
TEST(Arithmetic, WarmUpSlowsEverySixteenBins) {
  BinContext context;
  for (int n = 0; n < 100; ++n) {
    const uint32_t before = context.p0;
    const int bin = n % 5 == 4 ? 1 : 0;
    arithmetic::adapt(context, bin);
    const int shift = n < 16 ? 3 : n < 32 ? 4 : n < 48 ? 5 : 6;
    const uint32_t expected = bin == 0 ? before + ((32768 - before) >> shift) : before - (before >> shift);
    ASSERT_EQ(context.p0, expected) << "bin " << n;
  }
}

// A section one byte short stops the decoding at the first symbol that
// needs the missing byte, not after the section's last symbol: zeros would
// decode on (a fuzzer's 3 KB stream ran through 2^24 vertices).
TEST(Arithmetic, ASectionThatEndsEarlyStopsTheDecodingThere) {
  const syntax::SectionPlace place;
  syntax::EntropyWriteIO<false> writer(place);
  std::vector<BinContext> contexts(2);
  constexpr int kBins = 4000;
  for (int i = 0; i < kBins; ++i) {
    bool bin = i % 7 == 0;
    writer.bin("b", contexts[i % 2], i % 2, bin);
  }
  for (uint32_t i = 0; i < 10; ++i) writer.raw("r", 8, i);
  const std::vector<uint8_t> bins = writer.finish_bins(), raw = writer.finish_raw();
  const std::vector<uint8_t> short_bins(bins.begin(), bins.end() - 1), short_raw(raw.begin(), raw.end() - 1);
  auto stop = [&](bool in_bins) {
    syntax::EntropyReadIO<false> reader(in_bins ? short_bins : bins, in_bins ? raw : short_raw, place);
    std::vector<BinContext> decoding(2);
    int read = 0;
    try {
      for (; read < kBins; ++read) {
        bool bin = false;
        reader.bin("b", decoding[read % 2], read % 2, bin);
      }
      for (uint32_t value = 0; read < kBins + 10; ++read) reader.raw("r", 8, value);
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::kTruncated);
      EXPECT_EQ(e.element(), in_bins ? "bins" : "raw");
      return read;
    }
    return -1;
  };
  const int bins_read = stop(true);
  EXPECT_GT(bins_read, kBins / 2);
  EXPECT_LT(bins_read, kBins);
  EXPECT_EQ(stop(false), kBins + 9);  // the tenth raw byte is missing
}

TEST(Arithmetic, ResidualsOfEverySizeRoundTrip) {
  std::vector<int32_t> values{0, 1, -1, 2, -2, 3, 100, -100, 65535, -65536, (1 << 29), -(1 << 29), (1 << 30) + 7};
  test::Random random(3);
  for (int i = 0; i < 3000; ++i) values.push_back(random.uniform(-3000, 3000) >> random.uniform(0, 10));
  const syntax::SectionPlace place;
  syntax::EntropyWriteIO<false> writer(place);
  syntax::ResidualCoder<3> model;
  for (size_t i = 0; i < values.size(); ++i) {
    int32_t v = values[i];
    model.describe(writer, static_cast<int>(i % 3), v, syntax::kMotionResidual);
  }
  const std::vector<uint8_t> data = writer.finish_bins();
  const std::vector<uint8_t> raw_bytes = writer.finish_raw();
  syntax::EntropyReadIO<false> reader(data, raw_bytes, place);
  syntax::ResidualCoder<3> decoding;
  for (size_t i = 0; i < values.size(); ++i) {
    int32_t r = 0;
    decoding.describe(reader, static_cast<int>(i % 3), r, syntax::kMotionResidual);
    EXPECT_EQ(r, values[i]) << "residual " << i;
  }
  EXPECT_NO_THROW(reader.finish("motion_residual"));
}

// After the last symbol: no bin bytes left over, zero padding, no raw bytes left over.
TEST(Arithmetic, SectionsEndExactly) {
  const syntax::SectionPlace place;
  syntax::EntropyWriteIO<false> writer(place);
  syntax::ResidualCoder<1> model;
  std::vector<int32_t> values{5, -3, 0, 17};
  for (int32_t& v : values) model.describe(writer, 0, v, syntax::kMotionResidual);
  const std::vector<uint8_t> bins = writer.finish_bins(), raw = writer.finish_raw();
  auto decode = [&](const std::vector<uint8_t>& b, const std::vector<uint8_t>& r) {
    syntax::EntropyReadIO<false> reader(b, r, place);
    syntax::ResidualCoder<1> decoding;
    for (int32_t expected : values) {
      int32_t v = 0;
      decoding.describe(reader, 0, v, syntax::kMotionResidual);
      EXPECT_EQ(v, expected);
    }
    reader.finish("motion_residual");
  };
  EXPECT_NO_THROW(decode(bins, raw));
  std::vector<uint8_t> more_bins = bins;
  more_bins.push_back(0);
  EXPECT_THROW(decode(more_bins, raw), Error);
  std::vector<uint8_t> more_raw = raw;
  more_raw.push_back(0);
  EXPECT_THROW(decode(bins, more_raw), Error);
  std::vector<uint8_t> padded = raw;
  padded.back() |= 1;  // the raw bits do not fill their last byte: its last bit is padding
  try {
    decode(bins, padded);
    FAIL() << "nonzero padding accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.element(), "raw_padding");
  }
}

}  // namespace
}  // namespace m4mesh
