// The value classes a stream exercises, derived from the stream itself
// (so that the manifest cannot claim what a stream does not contain).
#pragma once

#include <cstdint>
#include <set>
#include <span>
#include <string>

#include "mesh/traversal.h"

namespace m4mesh {

// Decodes the stream (it must be valid) and names what it exercises, e.g.
// "split:2", "range:3", "delta_len:7", "mv:low", "wrap:up", "emulation".
std::set<std::string> value_classes(std::span<const uint8_t> stream, MotionMethod method = MotionMethod::kMethod2);

// Every class the suite must cover.
std::set<std::string> required_value_classes();

}  // namespace m4mesh
