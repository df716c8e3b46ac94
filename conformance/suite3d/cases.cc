#include "conformance/suite3d/cases.h"

#include <sstream>

#include "syntax/trace.h"

namespace m4mesh::suite3d {

SuiteCase valid(std::string id, std::string purpose, std::vector<std::string> clauses, const MeshSequence& s, Encode3dOptions o,
                bool traced, uint32_t hash_group) {
  std::ostringstream text;
  Trace trace(text);
  if (traced) o.trace = &trace;
  o.hash_group = hash_group;
  SuiteCase c = decode_case(std::move(id), std::move(purpose), std::move(clauses), encode_mesh3d(s, o).stream);
  c.encoder_trace = text.str();
  return c;
}

SuiteCase written_case(std::string id, std::string purpose, std::vector<std::string> clauses, std::vector<uint8_t> stream) {
  SuiteCase c = decode_case(std::move(id), std::move(purpose), std::move(clauses), std::move(stream));
  c.written = true;
  return c;
}

SuiteCase invalid(std::string id, std::string purpose, std::vector<std::string> clauses, std::vector<uint8_t> stream, ErrorKind kind,
                  std::string element, int64_t frame) {
  return reject_case(std::move(id), std::move(purpose), std::move(clauses), std::move(stream), kind, std::move(element), frame);
}

Encode3dOptions codec_with(std::string codec, CodecOptionValues values) {
  Encode3dOptions o;
  o.hash_group = 1;
  o.codec = std::move(codec);
  o.codec_options = std::move(values);
  return o;
}

Encode3dOptions lcc(CodecOptionValues values) { return codec_with("lcc", std::move(values)); }

Encode3dOptions affine(const std::string& me, int k) {
  return codec_with("affine-octree", {{"me", me}, {"matrix-bits", std::to_string(k)}});
}

Encode3dOptions cpca(CodecOptionValues values) {
  for (const auto& [option, value] : CodecOptionValues{{"model", "shape"}, {"basis", "index"}, {"group-bytes", "0"}})
    if (!values.contains(option)) values[option] = value;
  return codec_with("cpca-wpt", std::move(values));
}

}  // namespace m4mesh::suite3d
