// Wavefront OBJ frames (v and f records) and frame sequences.
#pragma once

#include <array>
#include <initializer_list>
#include <string>
#include <vector>

#include "mesh/topology.h"

namespace m4mesh {

struct ObjFrame {
  std::vector<std::array<double, 3>> vertices;
  std::vector<Triangle> faces;          // 0-based; polygons are fanned into triangles
  std::vector<uint64_t> vertex_lines;   // the line of each vertex, for errors
  std::vector<std::string> dropped;     // the kinds of record read past (vt, vn, usemtl, …), each once
};

// "FILE: only CODED are coded; its vt, vn records are left out" for the
// records a frame dropped, or "" when it dropped none.
std::string dropped_records_note(const std::string& file, const std::vector<std::string>& dropped, const std::string& coded);

// Errors name the file and line: malformed records, non-finite numbers,
// face indices out of range.
ObjFrame read_obj(const std::string& path);

// The frame files of a folder or of a pattern with '*', in the numeric
// order of the number in the file name (2.obj before 10.obj). A folder's
// frames are its files of one of `kinds` (extensions, in any case: *.OBJ
// too); files of two kinds are an input error naming one of each, and its
// other files go to `unused`. Several frames must each have a number, and
// two files of the same number (1.obj, 0001.obj) are an input error. A
// single file is a sequence of one frame.
std::vector<std::string> frame_files(const std::string& folder_or_pattern, std::initializer_list<const char*> kinds = {".obj"},
                                     std::vector<std::string>* unused = nullptr);

// A warning when frame_files' numbers skip some of a regular numbering: the
// numbers missing between files whose step exceeds the most common one
// (1, 2, 4, 5: 3 is missing; 0, 3, 6, every third, misses none). Empty
// when none is missing.
std::string numbering_gaps_warning(const std::string& folder_or_pattern, const std::vector<std::string>& files);

}  // namespace m4mesh
