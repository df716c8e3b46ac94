// The conformance suite generator: every stream of conformance/streams,
// built deterministically so that the committed suite can be regenerated.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "common/error.h"
#include "mesh/traversal.h"

namespace m4mesh {

struct SuiteCase {
  std::string id;
  std::string purpose;
  std::vector<std::string> clauses;  // specification clauses exercised
  std::vector<uint8_t> stream;
  MotionMethod method = MotionMethod::kMethod2;
  bool valid = true;
  // Negative streams: what a decoder must report.
  ErrorKind error_kind = ErrorKind::kTruncated;
  std::string error_element;
  int64_t error_plane = kNoPlane;
};

std::vector<SuiteCase> build_suite();

}  // namespace m4mesh
