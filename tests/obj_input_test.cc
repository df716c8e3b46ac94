// OBJ frame sequences as encoder input.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "common/error.h"
#include "encoder/frame_input.h"
#include "encoder/mesh_object_encoder.h"
#include "mesh/obj.h"
#include "tests/test_util.h"

namespace m4mesh {
namespace {

namespace fs = std::filesystem;

using test::TempDir;

// A 3×2 grid with spacing 0.5 (8 half pixels at scale 16), split '00'.
std::string grid_obj(double shift_y) {
  std::string text = "# grid\n";
  for (int r = 0; r < 2; ++r)
    for (int c = 0; c < 3; ++c)
      text += "v " + std::to_string(c * 0.5) + " " + std::to_string(r * 0.5 + shift_y) + " 0\n";
  text += "f 1 2 5\nf 1 5 4\nf 2/1 3/2 6/3\nf 2 6 5\n";
  return text;
}

TEST(ObjInput, FramesAreReadInNumericOrder) {
  TempDir dir;
  dir.write("f10.obj", grid_obj(0.125));
  dir.write("f2.obj", grid_obj(0.0625));
  dir.write("f1.obj", grid_obj(0));
  dir.write("notes.txt", "not a frame");
  const std::vector<std::string> files = frame_files(dir.path());
  ASSERT_EQ(files.size(), 3u);
  EXPECT_TRUE(files[0].ends_with("f1.obj"));
  EXPECT_TRUE(files[1].ends_with("f2.obj"));
  EXPECT_TRUE(files[2].ends_with("f10.obj"));
  EXPECT_EQ(frame_files(dir.path() + "/f1*.obj").size(), 2u);
  std::vector<std::string> unused;
  frame_files(dir.path(), {".obj"}, &unused);
  ASSERT_EQ(unused.size(), 1u);
  EXPECT_TRUE(unused[0].ends_with("notes.txt"));
}

TEST(ObjInput, ExtensionsInAnyCaseAndNoFrameTwice) {
  TempDir dir;
  dir.write("1.OBJ", grid_obj(0));
  dir.write("2.obj", grid_obj(0.0625));
  EXPECT_EQ(frame_files(dir.path()).size(), 2u);
  dir.write("0001.obj", grid_obj(0));
  try {
    frame_files(dir.path());
    FAIL() << "1.OBJ and 0001.obj are both frame 1";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("are both frame 1"), std::string::npos) << e.what();
  }
}

void expect_input_error(const std::string& path, std::initializer_list<const char*> kinds, const std::string& fragment) {
  try {
    frame_files(path, kinds);
    ADD_FAILURE() << "accepted; expected: " << fragment;
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kInput) << e.what();
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

TEST(ObjInput, FramesOfTwoKindsOrWithoutANumberAreAnError) {
  TempDir mixed;
  for (const char* name : {"0001.obj", "0002.obj", "0003.obj"}) mixed.write(name, grid_obj(0));
  mixed.write("output0001.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  expect_input_error(mixed.path(), {".obj", ".off", ".ply"}, "frames of 2 kinds (0001.obj, output0001.off)");
  EXPECT_EQ(frame_files(mixed.path() + "/*.obj", {".obj", ".off", ".ply"}).size(), 3u);  // a pattern picks one kind
  EXPECT_EQ(frame_files(mixed.path(), {".obj"}).size(), 3u);                             // 2D: the .off is not a frame

  const std::string unnumbered = mixed.path() + "/unnumbered";
  fs::create_directories(unnumbered);
  mixed.write("unnumbered/x.obj", grid_obj(0));
  EXPECT_EQ(frame_files(unnumbered).size(), 1u);  // one frame needs no number
  mixed.write("unnumbered/2.obj", grid_obj(0));
  expect_input_error(unnumbered, {".obj"}, "x.obj: a frame file without a number");
}

TEST(ObjInput, AGridBecomesAUniformMesh) {
  TempDir dir;
  std::vector<ObjFrame> frames{read_obj(dir.write("1.obj", grid_obj(0))), read_obj(dir.write("2.obj", grid_obj(0.0625)))};
  const FrameInput input = planes_from_frames(frames, {"1.obj", "2.obj"}, 16);
  ASSERT_EQ(input.planes.size(), 2u);
  EXPECT_EQ(input.planes[0].info.kind, MeshKind::kUniform);
  EXPECT_EQ(input.planes[0].info.uniform, (UniformParams{3, 2, 8, 8, 0}));
  EXPECT_EQ(input.planes[1].nodes[4], (Point{8, 9}));
  const std::string text = test::decoded_text(encode(input.planes).stream);
  EXPECT_NE(text.find("plane 1 P range=1"), std::string::npos);
}

TEST(ObjInput, AnIrregularMeshBecomesDelaunayWithItsBoundaryLoop) {
  TempDir dir;
  // A square with a centre node, triangulated as a fan: the CDT agrees.
  const std::string square = "v 0 0 0\nv 10 0 0\nv 10 10 0\nv 0 10 0\nv 5 5 0\nf 1 2 5\nf 2 3 5\nf 3 4 5\nf 4 1 5\n";
  std::vector<ObjFrame> frames{read_obj(dir.write("a.obj", square))};
  FrameInput input = planes_from_frames(frames, {"a.obj"}, 2);
  EXPECT_EQ(input.planes[0].info.kind, MeshKind::kDelaunay);
  EXPECT_EQ(input.planes[0].info.boundary, 4u);
  std::vector<std::string> reports;
  EncoderOptions options;
  options.report = [&](const std::string& message) { reports.push_back(message); };
  encode(input.planes, options);
  EXPECT_TRUE(reports.empty());
  // The same square split by one diagonal without the centre's fan: reported.
  const std::string other = "v 0 0 0\nv 10 0 0\nv 10 10 0\nv 0 10 0\nv 5 5 0\nf 1 2 5\nf 2 3 5\nf 3 4 1\nf 3 1 5\n";
  frames = {read_obj(dir.write("b.obj", other))};
  input = planes_from_frames(frames, {"b.obj"}, 2);
  encode(input.planes, options);
  ASSERT_EQ(reports.size(), 1u);
  EXPECT_NE(reports[0].find("the decoder's triangles win"), std::string::npos);
}

TEST(ObjInput, MalformedFilesNameTheLine) {
  TempDir dir;
  const std::pair<std::string, std::string> cases[] = {
      {"v 0 0 0\nv 1 nan 0\n", ":2: non-finite number"},
      {"v 0 0 0\nv 1 inf 0\n", ":2: non-finite number"},
      {"v 0 0\n", ":1: a vertex needs x y z"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", ":4: face index 4 outside 1…3"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n", ":4: malformed face index"},
      {"# nothing\n", ": no vertices"},
  };
  int k = 0;
  for (const auto& [text, fragment] : cases) {
    const std::string path = dir.write("bad" + std::to_string(k++) + ".obj", text);
    try {
      read_obj(path);
      ADD_FAILURE() << "accepted: " << text;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(path + fragment), std::string::npos) << e.what();
    }
  }
}

TEST(ObjInput, ChangingConnectivityIsRejected) {
  TempDir dir;
  ObjFrame a = read_obj(dir.write("1.obj", grid_obj(0)));
  ObjFrame b = a;
  b.vertices.pop_back();
  EXPECT_THROW(planes_from_frames({a, b}, {"1.obj", "2.obj"}, 16), Error);
  b = a;
  std::swap(b.faces[0], b.faces[1]);
  EXPECT_THROW(planes_from_frames({a, b}, {"1.obj", "2.obj"}, 16), Error);
}

}  // namespace
}  // namespace m4mesh
