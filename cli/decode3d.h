// m4mesh decode3d: a mesh3d stream (or its prefix, or some of its frames)
// to frames in any output form, with their hashes verified.
#pragma once

#include <cstdint>
#include <string>

namespace m4mesh {

struct Decode3dArgs {
  std::string input;
  std::string output;  // a folder of OBJ frames, a .m4seq, .pc2, .ply or .f32 file, or "-"
  std::string format;  // of "-": m4seq or f32
  bool verify = false;
  uint64_t max_bytes = 0;  // decode only the longest prefix of at most this many bytes (0: all)
  std::string frames;      // "A:B": write frames A … B only ("A:", ":B"); empty: all
  bool keep_going = false;  // on an error, keep the frames decoded before it
  bool md5 = false;         // print the MD5 of every frame's binary32 bytes (the output is then optional)
};
int run_decode3d(const Decode3dArgs& args);

}  // namespace m4mesh
