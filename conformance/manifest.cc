#include "conformance/manifest.h"

#include <filesystem>
#include <nlohmann/json.hpp>

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/md5.h"
#include "conformance/checker.h"
#include "conformance/coverage.h"
#include "conformance/suite3d/suite3d.h"
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

std::string md5_of(const std::vector<uint8_t>& bytes) {
  return md5_hex(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

// Where m4mesh's decoder places the error of a stream to reject; the
// generator refuses a case whose error is not the one it claims.
int64_t rejection_offset(SuiteKind kind, const SuiteCase& c, int method) {
  try {
    decoded_output_md5(kind, c.stream, method);
  } catch (const Error& error) {
    if (error.kind() == c.error_kind && error.element() == c.error_element && error.plane() == c.error_plane) return error.bit_offset();
    throw Error(ErrorKind::kStructure, "", kNoPlane, kNoOffset, c.id + ": the decoder reports " + error.what() + ", not the case's error");
  }
  throw Error(ErrorKind::kStructure, "", kNoPlane, kNoOffset, c.id + ": a stream to reject decodes");
}

}  // namespace

Manifest read_manifest(const std::string& path) {
  const std::vector<uint8_t> bytes = read_file(path);
  Manifest manifest;
  try {
    const ordered_json j = ordered_json::parse(bytes.begin(), bytes.end());
    const std::string kind = j.at("kind").get<std::string>();
    if (kind != "mesh2d" && kind != "mesh3d") throw Error(ErrorKind::kInput, "", kNoPlane, kNoOffset, path + ": unknown kind " + kind);
    manifest.kind = kind == "mesh3d" ? SuiteKind::kMesh3d : SuiteKind::kMesh2d;
    for (const ordered_json& entry : j.at("streams")) manifest.entries.push_back(from_json(entry, manifest.kind));
  } catch (const nlohmann::json::exception& e) {
    throw Error(ErrorKind::kInput, "", kNoPlane, kNoOffset, path + ": " + e.what());
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
  if (kind == SuiteKind::kMesh3d) return md5_of(decoded_frames3d(stream));
  DecoderOptions options;
  options.method = method_of(method);
  return decode_to_text(stream, options, {});
}

Manifest write_suite(const std::string& folder, SuiteKind kind, const std::vector<SuiteCase>& cases) {
  namespace fs = std::filesystem;
  fs::create_directories(fs::path(folder) / "streams");
  Manifest manifest;
  manifest.kind = kind;
  for (const SuiteCase& c : cases) {
    ManifestEntry e;
    e.id = c.id;
    e.file = "streams/" + c.id + ".m4m";
    e.purpose = c.purpose;
    e.clauses = c.clauses;
    e.stream_md5 = md5_of(c.stream);
    e.method = c.method == MotionMethod::kMethod1 ? 1 : 2;
    e.valid = c.valid;
    if (c.valid) {
      e.decoded_md5 = decoded_output_md5(kind, c.stream, e.method);
      const CheckReport report = kind == SuiteKind::kMesh3d ? check_mesh3d(c.stream) : check_stream(c.stream);
      for (const Finding& f : report.findings) e.warnings.push_back(format_finding(f));
      if (kind == SuiteKind::kMesh3d) {
        Mesh3dDecoder decoder(c.stream);
        while (decoder.next_frame()) ++e.planes;
      } else {
        DecoderOptions options;
        options.method = c.method;
        Decoder decoder(c.stream, options);
        while (decoder.next()) ++e.planes;
        for (const std::string& value_class : value_classes(c.stream, c.method)) e.classes.push_back(value_class);
      }
    } else {
      e.error_kind = to_string(c.error_kind);
      e.error_element = c.error_element;
      e.error_plane = c.error_plane;
      e.error_offset = rejection_offset(kind, c, e.method);
    }
    write_file_atomically((fs::path(folder) / e.file).string(), std::string_view(reinterpret_cast<const char*>(c.stream.data()), c.stream.size()));
    manifest.entries.push_back(std::move(e));
  }
  write_file_atomically((fs::path(folder) / "manifest.json").string(), manifest_json(manifest));
  return manifest;
}

void generate_suites(const std::string& folder) {
  write_suite(folder, SuiteKind::kMesh2d, build_suite());
  write_suite(folder + "/mesh3d", SuiteKind::kMesh3d, build_suite3d());
}

}  // namespace m4mesh
