// Each codec header field's range passed at both ends (docs' syntax
// tables; tests/requirements_test.cc checks that every end has its
// stream), and binary32 fields that are not finite or not positive: the
// field alone edited in a stream of the codec.
#include "conformance/suite3d/cases.h"
#include "conformance/suite3d/stream_edits.h"
#include "syntax/mesh3d/affine_octree.h"
#include "syntax/mesh3d/bfs3d.h"
#include "syntax/mesh3d/cpca_wpt.h"
#include "syntax/mesh3d/lcc.h"

namespace m4mesh::suite3d {

namespace {

struct HeaderEdit {
  const char* id;
  const char* field;
  uint32_t value;
  const char* purpose = nullptr;  // "FIELD VALUE" unless given
};

// binary32 bit patterns.
constexpr uint32_t kNan = 0x7FC00000, kInfinity = 0x7F800000, kMinusOne = 0xBF800000;

template <class CodecHeader>
void add_header_edits(std::vector<SuiteCase>& suite, const std::vector<uint8_t>& base, const char* clause, std::initializer_list<HeaderEdit> edits) {
  for (const HeaderEdit& e : edits) {
    const FieldBytes field = object_field<CodecHeader>(base, e.field);
    suite.push_back(invalid(e.id, e.purpose ? e.purpose : std::string(e.field) + " " + std::to_string(e.value), {clause},
                            edited(base, [&](ContainerParts& p) { put_field(p.object_payload, field, e.value); }), ErrorKind::kOutOfRange, e.field,
                            kNoPlane));
  }
}

}  // namespace

std::vector<SuiteCase> header_range_ends_rejected(const std::vector<SuiteCase>& valid) {
  std::vector<SuiteCase> suite;
  add_header_edits<Bfs3dHeader>(suite, stream_of(valid, "bfs3d-01-average"), "bfs3d",
                                {{"x-82-bfs3d-quantization-bits-3", "quantization_bits", 3}, {"x-83-bfs3d-quantization-bits-25", "quantization_bits", 25}});
  add_header_edits<AffineOctreeHeader>(suite, stream_of(valid, "ao-01-me1-k16"), "ao-header",
                                       {{"x-84-ao-quantization-bits-3", "quantization_bits", 3},
                                        {"x-85-ao-quantization-bits-25", "quantization_bits", 25},
                                        {"x-86-ao-matrix-bits-3", "matrix_bits", 3},
                                        {"x-87-ao-matrix-bits-25", "matrix_bits", 25},
                                        {"x-88-ao-matrix-range-0", "matrix_range_log2", 0},
                                        {"x-89-ao-matrix-range-9", "matrix_range_log2", 9},
                                        {"x-90-ao-max-depth-0", "max_depth", 0}});
  add_header_edits<LccHeader>(suite, stream_of(valid, "lcc-01-stream"), "lcc",
                              {{"x-91-lcc-quantization-bits-3", "quantization_bits", 3},
                               {"x-92-lcc-theta-bits-1", "theta_bits", 1},
                               {"x-93-lcc-rh-bits-0", "rh_bits", 0}});
  add_header_edits<CpcaHeader>(suite, stream_of(valid, "cpca-01-wpt"), "cpca", {{"x-94-cpca-quantization-bits-25", "quantization_bits", 25}});
  add_header_edits<Bfs3dHeader>(suite, stream_of(valid, "bfs3d-01-average"), "bfs3d",
                                {{"x-96-bfs3d-origin-nan", "origin_x", kNan, "origin_x a NaN"}, {"x-97-bfs3d-step-zero", "step_y", 0, "step_y 0"}});
  add_header_edits<AffineOctreeHeader>(suite, stream_of(valid, "ao-01-me1-k16"), "ao-header",
                                       {{"x-98-ao-step-negative", "step", kMinusOne, "step −1"},
                                        {"x-99-ao-origin-infinite", "origin_z", kInfinity, "origin_z +∞"}});
  add_header_edits<LccHeader>(suite, stream_of(valid, "lcc-01-stream"), "lcc",
                              {{"x-100-lcc-step-infinite", "step_x", kInfinity, "step_x +∞"},
                               {"x-101-lcc-rh-range-negative", "rh_range", kMinusOne, "rh_range −1"}});
  add_header_edits<CpcaHeader>(suite, stream_of(valid, "cpca-01-wpt"), "cpca", {{"x-102-cpca-step-nan", "step_z", kNan, "step_z a NaN"}});
  return suite;
}

}  // namespace m4mesh::suite3d
