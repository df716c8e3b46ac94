// `m4mesh conform`: runs every stream of a suite (2D or 3D, from its
// manifest's kind) through m4mesh's decoder or an external one.
#pragma once

#include <ostream>
#include <string>

namespace m4mesh {

struct ConformOptions {
  std::string suite;  // folder with manifest.json
  // External decoder, e.g. "mydec {in} {out}": {in} is the stream, {out}
  // the file to write (2D: the §9 text; 3D: every frame's binary32 bytes,
  // as decode3d -o FILE.f32), {method} 1 or 2 (2D). Each is single-quoted
  // for the shell; the command's own redirections are left alone. Empty:
  // m4mesh's own decoder. A command without {in} and {out} is a usage error.
  std::string decoder_command;
  // Seconds an external decoder may take on one stream: then it is killed
  // (its process group) and the stream fails.
  double timeout_seconds = 120;
  // After the table: what the suite's valid streams reach of the catalog
  // of normative items (conformance/coverage.h, coverage3d.h), and what not.
  bool coverage = false;
};

struct ConformResult {
  int passed = 0;
  int failed = 0;
  int skipped = 0;
};

// Prints a table and the last line "N passed, N failed[, N skipped]". A
// run passes when no stream failed: a skipped stream (Method I, which the
// specification makes informative, without {method}) is counted, not
// failed.
ConformResult run_conformance(const ConformOptions& options, std::ostream& out);

}  // namespace m4mesh
