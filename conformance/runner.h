// `m4mesh conform`: runs every stream of a suite through a decoder.
#pragma once

#include <ostream>
#include <string>

namespace m4mesh {

struct ConformOptions {
  std::string suite;  // folder with manifest.json
  // External decoder, e.g. "mydec {in} {out}" ({method} becomes 1 or 2);
  // empty: m4mesh's own decoder.
  std::string decoder_command;
};

struct ConformResult {
  int passed = 0;
  int failed = 0;
  int skipped = 0;
};

// Prints a table and the last line "N passed, N failed[, N skipped]".
ConformResult run_conformance(const ConformOptions& options, std::ostream& out);

}  // namespace m4mesh
