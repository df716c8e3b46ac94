// `m4mesh serve`: the web site (the player and the analyzer, docs/web.md)
// or a folder with its own index.html, over HTTP on loopback by default;
// given streams (.m4m files, or folders of them without a page), the site
// with those streams listed in its player.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace m4mesh {

struct ServeOptions {
  std::vector<std::string> paths;  // none: the site built beside the tool; a folder with index.html; or streams
  std::string host = "127.0.0.1";
  int port = 8080;               // 0: any free port (printed)
  uint64_t rate = 0;             // bytes per second of each .m4m response (0: unthrottled), to watch progressive streams arrive
};

// Serves until the process is stopped; returns the exit status.
int run_serve(const ServeOptions& options);

}  // namespace m4mesh
