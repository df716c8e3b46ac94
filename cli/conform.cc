#include "cli/conform.h"

#include <filesystem>
#include <iostream>

#include "cli/console.h"
#include "common/error.h"
#include "conformance/suite_files.h"

namespace m4mesh {

namespace {

// The suite when none is given: ./conformance, else the one installed
// beside the tool (PREFIX/share/m4mesh/conformance for PREFIX/bin/m4mesh),
// else the source tree's around a build folder (SOURCE/BUILD/cli/m4mesh).
std::string default_suite() {
  namespace fs = std::filesystem;
  std::error_code ignored;
  const fs::path tool = fs::read_symlink("/proc/self/exe", ignored).parent_path();
  for (const fs::path& folder : {fs::path("conformance"), tool / ".." / "share" / "m4mesh" / "conformance", tool / ".." / ".." / "conformance"})
    if (fs::exists(folder / "manifest.json", ignored)) return folder.lexically_normal().string();
  throw usage_error("no conformance suite in ./conformance or beside the tool: m4mesh conform FOLDER (the folder holding manifest.json)");
}

}  // namespace

int run_conform(ConformOptions options) {
  if (options.suite.empty()) {
    options.suite = default_suite();
    console::say("the suite in %s", options.suite.c_str());
  }
  const ConformResult result = run_conformance(options, std::cout);
  return result.failed == 0 ? 0 : 1;
}

int run_generate_suite(const std::string& folder) {
  console::check_output(folder);
  generate_suites(folder);
  console::say("%s: the 2D suite; %s/mesh3d: the 3D suite; each with streams/ and manifest.json", folder.c_str(), folder.c_str());
  return 0;
}

}  // namespace m4mesh
