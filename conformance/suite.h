// The 2D conformance suite generator: every stream of conformance/streams,
// built deterministically so that the committed suite can be regenerated.
// SuiteCase is the case of both suites (conformance/suite3d/suite3d.h).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "common/error.h"
#include "mesh/plane.h"
#include "mesh/traversal.h"

namespace m4mesh {

struct SuiteCase {
  std::string id;
  std::string purpose;
  std::vector<std::string> clauses;  // specification clauses exercised
  std::vector<uint8_t> stream;
  MotionMethod method = MotionMethod::kMethod2;  // 2D: the motion vector prediction it needs
  bool valid = true;
  // Negative streams: what a decoder must report (3D: the frame as the plane).
  ErrorKind error_kind = ErrorKind::kTruncated;
  std::string error_element;
  int64_t error_plane = kNoPlane;
  std::string encoder_trace;  // 3D, when built with traces: what the encoder printed while writing it
  bool written = false;       // 3D: units written symbol by symbol, not by the encoder: no encoder trace
};

// A case to decode, and one to reject with the error a decoder must report.
SuiteCase decode_case(std::string id, std::string purpose, std::vector<std::string> clauses, std::vector<uint8_t> stream);
SuiteCase reject_case(std::string id, std::string purpose, std::vector<std::string> clauses, std::vector<uint8_t> stream, ErrorKind kind,
                      std::string element, int64_t plane);

// The cases in groups: uniform, Delaunay, rejected.
std::vector<SuiteCase> build_suite();

// Shapes of the suite that the tests use too.
std::vector<Point> comb_boundary();    // a comb: notches cut up from the bottom
std::vector<Point> spiral_boundary();  // a square spiral corridor, 20 wide
// The 3×3 uniform mesh and two P-planes of tests/hand_stream_test.cc.
std::vector<MeshPlane> hand_stream_planes();
// A uniform mesh whose P-plane puts vectors at low and high of motion_range_code `code`.
std::vector<MeshPlane> range_limit_planes(uint32_t code);
// A P-plane (range `code`) whose neighbouring vectors make the differences wrap both ways.
std::vector<MeshPlane> wrap_planes(uint32_t code);

}  // namespace m4mesh
