// The 3D commands of the m4mesh tool.
#pragma once

#include <string>

namespace m4mesh {

struct Encode3dArgs {
  std::string input;
  std::string output;
  std::string codec = "bfs3d";
  int bits = 12;
  bool parallelogram = false;
  double max_error = 1.0;  // affine-octree ME, in percent of the root cube
  int matrix_bits = 16;
  int max_depth = 16;
  int intra_period = 0;
  bool no_hash = false;
  int fps = 25;
};
int run_encode3d(const Encode3dArgs& args);

struct Decode3dArgs {
  std::string input;
  std::string output;  // a folder of OBJ frames, or a .m4seq file
  bool verify = false;
};
int run_decode3d(const Decode3dArgs& args);

int run_info3d(const std::string& input);

struct MetricsArgs {
  std::string original;
  std::string decoded;
  std::string stream;  // optional: for bits per vertex per frame
};
int run_metrics(const MetricsArgs& args);

int run_convert(const std::string& input, const std::string& output);

}  // namespace m4mesh
