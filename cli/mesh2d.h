// m4mesh encode and decode: §9 text or OBJ frames to a 2D mesh stream, and
// back to §9 text with its MD5.
#pragma once

#include <string>

namespace m4mesh {

struct EncodeArgs {
  std::string input;
  std::string output;
  int method = 2;
  bool keep_order = false;
  bool no_end_code = false;
  bool trace = false;
  double scale = 1.0;
};
int run_encode(const EncodeArgs& args);

struct DecodeArgs {
  std::string input;
  std::string output;
  int method = 2;
  bool md5_only = false;
  bool keep_going = false;
};
int run_decode(const DecodeArgs& args);

}  // namespace m4mesh
