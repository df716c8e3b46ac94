#include "conformance/suite_files.h"

#include <filesystem>

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/md5.h"
#include "conformance/checker.h"
#include "conformance/coverage.h"
#include "conformance/suite3d/suite3d.h"
#include "decoder/mesh3d/container_decoder.h"
#include "decoder/mesh_object_decoder.h"

namespace m4mesh {

namespace {

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
    e.stream_md5 = md5_hex(c.stream);
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
