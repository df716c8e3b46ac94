// Sequence files: OBJ, OFF and the binary .m4seq agree; PC2 with the OBJ
// beside it; the cloth flag of ../shared/data.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "common/bit_cast.h"
#include "common/error.h"
#include "mesh3d/sequence.h"
#include "tests/test_util.h"

namespace m4mesh {
namespace {

namespace fs = std::filesystem;

using test::test_sequence;

TEST(SequenceFiles, ObjOffAndBinaryAgree) {
  const fs::path dir = fs::temp_directory_path() / "m4mesh-seq-test";
  fs::remove_all(dir);
  const MeshSequence s = test_sequence(3, 10);
  write_obj_frames(s, (dir / "obj").string());
  const MeshSequence from_obj = load_sequence((dir / "obj").string());
  EXPECT_EQ(from_obj.faces, s.faces);
  ASSERT_EQ(from_obj.frames.size(), 3u);
  EXPECT_NEAR(from_obj.frames[2][5].x, s.frames[2][5].x, 1e-8);
  write_binary_sequence(from_obj, (dir / "s.m4seq").string());
  const MeshSequence binary = load_sequence((dir / "s.m4seq").string());
  EXPECT_EQ(binary.faces, s.faces);
  EXPECT_EQ(binary.frames[1][3].y, static_cast<double>(static_cast<float>(from_obj.frames[1][3].y)));
  std::ofstream(dir / "a1.off") << "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n";
  std::ofstream(dir / "a2.off") << "OFF\n# moved\n4 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n4 0 1 2 3\n";
  std::ofstream(dir / "a10.off") << "OFF\n3 1 0\n0 0 0\n1 0 0\n1 1 0\n3 0 1 2\n";
  try {
    load_sequence((dir / "a*.off").string());
    ADD_FAILURE() << "a changed vertex count was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("a10.off"), std::string::npos) << e.what();
  }
  fs::remove(dir / "a10.off");
  const MeshSequence off = load_sequence((dir / "a*.off").string());
  EXPECT_EQ(off.frames.size(), 2u);
  EXPECT_EQ(off.faces.size(), 2u);
  EXPECT_EQ(off.frames[1][2].z, 1.0);
  fs::remove_all(dir);
}

// A PC2 file of `samples` frames of `points` points: point i of frame f at (i, f, 0.5).
std::string pc2_bytes(uint32_t points, uint32_t samples, const char* signature = "POINTCACHE2") {
  std::string out(signature, 11);
  out += '\0';
  auto put = [&](uint32_t v) {
    for (int i = 0; i < 4; ++i) out += static_cast<char>((v >> (8 * i)) & 0xFF);
  };
  auto put_float = [&](float f) { put(bit_cast<uint32_t>(f)); };
  put(1);
  put(points);
  put_float(0);
  put_float(25);
  put(samples);
  for (uint32_t f = 0; f < samples; ++f)
    for (uint32_t i = 0; i < points; ++i) {
      put_float(static_cast<float>(i));
      put_float(static_cast<float>(f));
      put_float(0.5f);
    }
  return out;
}

TEST(SequenceFiles, Pc2WithTheObjBesideIt) {
  const fs::path dir = fs::temp_directory_path() / "m4mesh-pc2-test";
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "sheet.obj") << "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n";
  std::ofstream(dir / "sheet.pc2", std::ios::binary) << pc2_bytes(4, 3);
  const MeshSequence s = load_sequence((dir / "sheet.pc2").string());
  EXPECT_EQ(s.vertex_count, 4u);
  EXPECT_EQ(s.faces.size(), 2u);
  ASSERT_EQ(s.frames.size(), 3u);
  EXPECT_EQ(s.frames[2][3], (Vec3{3, 2, 0.5}));
  auto rejected = [&](const std::string& bytes, const char* words) {
    std::ofstream(dir / "sheet.pc2", std::ios::binary | std::ios::trunc) << bytes;
    try {
      load_sequence((dir / "sheet.pc2").string());
      ADD_FAILURE() << "accepted: " << words;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
  };
  rejected(pc2_bytes(5, 3), "5 points where");
  rejected(pc2_bytes(4, 3).substr(0, 60), "truncated PC2");
  rejected(pc2_bytes(4, 3, "POINTCACHE3"), "not a PC2 file");
  rejected(pc2_bytes(4, 3) + "x", "bytes after the last sample");
  std::string huge = pc2_bytes(4, 1);
  huge[28] = '\x7f';  // a sample count of about 2^31 with one sample's data: refused before allocating
  rejected(huge, "truncated PC2");
  fs::remove(dir / "sheet.obj");
  rejected(pc2_bytes(4, 3), "which is missing");
  fs::remove_all(dir);
}

const fs::path kData = fs::path(M4MESH_SOURCE_DIR) / ".." / "shared" / "data";

TEST(RealData, ClothFlagPc2) {
  if (!fs::exists(kData / "cloth" / "flag")) GTEST_SKIP() << "../shared/data/cloth/flag is absent";
  const MeshSequence flag = load_sequence((kData / "cloth" / "flag" / "flag.pc2").string());
  EXPECT_EQ(flag.vertex_count, 4225u);
  EXPECT_EQ(flag.faces.size(), 8192u);
  EXPECT_EQ(flag.frames.size(), 300u);
  const MeshSequence obj = load_sequence((kData / "cloth" / "flag" / "flag.obj").string());
  for (uint32_t i = 0; i < flag.vertex_count; ++i)
    ASSERT_EQ(flag.frames[0][i].x, static_cast<double>(static_cast<float>(obj.frames[0][i].x))) << "vertex " << i;
}

}  // namespace
}  // namespace m4mesh
