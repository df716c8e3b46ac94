// Wavefront OBJ frames (v and f records) and frame sequences.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "mesh/topology.h"

namespace m4mesh {

struct ObjFrame {
  std::vector<std::array<double, 3>> vertices;
  std::vector<Triangle> faces;          // 0-based; polygons are fanned into triangles
  std::vector<uint64_t> vertex_lines;   // the line of each vertex, for errors
};

// Errors name the file and line: malformed records, non-finite numbers,
// face indices out of range.
ObjFrame read_obj(const std::string& path);

// The frame files of a folder (every *.obj, or *.off with that extension,
// in any case: *.OBJ too) or of a pattern with '*', in the numeric order
// of the number in the file name (2.obj before 10.obj); two files of the
// same number (1.obj, 0001.obj) are an input error. A single file is a
// sequence of one frame. `unused` receives a folder's other files.
std::vector<std::string> frame_files(const std::string& folder_or_pattern, const std::string& extension = ".obj",
                                     std::vector<std::string>* unused = nullptr);

}  // namespace m4mesh
