// Floating-point text to double, as std::from_chars reads it.
#pragma once

namespace m4mesh {

// Reads a number at `begin` (no leading space, no '+'); returns the end of
// what it read, `begin` when there is no number there. The web build's
// libc++ (Emscripten 3.1.6) has no floating from_chars: there strtod reads
// the same digits, in the C locale that build always runs in.
const char* parse_double(const char* begin, const char* end, double& value);

}  // namespace m4mesh
