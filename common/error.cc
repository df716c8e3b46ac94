#include "common/error.h"

namespace m4mesh {

const char* to_string(ErrorKind kind) {
  switch (kind) {
    case ErrorKind::kTruncated: return "truncated";
    case ErrorKind::kMissingStartCode: return "missing-start-code";
    case ErrorKind::kBadStuffing: return "bad-stuffing";
    case ErrorKind::kReservedValue: return "reserved-value";
    case ErrorKind::kOutOfRange: return "out-of-range";
    case ErrorKind::kInvalidCode: return "invalid-code";
    case ErrorKind::kTrailingData: return "trailing-data";
    case ErrorKind::kGeometry: return "geometry";
    case ErrorKind::kStructure: return "structure";
    case ErrorKind::kLimit: return "limit";
    case ErrorKind::kInput: return "input";
    case ErrorKind::kIo: return "io";
    case ErrorKind::kUsage: return "usage";
  }
  return "unknown";
}

static std::string compose(const std::string& element, int64_t plane, int64_t bit_offset, const std::string& message, bool mesh3d,
                           int64_t unit) {
  std::string s;
  if (mesh3d && unit != kNoUnit) s += "unit " + std::to_string(unit);
  if (plane != kNoPlane) s += (s.empty() ? "" : ", ") + std::string(mesh3d ? "frame " : "plane ") + std::to_string(plane);
  if (!element.empty()) {
    if (!s.empty()) s += ", ";
    s += element;
  }
  if (bit_offset != kNoOffset) s += " at bit " + std::to_string(bit_offset);
  if (!s.empty()) s += ": ";
  return s + message;
}

Error::Error(ErrorKind kind, std::string element, int64_t plane, int64_t bit_offset, const std::string& message)
    : std::runtime_error(compose(element, plane, bit_offset, message, false, kNoUnit)),
      kind_(kind),
      element_(std::move(element)),
      plane_(plane),
      bit_offset_(bit_offset),
      message_(message) {}

Error::Error(ErrorKind kind, std::string element, int64_t plane, int64_t bit_offset, const std::string& message, int64_t unit)
    : std::runtime_error(compose(element, plane, bit_offset, message, true, unit)),
      kind_(kind),
      element_(std::move(element)),
      plane_(plane),
      bit_offset_(bit_offset),
      message_(message),
      mesh3d_(true),
      unit_(unit) {}

Error Error::in_mesh3d(int64_t unit) const { return Error(kind_, element_, plane_, bit_offset_, message_, unit); }

Error input_error(const std::string& file, int64_t line, const std::string& message) {
  std::string text = file;
  if (line > 0) text.append(":").append(std::to_string(line));
  text.append(": ").append(message);
  return Error(ErrorKind::kInput, "", kNoPlane, kNoOffset, text);
}

Error usage_error(const std::string& message) { return Error(ErrorKind::kUsage, "", kNoPlane, kNoOffset, message); }

}  // namespace m4mesh
