// The 3D container's framing: start-code emulation prevention, and a
// stream split into its object, units and end code.
#include <gtest/gtest.h>

#include "bitstream/emulation.h"
#include "encoder/mesh3d/container_encoder.h"
#include "syntax/mesh3d/container.h"
#include "tests/test_util.h"

namespace m4mesh {
namespace {

using test::test_sequence;

TEST(Emulation, EscapedPayloadsNeverHoldAStartCodePrefix) {
  test::Random random(1);
  for (int trial = 0; trial < 500; ++trial) {
    std::vector<uint8_t> payload(static_cast<size_t>(random.uniform(0, 64)));
    for (uint8_t& b : payload) b = static_cast<uint8_t>(random.uniform(0, 3) == 0 ? random.uniform(0, 255) : random.uniform(0, 3));
    const std::vector<uint8_t> escaped = escape_payload(payload);
    for (size_t i = 0; i + 2 < escaped.size(); ++i)
      ASSERT_FALSE(escaped[i] == 0 && escaped[i + 1] == 0 && escaped[i + 2] <= 2);
    if (escaped.size() >= 2) {
      ASSERT_FALSE(escaped[escaped.size() - 1] == 0 && escaped[escaped.size() - 2] == 0);
    }
    ASSERT_EQ(unescape_payload(escaped), payload);
  }
  EXPECT_EQ(escape_payload(std::vector<uint8_t>{0, 0, 1}), (std::vector<uint8_t>{0, 0, 3, 1}));
  EXPECT_EQ(escape_payload(std::vector<uint8_t>{0, 0, 3}), (std::vector<uint8_t>{0, 0, 3, 3}));
  EXPECT_EQ(escape_payload(std::vector<uint8_t>{5, 0, 0}), (std::vector<uint8_t>{5, 0, 0, 3}));
  EXPECT_EQ(escape_payload(std::vector<uint8_t>{0, 0, 4}), (std::vector<uint8_t>{0, 0, 4}));
}

TEST(Container, SplitsObjectUnitsAndEndCode) {
  ContainerWriter writer;
  writer.object(std::vector<uint8_t>{1, 2, 0, 0});
  writer.unit(std::vector<uint8_t>{0, 0, 1, 7});
  writer.unit(std::vector<uint8_t>{});
  const std::vector<uint8_t> stream = writer.finish();
  const ContainerParts parts = split_container(stream);
  EXPECT_EQ(parts.object_payload, (std::vector<uint8_t>{1, 2, 0, 0}));
  ASSERT_EQ(parts.units.size(), 2u);
  EXPECT_EQ(parts.units[0].payload, (std::vector<uint8_t>{0, 0, 1, 7}));
  EXPECT_TRUE(parts.has_end_code);
  std::vector<uint8_t> trailing = stream;
  trailing.push_back(9);
  EXPECT_THROW(split_container(trailing), Error);
  std::vector<uint8_t> no_end(stream.begin(), stream.end() - 4);
  EXPECT_FALSE(split_container(no_end).has_end_code);
  EXPECT_THROW(split_container(std::vector<uint8_t>{0, 0, 1, 0xC5}), Error);
}

}  // namespace
}  // namespace m4mesh
