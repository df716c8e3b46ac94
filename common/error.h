// The one error type of m4mesh: every failure names its kind, the syntax
// element, the plane and the bit offset (when they apply).
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>

namespace m4mesh {

enum class ErrorKind {
  kTruncated,         // the data ends inside a syntax element
  kMissingStartCode,  // a start code was expected and not found
  kBadStuffing,       // next_start_code() bits are not '0' then '1's
  kReservedValue,     // a value the specification reserves
  kOutOfRange,        // a value outside its allowed range
  kInvalidCode,       // a bit pattern that is not a code of a VLC table
  kTrailingData,      // bytes after the end code
  kGeometry,          // invalid Delaunay geometry (boundary, nodes)
  kStructure,         // plane order (a P-plane first, ...)
  kLimit,             // an implementation limit documented in docs/
  kInput,             // malformed encoder input (text, OBJ)
  kIo,                // file system
  kUsage,             // bad options
};

const char* to_string(ErrorKind kind);

inline constexpr int64_t kNoPlane = -1;
inline constexpr int64_t kNoOffset = -1;
inline constexpr int64_t kNoUnit = -1;

class Error : public std::runtime_error {
 public:
  // what() is "plane K, ELEMENT at bit N: MESSAGE" (parts that do not apply are left out).
  Error(ErrorKind kind, std::string element, int64_t plane, int64_t bit_offset,
        const std::string& message);

  // The same error in a 3D stream, where plane() is a frame: what() is
  // "unit U, frame F, ELEMENT at bit N: MESSAGE" (kNoUnit: outside any unit).
  Error in_mesh3d(int64_t unit) const;

  ErrorKind kind() const { return kind_; }
  const std::string& element() const { return element_; }
  int64_t plane() const { return plane_; }
  int64_t bit_offset() const { return bit_offset_; }
  const std::string& message() const { return message_; }
  bool mesh3d() const { return mesh3d_; }
  int64_t unit() const { return unit_; }

 private:
  Error(ErrorKind kind, std::string element, int64_t plane, int64_t bit_offset, const std::string& message, int64_t unit);

  ErrorKind kind_;
  std::string element_;
  int64_t plane_;
  int64_t bit_offset_;
  std::string message_;
  bool mesh3d_ = false;
  int64_t unit_ = kNoUnit;
};

// An encoder-input or file error that names the file and line.
Error input_error(const std::string& file, int64_t line, const std::string& message);
// Bad options or a bad request of the caller's: no element, plane or offset.
Error usage_error(const std::string& message);

}  // namespace m4mesh
