#include "conformance/judge.h"

#include "common/error.h"
#include "common/md5.h"

namespace m4mesh {

std::string stream_md5_mismatch(const ManifestEntry& entry, const std::vector<uint8_t>& stream) {
  const std::string md5 = md5_hex(stream);
  return md5 == entry.stream_md5 ? "" : "the stream file's MD5 is " + md5 + ", the manifest says " + entry.stream_md5;
}

Verdict judge_stream(SuiteKind kind, const ManifestEntry& e, const std::vector<uint8_t>& stream) {
  if (std::string mismatch = stream_md5_mismatch(e, stream); !mismatch.empty()) return {false, std::move(mismatch)};
  const char* unit = kind == SuiteKind::kMesh3d ? "frame " : "plane ";
  try {
    const std::string md5 = decoded_output_md5(kind, stream, e.method);
    if (!e.valid) return {false, "decoded, expected " + e.error_kind + " at " + e.error_element};
    if (md5 != e.decoded_md5) return {false, "decoded MD5 " + md5 + ", expected " + e.decoded_md5};
    return {true, md5};
  } catch (const Error& error) {
    if (e.valid) return {false, error.what()};
    if (to_string(error.kind()) != e.error_kind || error.element() != e.error_element || error.plane() != e.error_plane ||
        error.bit_offset() != e.error_offset)
      return {false, std::string(to_string(error.kind())) + ": " + error.what() + "; expected " + e.error_kind + " at " + unit +
                         std::to_string(e.error_plane) + ", " + e.error_element + " at bit " + std::to_string(e.error_offset)};
    return {true, std::string(to_string(error.kind())) + ": " + error.what()};
  }
}

}  // namespace m4mesh
