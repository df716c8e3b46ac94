// m4mesh trace, info and check: a 2D or 3D stream element by element,
// plane or unit by unit, and every violation of the specification.
#pragma once

#include <string>

#include "decoder/stream_trace.h"

namespace m4mesh {

// Every syntax element (or those `selection` keeps): bit offset, name, bits, value.
int run_trace(const std::string& input, const TraceSelection& selection);
// Plane by plane (2D) or the headers and units (3D).
int run_info(const std::string& input);
// Every violation, with plane or frame, element and bit; 0 only if conformant.
int run_check(const std::string& input);

}  // namespace m4mesh
