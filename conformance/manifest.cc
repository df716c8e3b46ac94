#include "conformance/manifest.h"

#include <nlohmann/json.hpp>

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/md5.h"
#include "decoder/mesh3d/container_decoder.h"
#include "decoder/mesh_object_decoder.h"
#include "syntax/mesh3d/container.h"

namespace m4mesh {

namespace {

using nlohmann::ordered_json;

MotionMethod method_of(int method) { return method == 1 ? MotionMethod::kMethod1 : MotionMethod::kMethod2; }

ordered_json to_json(const ManifestEntry& e, SuiteKind kind) {
  ordered_json j;
  j["id"] = e.id;
  j["file"] = e.file;
  j["purpose"] = e.purpose;
  j["clauses"] = e.clauses;
  j["stream_md5"] = e.stream_md5;
  if (kind == SuiteKind::kMesh2d) j["method"] = e.method;
  j["expect"] = e.valid ? "decode" : "error";
  if (e.valid) {
    j["decoded_md5"] = e.decoded_md5;
    j["planes"] = e.planes;
    if (kind == SuiteKind::kMesh2d) j["classes"] = e.classes;
    j["warnings"] = e.warnings;
  } else {
    j["error_kind"] = e.error_kind;
    j["error_element"] = e.error_element;
    j["error_plane"] = e.error_plane;
    j["error_offset"] = e.error_offset;
  }
  return j;
}

ManifestEntry from_json(const ordered_json& j, SuiteKind kind) {
  ManifestEntry e;
  e.id = j.at("id").get<std::string>();
  e.file = j.at("file").get<std::string>();
  e.purpose = j.at("purpose").get<std::string>();
  e.clauses = j.at("clauses").get<std::vector<std::string>>();
  e.stream_md5 = j.at("stream_md5").get<std::string>();
  if (kind == SuiteKind::kMesh2d) e.method = j.at("method").get<int>();
  e.valid = j.at("expect").get<std::string>() == "decode";
  if (e.valid) {
    e.decoded_md5 = j.at("decoded_md5").get<std::string>();
    e.planes = j.at("planes").get<int64_t>();
    if (kind == SuiteKind::kMesh2d) e.classes = j.at("classes").get<std::vector<std::string>>();
    e.warnings = j.at("warnings").get<std::vector<std::string>>();
  } else {
    e.error_kind = j.at("error_kind").get<std::string>();
    e.error_element = j.at("error_element").get<std::string>();
    e.error_plane = j.at("error_plane").get<int64_t>();
    e.error_offset = j.at("error_offset").get<int64_t>();
  }
  return e;
}

}  // namespace

Manifest read_manifest(const std::string& path) {
  const std::vector<uint8_t> bytes = read_file(path);
  return parse_manifest(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), path);
}

Manifest parse_manifest(std::string_view text, const std::string& name) {
  Manifest manifest;
  try {
    const ordered_json j = ordered_json::parse(text);
    const std::string kind = j.at("kind").get<std::string>();
    if (kind != "mesh2d" && kind != "mesh3d") throw Error(ErrorKind::kInput, "", kNoPlane, kNoOffset, name + ": unknown kind " + kind);
    manifest.kind = kind == "mesh3d" ? SuiteKind::kMesh3d : SuiteKind::kMesh2d;
    for (const ordered_json& entry : j.at("streams")) manifest.entries.push_back(from_json(entry, manifest.kind));
  } catch (const nlohmann::json::exception& e) {
    throw Error(ErrorKind::kInput, "", kNoPlane, kNoOffset, name + ": " + e.what());
  }
  return manifest;
}

std::string manifest_json(const Manifest& manifest) {
  const bool mesh3d = manifest.kind == SuiteKind::kMesh3d;
  ordered_json j;
  j["suite"] = mesh3d ? "m4mesh conformance: 3D container (§12; docs/container3d.md and each codec's document)"
                      : "m4mesh conformance: 2D mesh object (mesh-bitstream.md §1–§11)";
  j["kind"] = mesh3d ? "mesh3d" : "mesh2d";
  j["decoded_output"] = mesh3d ? "MD5 of every frame's binary32 x, y, z per vertex (little-endian), frame after frame; planes are frames"
                               : "MD5 of the §9 text";
  j["streams"] = ordered_json::array();
  for (const ManifestEntry& e : manifest.entries) j["streams"].push_back(to_json(e, manifest.kind));
  return j.dump(2) + "\n";
}

std::string decoded_output_md5(SuiteKind kind, const std::vector<uint8_t>& stream, int method) {
  if (kind == SuiteKind::kMesh3d) return md5_hex(decoded_frames3d(stream));
  DecoderOptions options;
  options.method = method_of(method);
  return decode_to_text(stream, options, {});
}

}  // namespace m4mesh
