// Completeness defined from the docs' side, not from m4mesh's branches:
// every range a syntax table of the docs prints (the tables are the
// descriptions', tests/docs_test.cc) is met at both ends by a stream to
// decode and passed at both ends by a stream to reject, and every code of
// every VLC table of the 2D specification occurs in a stream to decode.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <set>
#include <sstream>

#include "codecs3d/registry.h"
#include "common/atomic_file.h"
#include "conformance/manifest.h"
#include "decoder/mesh3d/container_decoder.h"
#include "decoder/mesh_object_decoder.h"
#include "syntax/describe.h"
#include "syntax/mesh3d/affine_octree.h"
#include "syntax/mesh3d/base_mesh.h"
#include "syntax/mesh3d/bfs3d.h"
#include "syntax/mesh3d/container.h"
#include "syntax/mesh3d/cpca_wpt.h"
#include "syntax/mesh3d/lcc.h"
#include "syntax/table_io.h"
#include "syntax/trace.h"

namespace m4mesh {
namespace {

namespace fs = std::filesystem;

const fs::path kSuite = M4MESH_CONFORMANCE_DIR;

// A field's range and where it applies: kAnyCodec for the container and
// the base mesh, a codec_id for a codec's own structures, k2d for the 2D
// specification.
constexpr int kAnyCodec = 0;
constexpr int k2d = -1;
struct FieldRange {
  int codec;
  syntax::TableIO::Range range;
};

template <class T>
void add_ranges(std::vector<FieldRange>& out, int codec) {
  syntax::TableIO io;
  T value;
  syntax::describe(io, value);
  for (const syntax::TableIO::Range& r : io.ranges()) out.push_back({codec, r});
}

std::vector<FieldRange> documented_ranges() {
  std::vector<FieldRange> ranges;
  add_ranges<UniformGeometry>(ranges, k2d);
  add_ranges<DelaunayGeometry>(ranges, k2d);
  add_ranges<ObjectHeader>(ranges, kAnyCodec);
  add_ranges<UnitHeader>(ranges, kAnyCodec);
  add_ranges<GroupHash>(ranges, kAnyCodec);
  add_ranges<BaseMeshData>(ranges, kAnyCodec);
  add_ranges<Bfs3dHeader>(ranges, kBfs3dId);
  add_ranges<AffineOctreeHeader>(ranges, kAffineOctreeId);
  add_ranges<AffineFrame>(ranges, kAffineOctreeId);
  add_ranges<LccHeader>(ranges, kLccId);
  add_ranges<CpcaHeader>(ranges, kCpcaWptId);
  add_ranges<CpcaRefinement>(ranges, kCpcaWptId);
  return ranges;
}

// What the suites hold for a field: the values decoded streams carry, and
// the values streams are rejected for ("value V outside LO…HI").
struct Seen {
  std::set<int64_t> decoded, rejected;
};
using Key = std::pair<int, std::string>;  // codec (or k2d), element

// A stream's trace and, for a stream to reject, its error.
std::string traced(const std::vector<uint8_t>& stream, SuiteKind kind, std::optional<Error>& error) {
  std::ostringstream text;
  try {
    if (kind == SuiteKind::kMesh3d) {
      trace_mesh3d(stream, text);
    } else {
      Trace trace(text);
      DecoderOptions options;
      options.trace = &trace;
      decode_to_text(stream, options, {});
    }
  } catch (const Error& e) {
    error = e;
  }
  return text.str();
}

std::map<Key, Seen> values_in_suites(const std::set<std::string>& names) {
  std::map<Key, Seen> seen;
  for (const char* sub : {".", "mesh3d"}) {
    const Manifest manifest = read_manifest((kSuite / sub / "manifest.json").string());
    for (const ManifestEntry& e : manifest.entries) {
      std::optional<Error> error;
      std::istringstream lines(traced(read_file((kSuite / sub / e.file).string()), manifest.kind, error));
      int codec = manifest.kind == SuiteKind::kMesh3d ? kAnyCodec : k2d;
      for (std::string l; std::getline(lines, l);) {
        const std::optional<TraceLine> line = parse_trace_line(l);
        if (!line || !line->numeric() || !names.contains(line->name)) {
          if (line && line->name == "codec_id") codec = std::stoi(line->value);
          continue;
        }
        if (!e.valid) continue;
        const int64_t value = std::stoll(line->value);
        seen[{codec, line->name}].decoded.insert(value);
        if (codec != k2d) seen[{kAnyCodec, line->name}].decoded.insert(value);
      }
      if (e.valid || !error || error->kind() != ErrorKind::kOutOfRange) continue;
      const std::string what = error->what();
      const size_t at = what.find(": value ");
      if (at == std::string::npos || what.find(" outside ", at) == std::string::npos) continue;
      const int64_t value = std::stoll(what.substr(at + 8));
      seen[{codec, error->element()}].rejected.insert(value);
      if (codec != k2d) seen[{kAnyCodec, error->element()}].rejected.insert(value);
    }
  }
  return seen;
}

// Range ends no stream of a suite can reach, each with its reason.
const std::map<std::string, std::string> kUnreachable = {
    {"vertex_count decoded 16777216", "a stream of 2^24 vertices is too large for a suite"},
    {"face_count decoded 33554432", "a stream of 2^25 faces is too large for a suite"},
    {"group_frames decoded 65535", "a group of 65,535 frames needs a stream of as many frames"},
};

TEST(Requirements, EveryRangeEndIsMetAndPassed) {
  const std::vector<FieldRange> ranges = documented_ranges();
  std::set<std::string> names;
  for (const FieldRange& r : ranges) names.insert(r.range.name);
  const std::map<Key, Seen> seen = values_in_suites(names);
  size_t ends = 0, unreachable = 0;
  for (const FieldRange& r : ranges) {
    const auto found = seen.find({r.codec, r.range.name});
    const Seen none;
    const Seen& s = found == seen.end() ? none : found->second;
    const int64_t lo = r.range.lo, hi = r.range.hi, largest = (int64_t{1} << r.range.bits) - 1;
    const std::string codec = r.codec == k2d ? "2D" : r.codec == kAnyCodec ? "3D" : "codec " + std::to_string(r.codec);
    auto expect = [&](bool met, const char* verdict, int64_t value) {
      ++ends;
      const std::string what = r.range.name + " " + verdict + " " + std::to_string(value);
      if (kUnreachable.contains(what)) {
        ++unreachable;
        return;
      }
      EXPECT_TRUE(met) << codec << ": no stream with " << r.range.name << " " << value << " is " << verdict << " (range " << lo << " … " << hi << ")";
    };
    expect(s.decoded.contains(lo), "decoded", lo);
    expect(s.decoded.contains(hi), "decoded", hi);
    if (lo > 0) expect(s.rejected.contains(lo - 1), "rejected", lo - 1);
    if (hi < largest) expect(s.rejected.contains(hi + 1), "rejected", hi + 1);
  }
  std::printf("%zu ranges, %zu ends (%zu out of a suite's reach)\n", ranges.size(), ends, unreachable);
}

// Every code of §4.1 and §4.2 in a stream to decode, for each element that
// uses the table; a length-11 delta (|delta| ≥ 1024) puts a coordinate
// outside 0 … 1023, so its code occurs in a stream to reject, read before
// the coordinate is refused.
TEST(Requirements, EveryVlcCodeOccurs) {
  const std::map<std::string, const VlcTable*> tables = {{"delta_x_len_vlc", &delta_length_table()},
                                                         {"delta_y_len_vlc", &delta_length_table()},
                                                         {"delta_mv_x_vlc", &motion_code_table()},
                                                         {"delta_mv_y_vlc", &motion_code_table()}};
  constexpr int kRejectedOnly = 11;
  std::map<std::string, std::set<int>> decoded, rejected;
  const Manifest manifest = read_manifest((kSuite / "manifest.json").string());
  for (const ManifestEntry& e : manifest.entries) {
    std::optional<Error> error;
    std::istringstream lines(traced(read_file((kSuite / e.file).string()), manifest.kind, error));
    for (std::string l; std::getline(lines, l);) {
      const std::optional<TraceLine> line = parse_trace_line(l);
      if (line && tables.contains(line->name)) (e.valid ? decoded : rejected)[line->name].insert(std::stoi(line->value));
    }
  }
  size_t codes = 0;
  for (const auto& [element, table] : tables)
    for (const VlcRow& row : table->rows()) {
      ++codes;
      if (table == &delta_length_table() && row.symbol == kRejectedOnly)
        EXPECT_TRUE(rejected[element].contains(row.symbol)) << element << ": no stream to reject reads the code of " << row.symbol;
      else
        EXPECT_TRUE(decoded[element].contains(row.symbol)) << element << ": no stream to decode codes " << row.symbol;
    }
  std::printf("%zu codes of %zu elements\n", codes, tables.size());
}

}  // namespace
}  // namespace m4mesh
