#include "conformance/manifest.h"

#include <filesystem>
#include <nlohmann/json.hpp>

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/md5.h"
#include "conformance/checker.h"
#include "conformance/coverage.h"
#include "conformance/suite.h"
#include "decoder/decoder.h"

namespace m4mesh {

namespace {

using nlohmann::ordered_json;

ordered_json to_json(const ManifestEntry& e) {
  ordered_json j;
  j["id"] = e.id;
  j["file"] = e.file;
  j["purpose"] = e.purpose;
  j["clauses"] = e.clauses;
  j["stream_md5"] = e.stream_md5;
  j["method"] = e.method;
  j["expect"] = e.valid ? "decode" : "error";
  if (e.valid) {
    j["decoded_md5"] = e.decoded_md5;
    j["planes"] = e.planes;
    j["classes"] = e.classes;
    j["warnings"] = e.warnings;
  } else {
    j["error_kind"] = e.error_kind;
    j["error_element"] = e.error_element;
    j["error_plane"] = e.error_plane;
  }
  return j;
}

ManifestEntry from_json(const ordered_json& j) {
  ManifestEntry e;
  e.id = j.at("id").get<std::string>();
  e.file = j.at("file").get<std::string>();
  e.purpose = j.at("purpose").get<std::string>();
  e.clauses = j.at("clauses").get<std::vector<std::string>>();
  e.stream_md5 = j.at("stream_md5").get<std::string>();
  e.method = j.at("method").get<int>();
  e.valid = j.at("expect").get<std::string>() == "decode";
  if (e.valid) {
    e.decoded_md5 = j.at("decoded_md5").get<std::string>();
    e.planes = j.at("planes").get<int64_t>();
    e.classes = j.at("classes").get<std::vector<std::string>>();
    e.warnings = j.at("warnings").get<std::vector<std::string>>();
  } else {
    e.error_kind = j.at("error_kind").get<std::string>();
    e.error_element = j.at("error_element").get<std::string>();
    e.error_plane = j.at("error_plane").get<int64_t>();
  }
  return e;
}

}  // namespace

Manifest read_manifest(const std::string& path) {
  const std::vector<uint8_t> bytes = read_file(path);
  Manifest manifest;
  try {
    const ordered_json j = ordered_json::parse(bytes.begin(), bytes.end());
    for (const ordered_json& entry : j.at("streams")) manifest.entries.push_back(from_json(entry));
  } catch (const nlohmann::json::exception& e) {
    throw Error(ErrorKind::kInput, "", kNoPlane, kNoOffset, path + ": " + e.what());
  }
  return manifest;
}

std::string manifest_json(const Manifest& manifest) {
  ordered_json j;
  j["suite"] = "m4mesh conformance: 2D mesh object (mesh-bitstream.md §1–§11)";
  j["decoded_output"] = "MD5 of the §9 text";
  j["streams"] = ordered_json::array();
  for (const ManifestEntry& e : manifest.entries) j["streams"].push_back(to_json(e));
  return j.dump(2) + "\n";
}

Manifest generate_suite(const std::string& folder) {
  namespace fs = std::filesystem;
  fs::create_directories(fs::path(folder) / "streams");
  Manifest manifest;
  for (const SuiteCase& c : build_suite()) {
    ManifestEntry e;
    e.id = c.id;
    e.file = "streams/" + c.id + ".m4m";
    e.purpose = c.purpose;
    e.clauses = c.clauses;
    const std::string_view bytes(reinterpret_cast<const char*>(c.stream.data()), c.stream.size());
    e.stream_md5 = md5_hex(bytes);
    e.method = c.method == MotionMethod::kMethod1 ? 1 : 2;
    e.valid = c.valid;
    if (c.valid) {
      DecoderOptions options;
      options.method = c.method;
      e.decoded_md5 = decode_to_text(c.stream, options, {});
      Decoder decoder(c.stream, options);
      while (decoder.next()) ++e.planes;
      for (const std::string& value_class : value_classes(c.stream, c.method)) e.classes.push_back(value_class);
      for (const Finding& f : check_stream(c.stream).findings) e.warnings.push_back(format_finding(f));
    } else {
      e.error_kind = to_string(c.error_kind);
      e.error_element = c.error_element;
      e.error_plane = c.error_plane;
    }
    write_file_atomically((fs::path(folder) / e.file).string(), bytes);
    manifest.entries.push_back(std::move(e));
  }
  write_file_atomically((fs::path(folder) / "manifest.json").string(), manifest_json(manifest));
  return manifest;
}

}  // namespace m4mesh
