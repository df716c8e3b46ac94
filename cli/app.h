// The m4mesh command line as a function, for the executable and for tests
// that run it in-process (a codec registered by a test is then on it).
#pragma once

namespace m4mesh {

// Parses and runs one command line; returns the exit status.
int run_m4mesh(int argc, const char* const* argv);

}  // namespace m4mesh
