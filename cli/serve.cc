#include "cli/serve.h"

#include <httplib.h>

#include <nlohmann/json.hpp>

#include <algorithm>
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
      {".gif", "image/gif"},                 {".svg", "image/svg+xml"},   {".txt", "text/plain; charset=utf-8"}, {".md", "text/plain; charset=utf-8"},
      {".glb", "model/gltf-binary"},         {".gltf", "model/gltf+json"}};
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

// What `serve` lists beside the site: streams, glTF animations the player
// shows beside them, and textures (PNG) of 2D streams.
bool servable(const fs::path& file) {
  return file.extension() == ".m4m" || file.extension() == ".glb" || file.extension() == ".gltf" || file.extension() == ".png";
}

// The streams and glTF files named (files, and those of folders), by the
// name they are served under (streams/NAME).
std::map<std::string, fs::path> streams_of(const std::vector<std::string>& paths) {
  std::map<std::string, fs::path> streams;
  auto add = [&streams](const fs::path& file) {
    const std::string name = file.filename().string();
    if (!streams.emplace(name, fs::weakly_canonical(file)).second) throw usage_error("two streams named " + name + ": rename one");
  };
  for (const std::string& path : paths) {
    if (fs::is_directory(path)) {
      std::vector<fs::path> found;
      for (const fs::directory_entry& entry : fs::directory_iterator(path))
        if (entry.is_regular_file() && servable(entry.path())) found.push_back(entry.path());
      if (found.empty()) throw usage_error(path + ": neither a site (no index.html) nor a folder of streams (no .m4m, .glb, .gltf or .png file)");
      std::sort(found.begin(), found.end());
      for (const fs::path& file : found) add(file);
    } else if (fs::is_regular_file(path) && servable(path)) {
      add(path);
    } else {
      throw usage_error(path + ": not a folder, a .m4m stream, a .glb or .gltf animation or a .png texture");
    }
  }
  return streams;
}

std::string streams_json(const std::map<std::string, fs::path>& streams) {
  nlohmann::json list = nlohmann::json::array();
  for (const auto& [name, file] : streams) list.push_back({{"name", name}, {"url", "streams/" + name}, {"bytes", fs::file_size(file)}});
  return list.dump() + "\n";
}

}  // namespace

int run_serve(const ServeOptions& options) {
  // One folder with a page: that folder. Else the site, with the streams named.
  const bool folder = options.paths.size() == 1 && fs::exists(fs::path(options.paths[0]) / "index.html");
  const std::map<std::string, fs::path> streams = folder ? std::map<std::string, fs::path>{} : streams_of(options.paths);
  const fs::path root = folder ? fs::weakly_canonical(options.paths[0]) : default_site();
  httplib::Server server;
  server.Get(R"(/.*)", [&](const httplib::Request& request, httplib::Response& response) {
    if (!streams.empty() && request.path == "/streams.json") {
      response.set_header("Cache-Control", "no-store");
      response.set_content(streams_json(streams), "application/json");
      return;
    }
    const auto stream = request.path.starts_with("/streams/") ? streams.find(request.path.substr(9)) : streams.end();
    const fs::path file = stream != streams.end() ? stream->second : file_for(root, request.path);
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
  // The streams the page lists, and the files it shows beside them.
  uint64_t listed_streams = 0, animations = 0, textures = 0;
  for (const auto& [name, file] : streams) ++(file.extension() == ".m4m" ? listed_streams : file.extension() == ".png" ? textures : animations);
  std::string beside;
  if (animations > 0) beside += console::counted(animations, "glTF animation", "glTF animations");
  if (textures > 0) beside += (beside.empty() ? "" : " and ") + console::counted(textures, "texture", "textures");
  const std::string listed = streams.empty() ? "" : " with " + console::counted(listed_streams, "stream", "streams") + " listed" +
                                                        (beside.empty() ? "" : ", and " + beside);
  std::printf("serving %s%s at http://%s:%d/%s\n", root.c_str(), listed.c_str(), options.host.c_str(), port, rate.c_str());
  std::fflush(stdout);
  if (!server.listen_after_bind()) throw Error(ErrorKind::kIo, "", kNoPlane, kNoOffset, "the server stopped");
  return 0;
}

}  // namespace m4mesh
