// Helpers shared by the tests.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "common/random.h"
#include "decoder/mesh3d/container_decoder.h"
#include "mesh/plane.h"
#include "mesh3d/sequence.h"

namespace m4mesh::test {

// Bytes from a string of '0'/'1' (spaces and '|' ignored); the length must be a multiple of 8.
std::vector<uint8_t> bytes_from_bits(std::string_view bits);
// '0'/'1' string of bytes.
std::string bits_of(const std::vector<uint8_t>& bytes);

using Random = SplitMix64;

// Runs `work` on a thread whose affinity is one core (the first of the
// process's): what a process under `taskset -c N` sees. False where the
// system cannot pin a thread.
bool on_one_core(const std::function<void()>& work);

// A folder of the running test's own under the temporary folder, removed with everything in it.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  // `name` inside the folder.
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }
  // Writes `text` to `name` inside the folder; returns its path.
  std::string write(const std::string& name, const std::string& text) const;
  std::string path() const { return path_.string(); }

 private:
  std::filesystem::path path_;
};

// A random star-shaped simple polygon of `boundary` nodes around (512, 512)
// with `interior` distinct nodes strictly inside, in §10 order (node 0
// top-left, boundary counterclockwise).
std::vector<Point> random_polygon_with_interior(uint64_t seed, uint32_t boundary, uint32_t interior,
                                                int32_t min_radius = 150, int32_t max_radius = 500);

// Whether p lies strictly inside the polygon nodes[0 … boundary−1].
bool strictly_inside(const std::vector<Point>& nodes, uint32_t boundary, const Point& p);

// §9 text of a stream's decoding.
std::string decoded_text(const std::vector<uint8_t>& stream);

// Decodes every prefix of a 3D stream (lengths 0, step, 2·step, …) and 300
// copies with one flipped bit, each of which must decode or raise Error;
// returns how many prefixes were rejected.
int decode_damaged_mesh3d(const std::vector<uint8_t>& stream, size_t step, uint64_t seed);

// 3D decoding that compares every hashed frame with its hash unit and
// records the result (hash_result) instead of failing.
inline Decode3dOptions verifying() {
  Decode3dOptions options;
  options.hashes = HashCheck::kRecord;
  return options;
}

// A UV sphere (closed), a separate open sheet, and one isolated vertex, in motion.
MeshSequence test_sequence(int frames, uint64_t seed);

}  // namespace m4mesh::test
