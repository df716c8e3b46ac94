// The §9 decoded-output text: exact format, its MD5, and parsing with errors
// that name the line.
#include <gtest/gtest.h>

#include "common/error.h"
#include "common/md5.h"
#include "encoder/mesh_object_encoder.h"
#include "mesh/decoded_text.h"
#include "tests/test_util.h"

namespace m4mesh {
namespace {

TEST(DecodedText, ExactFormat) {
  std::vector<MeshPlane> planes{uniform_plane(2, 2, 32, 16, 1)};
  std::vector<Point> moved = planes[0].nodes;
  moved[3] = {33, 14};
  planes.push_back(inter_plane(moved));
  const std::string text = test::decoded_text(encode(planes).stream);
  EXPECT_EQ(text,
            "m4mesh-decoded 1\n"
            "plane 0 I uniform cols=2 rows=2 dx=32 dy=16 split=1\n"
            "nodes 4\n0 0\n32 0\n0 16\n32 16\n"
            "triangles 2\n0 1 2\n1 3 2\n"
            "plane 1 P range=1\n"
            "nodes 4\n0 0\n32 0\n0 16\n33 14\n"
            "end\n");
  EXPECT_EQ(md5_hex(text), [&] {
    Md5 md5;
    md5.update(text.substr(0, 10));
    md5.update(text.substr(10));
    return md5.hex_digest();
  }());
  EXPECT_EQ(md5_hex(""), "d41d8cd98f00b204e9800998ecf8427e");
}

TEST(DecodedText, ParseErrorsNameTheLine) {
  const std::string good = "m4mesh-decoded 1\nplane 0 I delaunay boundary=3\nnodes 3\n0 0\n0 10\n10 0\ntriangles 1\n0 1 2\nend\n";
  EXPECT_EQ(parse_decoded_text(good, "in.txt").size(), 1u);
  const std::pair<std::string, std::string> cases[] = {
      {"m4mesh-decoded 2\n", "in.txt:1:"},
      {"m4mesh-decoded 1\nplane 0 P range=1\nnodes 3\n", "in.txt:2:"},
      {"m4mesh-decoded 1\nplane 0 I delaunay boundary=3\nnodes 3\n0 0\n0 x\n", "in.txt:5:"},
      {"m4mesh-decoded 1\nplane 0 I delaunay boundary=3\nnodes 3\n0 0\n0 1e3\n", "in.txt:5:"},
      {"m4mesh-decoded 1\nplane 0 I uniform cols=1 rows=2 dx=1 dy=1 split=0\n", "in.txt:2:"},
      {"m4mesh-decoded 1\nplane 0 I delaunay boundary=3\nnodes 3\n0 0\n0 10\n10 0\ntriangles 1\n0 1 3\n", "in.txt:8:"},
      {good + "extra\n", "in.txt:10:"},
      {"m4mesh-decoded 1\nplane 0 I delaunay boundary=3\nnodes 3\n0 0\n0 10\n10 0\ntriangles 1\n0 1 2\nplane 1 P range=1\nnodes 4\n", "in.txt:10:"},
      {"m4mesh-decoded 1\nplane 0 I delaunay boundary=3\nnodes 3\n0 0\n0 10\n10 0", "in.txt:6:"},
  };
  for (const auto& [text, where] : cases) {
    try {
      parse_decoded_text(text, "in.txt");
      ADD_FAILURE() << "accepted: " << text;
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::kInput);
      EXPECT_EQ(std::string(e.what()).rfind(where, 0), 0u) << e.what();
    }
  }
}

}  // namespace
}  // namespace m4mesh
