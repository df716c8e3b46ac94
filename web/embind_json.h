// What both WebAssembly modules share (docs/web.md): bytes in from
// JavaScript, every call's JSON answer, an error as
// {"error": {kind, element, plane, unit, offset, message, text}} and never
// a JavaScript exception, and the stream's kind.
#pragma once

#include <emscripten/val.h>

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "bitstream/start_codes.h"
#include "common/error.h"
#include "syntax/mesh3d/container.h"

namespace m4mesh::web {

using emscripten::val;
using json = nlohmann::json;

inline std::vector<uint8_t> bytes_of(const val& array) { return emscripten::convertJSArrayToNumberVector<uint8_t>(array); }

inline json error_json(const Error& e) {
  return {{"kind", to_string(e.kind())}, {"element", e.element()}, {"plane", e.plane()},     {"unit", e.unit()},
          {"offset", e.bit_offset()},    {"mesh3d", e.mesh3d()},   {"message", e.message()}, {"text", e.what()}};
}

inline json internal_error(const char* what) { return {{"kind", "internal"}, {"text", what}}; }

// Runs `make` and returns its JSON; an error becomes {"error": …}.
template <class Make>
std::string guarded(Make&& make) {
  try {
    return make().dump();
  } catch (const Error& e) {
    return json{{"error", error_json(e)}}.dump();
  } catch (const std::exception& e) {
    return json{{"error", internal_error(e.what())}}.dump();
  }
}

// {"kind": "2d" | "3d" | "none"}: which decoder the stream needs, from its
// first four bytes (fewer, or another start: none).
inline std::string stream_kind(const val& bytes) {
  const std::vector<uint8_t> stream = bytes_of(bytes);
  const bool mesh2d = stream.size() >= 4 && stream[0] == 0 && stream[1] == 0 && stream[2] == 1 && stream[3] == (kMeshObjectStartCode & 0xFF);
  return json{{"kind", is_mesh3d_stream(stream) ? "3d" : mesh2d ? "2d" : "none"}}.dump();
}

}  // namespace m4mesh::web
