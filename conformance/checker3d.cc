// `m4mesh check` on 3D streams (docs/container3d.md).
#include "conformance/checker.h"

#include <optional>
#include <set>

#include "decoder/mesh3d/container_decoder.h"

namespace m4mesh {

namespace {

constexpr size_t kMaxErrors = 1000;

Finding mesh3d_finding(bool error, ErrorKind kind, int64_t frame, std::string element, int64_t bit, std::string message,
                       std::optional<size_t> unit) {
  return {error, kind, frame, std::move(element), bit, std::move(message), true, unit};
}

Finding finding_of(const Error& e, std::optional<size_t> unit) {
  return mesh3d_finding(true, e.kind(), e.plane(), e.element(), e.bit_offset(), e.message(), unit);
}

}  // namespace

CheckReport check_mesh3d(std::span<const uint8_t> stream) {
  CheckReport report;
  Decode3dOptions options;
  options.hashes = HashCheck::kRecord;
  std::unique_ptr<Mesh3dDecoder> decoder;
  try {
    decoder = std::make_unique<Mesh3dDecoder>(stream, options);
  } catch (const Error& e) {
    report.findings.push_back(finding_of(e, std::nullopt));
    return report;
  }
  bool after_error = false;  // units decoded after the first error
  for (;;) {
    const size_t taken = decoder->units_taken();
    try {
      if (!decoder->next_unit()) break;
      after_error = report.errors() > 0;
      // After an error, later frames decode from a damaged state: their hashes tell nothing new.
      if (report.errors() == 0) {
        std::set<int64_t> units;  // a group's frames share their hash unit's finding
        for (uint32_t frame : decoder->unit().verified)
          if (decoder->hash_result(frame) == false) {
            const Error e = decoder->mismatch_error(frame);
            if (units.insert(e.unit()).second) report.findings.push_back(finding_of(e, static_cast<size_t>(e.unit())));
          }
      }
    } catch (const Error& e) {
      // An error that took no unit is the stream's end (frames missing).
      const bool in_unit = decoder->units_taken() != taken;
      report.findings.push_back(finding_of(e, in_unit ? std::optional<size_t>(decoder->units_taken() - 1) : std::nullopt));
      if (report.findings.size() >= kMaxErrors) {
        report.findings.push_back(mesh3d_finding(false, ErrorKind::kLimit, kNoPlane, "", kNoOffset, "the check stops after 1000 errors", std::nullopt));
        break;
      }
      decoder->resume();
    }
  }
  report.planes = static_cast<int64_t>(decoder->units_taken());  // hash units too, as `info` counts them
  if (after_error)
    report.findings.push_back(mesh3d_finding(false, ErrorKind::kStructure, kNoPlane, "frame_md5", kNoOffset,
                                             "frames after the first error decode from a damaged state: their hashes were not compared",
                                             std::nullopt));
  if (!decoder->has_end_code())
    report.findings.push_back(
        mesh3d_finding(false, ErrorKind::kStructure, kNoPlane, "mesh_object_end_code", kNoOffset, "the stream has no end code", std::nullopt));
  return report;
}

}  // namespace m4mesh
