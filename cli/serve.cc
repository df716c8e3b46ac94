#include "cli/serve.h"

#include <httplib.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <thread>

#include "cli/console.h"
#include "common/error.h"

namespace m4mesh {

namespace fs = std::filesystem;

namespace {

// The site the build assembles (BUILD/web/site for BUILD/cli/m4mesh), or
// the one installed beside the tool (PREFIX/share/m4mesh/site).
fs::path default_site() {
  std::error_code ignored;
  const fs::path tool = fs::read_symlink("/proc/self/exe", ignored).parent_path();
  for (const fs::path& folder : {tool / ".." / "web" / "site", tool / ".." / "share" / "m4mesh" / "site"})
    if (fs::exists(folder / "index.html", ignored)) return fs::weakly_canonical(folder);
  throw usage_error("no web site beside the tool: build it (cmake --build build: it needs Emscripten and web/node_modules, see docs/web.md) or name a FOLDER");
}

const char* content_type(const fs::path& file) {
  static const std::map<std::string, const char*> kTypes = {
      {".html", "text/html; charset=utf-8"}, {".js", "text/javascript"},  {".mjs", "text/javascript"},   {".css", "text/css"},
      {".json", "application/json"},         {".wasm", "application/wasm"}, {".png", "image/png"},       {".jpg", "image/jpeg"},
      {".gif", "image/gif"},                 {".svg", "image/svg+xml"},   {".txt", "text/plain; charset=utf-8"}, {".md", "text/plain; charset=utf-8"}};
  const auto it = kTypes.find(file.extension().string());
  return it == kTypes.end() ? "application/octet-stream" : it->second;
}

// The file a request path names inside `root`; empty when it names none
// (or lies outside: "..", links out of the folder).
fs::path file_for(const fs::path& root, const std::string& request_path) {
  fs::path relative = fs::path(request_path).relative_path().lexically_normal();
  if (relative.empty() || relative == ".") relative = "index.html";
  if (*relative.begin() == "..") return {};
  std::error_code error;
  fs::path file = fs::weakly_canonical(root / relative, error);
  if (!error && fs::is_directory(file, error)) file /= "index.html";
  const auto [end, _] = std::mismatch(root.begin(), root.end(), file.begin(), file.end());
  if (error || end != root.end() || !fs::is_regular_file(file, error)) return {};
  return file;
}

}  // namespace

int run_serve(const ServeOptions& options) {
  const fs::path root = options.folder.empty() ? default_site() : fs::weakly_canonical(options.folder);
  if (!fs::is_directory(root)) throw Error(ErrorKind::kIo, "", kNoPlane, kNoOffset, root.string() + ": not a folder");
  httplib::Server server;
  server.Get(R"(/.*)", [&](const httplib::Request& request, httplib::Response& response) {
    const fs::path file = file_for(root, request.path);
    if (file.empty()) {
      response.status = 404;
      response.set_content("not found: " + request.path + "\n", "text/plain");
      console::detail("GET %s 404", request.path.c_str());
      return;
    }
    std::ifstream in(file, std::ios::binary);
    auto body = std::make_shared<std::string>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    response.set_header("Cache-Control", "no-store");
    console::detail("GET %s 200 %zu bytes", request.path.c_str(), body->size());
    if (options.rate == 0 || file.extension() != ".m4m") {
      response.set_content(*body, content_type(file));
      return;
    }
    // A stream, throttled: a tenth of a second's bytes every tenth of a second.
    const size_t slice = std::max<size_t>(1, options.rate / 10);
    response.set_content_provider(body->size(), content_type(file), [body, slice](size_t offset, size_t, httplib::DataSink& sink) {
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
      return sink.write(body->data() + offset, std::min(slice, body->size() - offset));
    });
  });
  // SO_REUSEADDR only: httplib's default adds SO_REUSEPORT, with which a
  // second server binds a port in use and the two share its requests.
  server.set_socket_options([](socket_t socket) {
    const int yes = 1;
    setsockopt(socket, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  });
  const int port = options.port == 0 ? server.bind_to_any_port(options.host) : (server.bind_to_port(options.host, options.port) ? options.port : -1);
  if (port < 0)
    throw Error(ErrorKind::kIo, "", kNoPlane, kNoOffset,
                "cannot listen on " + options.host + ":" + std::to_string(options.port) + " (in use? --port N, or --port 0 for any free port)");
  // The address on standard output, first line, flushed: scripts read it.
  const std::string rate = options.rate ? " (streams, .m4m, at " + std::to_string(options.rate) + " bytes/s)" : "";
  std::printf("serving %s at http://%s:%d/%s\n", root.c_str(), options.host.c_str(), port, rate.c_str());
  std::fflush(stdout);
  if (!server.listen_after_bind()) throw Error(ErrorKind::kIo, "", kNoPlane, kNoOffset, "the server stopped");
  return 0;
}

}  // namespace m4mesh
