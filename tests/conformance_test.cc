// The conformance suite: regeneration, coverage, syntax round trips and the checker.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <tuple>

#include "common/atomic_file.h"
#include "conformance/checker.h"
#include "conformance/coverage.h"
#include "conformance/suite3d/base_mesh_oracles.h"
#include "conformance/suite_files.h"
#include "decoder/mesh3d/container_decoder.h"
#include "decoder/mesh_object_decoder.h"
#include "mesh3d/frame_hash.h"
#include "syntax/mesh3d/container.h"
#include "syntax/mesh_object.h"
#include "syntax/trace.h"
#include "syntax/values.h"
#include "tests/test_util.h"

namespace m4mesh {
namespace {

namespace fs = std::filesystem;

const fs::path kSuite = M4MESH_CONFORMANCE_DIR;
const fs::path kSpec = fs::path(M4MESH_SOURCE_DIR) / ".." / "shared" / "spec" / "mesh-bitstream.md";

std::vector<uint8_t> stream_of(const ManifestEntry& e) { return read_file((kSuite / e.file).string()); }

// Both suites, 2D and 3D: every stream and manifest regenerates byte for byte.
TEST(Conformance, RegenerationGivesIdenticalBytes) {
  const fs::path folder = fs::temp_directory_path() / "m4mesh-suites-regenerated";
  fs::remove_all(folder);
  generate_suites(folder.string());
  for (const char* sub : {".", "mesh3d"}) {
    EXPECT_EQ(read_file((folder / sub / "manifest.json").string()), read_file((kSuite / sub / "manifest.json").string()))
        << sub << "/manifest.json differs: run `m4mesh generate-suite conformance` and review the change";
    const Manifest regenerated = read_manifest((folder / sub / "manifest.json").string());
    for (const ManifestEntry& e : regenerated.entries)
      EXPECT_EQ(read_file((folder / sub / e.file).string()), read_file((kSuite / sub / e.file).string())) << e.id << " differs from the committed stream";
    size_t committed = 0;
    for (const auto& entry : fs::directory_iterator(kSuite / sub / "streams")) committed += entry.path().extension() == ".m4m";
    EXPECT_EQ(committed, regenerated.entries.size()) << sub << "/streams holds files the manifest does not list";
  }
  fs::remove_all(folder);
}

// base-26-front gives every answer its description lists before its cap of gates.
TEST(Conformance, FrontStreamGivesEveryAnswerItLists) {
  suite3d::FrontOracle oracle;
  suite3d::BinRecorder recorder;
  syntax::BaseMeshContexts contexts;
  GateTraversal traversal(0);
  oracle.watch(traversal);
  constexpr uint32_t kUnbounded = std::numeric_limits<uint32_t>::max();
  EXPECT_THROW(describe_traversal(recorder, contexts, traversal, kUnbounded, kUnbounded, &oracle), std::out_of_range);
  EXPECT_TRUE(oracle.done()) << oracle.left();
}

// The rule of docs/container3d.md ("Errors") and docs/decisions.md (3): an
// error that names a field is placed at that field's first bit. Checked
// against the decoder's own trace, which prints each field where it
// starts, for every stream to reject whose element is a traced field
// (truncation stops inside the element, before it is traced; trailing data
// is placed after the end code it names; missing frames have no offset).
TEST(Conformance, RejectionsArePlacedAtTheFirstBitOfTheirField) {
  int checked = 0;
  for (const char* sub : {".", "mesh3d"}) {
    const Manifest manifest = read_manifest((kSuite / sub / "manifest.json").string());
    for (const ManifestEntry& e : manifest.entries) {
      if (e.valid || e.error_kind == "truncated" || e.error_kind == "trailing-data") continue;
      const std::vector<uint8_t> stream = read_file((kSuite / sub / e.file).string());
      std::ostringstream text;
      Trace trace(text);
      try {
        if (manifest.kind == SuiteKind::kMesh3d) {
          trace_mesh3d(stream, text);
        } else {
          DecoderOptions options;
          options.trace = &trace;
          decode_to_text(stream, options, {});
        }
      } catch (const Error&) {
      }
      // The last traced line of the element placed at a bit of its payload
      // (offsets count from the unit's start code, or the stream's start),
      // in the unit that holds the error (none when the decoder refused the
      // field before tracing it).
      const std::vector<ContainerUnit> units = manifest.kind == SuiteKind::kMesh3d ? split_container(stream).units : std::vector<ContainerUnit>{};
      int64_t error_unit = -1;
      for (size_t u = 0; u < units.size(); ++u)
        if (e.error_offset >= 0 && 8 * units[u].byte_offset <= static_cast<uint64_t>(e.error_offset)) error_unit = static_cast<int64_t>(u);
      int64_t expected = -1;
      std::istringstream lines(text.str());
      for (std::string l; std::getline(lines, l);) {
        const std::optional<TraceLine> line = parse_trace_line(l);
        if (!line || line->name != e.error_element || line->position.find(':') != std::string::npos) continue;
        if (line->unit >= 0 && line->unit != error_unit) continue;
        const uint64_t base = line->unit < 0 ? 0 : 8 * units.at(static_cast<size_t>(line->unit)).byte_offset;
        expected = static_cast<int64_t>(base + std::stoull(line->position));
      }
      if (expected < 0) continue;  // not a traced field: a structure, a section's symbols, a whole-stream rule
      EXPECT_EQ(e.error_offset, expected) << sub << "/" << e.id << ": " << e.error_element;
      ++checked;
    }
  }
  EXPECT_GE(checked, 45);
}

// A stream decoded while it arrives (the web player): bytes come 97 at a
// time, the decoder is extended with those up to the last start code, takes
// every whole unit, and ends with the same frames and hash checks as the
// decoder given the whole stream, on every valid stream of the 3D suite.
TEST(Conformance, StreamsDecodeAlikeWhileTheyArrive) {
  size_t checked = 0;
  for (const ManifestEntry& e : read_manifest((kSuite / "mesh3d" / "manifest.json").string()).entries) {
    if (!e.valid) continue;
    const std::vector<uint8_t> stream = read_file((kSuite / "mesh3d" / e.file).string());
    Decode3dOptions options;
    options.hashes = HashCheck::kRecord;
    std::optional<Mesh3dDecoder> decoder;
    std::map<uint32_t, std::vector<Float3>> frames;
    std::set<uint32_t> released;  // a progressive codec's frames final before its last unit (segments)
    const auto take_units = [&] {
      while (decoder->units_taken() < decoder->units_received()) {
        ASSERT_TRUE(decoder->next_unit()) << e.id;
        for (uint32_t f : decoder->unit().released) {
          decoder->frame(f, frames[f] = std::vector<Float3>(decoder->header().vertex_count));
          released.insert(f);
        }
        for (uint32_t f : decoder->unit().frames) decoder->frame(f, frames[f] = std::vector<Float3>(decoder->header().vertex_count));
      }
    };
    const auto feed = [&](std::span<const uint8_t> bytes) {
      if (decoder)
        decoder->extend(bytes);
      else
        decoder.emplace(bytes, options);
      take_units();
    };
    for (size_t received = 97; received < stream.size(); received += 97)
      if (const size_t whole = whole_payloads_size(std::span(stream).first(received)); whole > 0) feed(std::span(stream).first(whole));
    feed(stream);
    EXPECT_FALSE(decoder->next_unit()) << e.id;
    EXPECT_FALSE(decoder->first_mismatch().has_value()) << e.id;
    std::vector<uint8_t> bytes;
    const size_t frame_count = decoder->header().frame_count != 0 ? decoder->header().frame_count : frames.size();  // 0: streaming
    for (uint32_t f = 0; f < frame_count; ++f) {
      if (decoder->progressive() && !released.contains(f)) decoder->frame(f, frames[f] = std::vector<Float3>(decoder->header().vertex_count));
      const std::vector<uint8_t> b = frame_bytes(frames[f]);
      bytes.insert(bytes.end(), b.begin(), b.end());
    }
    EXPECT_EQ(bytes, decoded_frames3d(stream)) << e.id;
    ++checked;
  }
  EXPECT_GE(checked, 80u);
}

TEST(Conformance, SuiteSize) {
  const Manifest manifest = read_manifest((kSuite / "manifest.json").string());
  size_t valid = 0;
  for (const ManifestEntry& e : manifest.entries) valid += e.valid;
  EXPECT_GE(valid, 40u);
  EXPECT_GE(manifest.entries.size() - valid, 20u);
}

// Every numbered clause of the specification has a stream.
TEST(Conformance, EveryClauseOfTheSpecificationIsCovered) {
  if (!fs::exists(kSpec)) GTEST_SKIP() << "the specification is not at " << kSpec << " (../shared absent)";
  // Headings "## N. Title" and "### N.M Title".
  std::ifstream spec(kSpec);
  std::set<std::string> clauses;
  for (std::string line; std::getline(spec, line);) {
    if (!line.starts_with("## ") && !line.starts_with("### ")) continue;
    const std::string rest = line.substr(line.find(' ') + 1);
    const std::string number = rest.substr(0, rest.find(' '));
    std::string clause = number.ends_with(".") ? number.substr(0, number.size() - 1) : number;
    if (!clause.empty() && clause.find_first_not_of("0123456789.") == std::string::npos) clauses.insert(clause);
  }
  ASSERT_GE(clauses.size(), 20u);
  std::set<std::string> covered;
  for (const ManifestEntry& e : read_manifest((kSuite / "manifest.json").string()).entries)
    for (const std::string& c : e.clauses) {
      covered.insert(c);
      covered.insert(c.substr(0, c.find('.')));  // a subclause covers its parent
    }
  // §12 (3D containers) is exercised by the 3D suites, not by 2D mesh object streams.
  clauses.erase("12");
  for (const std::string& c : clauses) EXPECT_TRUE(covered.count(c)) << "no stream covers §" << c;
}

// The manifest's value classes are what the streams really contain, and
// together they cover every required class.
TEST(Conformance, ValueClassesAreCoveredAndTrue) {
  std::set<std::string> covered;
  for (const ManifestEntry& e : read_manifest((kSuite / "manifest.json").string()).entries) {
    if (!e.valid) continue;
    const std::set<std::string> actual = value_classes(stream_of(e), e.method == 1 ? MotionMethod::kMethod1 : MotionMethod::kMethod2);
    EXPECT_EQ(std::set<std::string>(e.classes.begin(), e.classes.end()), actual) << e.id;
    covered.insert(actual.begin(), actual.end());
  }
  for (const std::string& c : required_value_classes()) EXPECT_TRUE(covered.count(c)) << "no stream has value class " << c;
}

// Parse every stream the syntax can hold into structures and write it back.
TEST(Conformance, EveryParsableStreamRoundTripsThroughSyntaxStructures) {
  for (const ManifestEntry& e : read_manifest((kSuite / "manifest.json").string()).entries) {
    const std::vector<uint8_t> stream = stream_of(e);
    // Valid streams, and negative ones whose error is in the geometry, hold correct syntax.
    const bool parsable = e.valid || e.error_kind == "geometry";
    MeshObject object;
    try {
      object = syntax::read_mesh_object(stream);
    } catch (const Error& error) {
      EXPECT_FALSE(parsable) << e.id << " does not parse: " << error.what();
      continue;
    }
    EXPECT_TRUE(parsable) << e.id << " parses";
    EXPECT_EQ(syntax::write_mesh_object(object), stream) << e.id;
  }
}

TEST(Conformance, CheckerAcceptsValidAndRejectsInvalidStreams) {
  for (const ManifestEntry& e : read_manifest((kSuite / "manifest.json").string()).entries) {
    const CheckReport report = check_stream(stream_of(e));
    EXPECT_EQ(report.conformant(), e.valid) << e.id;
    if (e.valid) {
      std::vector<std::string> warnings;
      for (const Finding& f : report.findings) warnings.push_back(format_finding(f));
      EXPECT_EQ(warnings, e.warnings) << e.id;
      continue;
    }
    ASSERT_FALSE(report.findings.empty()) << e.id;
    const Finding& first = *std::find_if(report.findings.begin(), report.findings.end(), [](const Finding& f) { return f.error; });
    EXPECT_EQ(to_string(first.kind), e.error_kind) << e.id << ": " << format_finding(first);
  }
}

// Violations in two planes, and two in one plane: the checker lists them all.
TEST(Conformance, CheckerListsEveryViolation) {
  const Manifest manifest = read_manifest((kSuite / "manifest.json").string());
  std::vector<uint8_t> stream;
  for (const ManifestEntry& e : manifest.entries)
    if (e.id == "p02-uniform-split0") stream = stream_of(e);
  ASSERT_EQ(stream.size() > 0, true);
  // Where each element lies, from the tracer.
  std::ostringstream text;
  Trace trace(text);
  syntax::read_mesh_object(stream, &trace);
  std::vector<std::tuple<uint64_t, std::string, int>> elements;
  std::istringstream lines(text.str());
  uint64_t offset;
  std::string name, value;
  int bits;
  while (lines >> offset >> name >> bits >> value) elements.push_back({offset, name, bits});
  auto set_bit = [&](uint64_t bit, bool one) {
    const uint8_t mask = static_cast<uint8_t>(0x80 >> (bit % 8));
    stream[bit / 8] = one ? stream[bit / 8] | mask : stream[bit / 8] & static_cast<uint8_t>(~mask);
  };
  int ranges = 0, stuffings = 0;
  for (const auto& [at, element, size] : elements) {
    if (element == "motion_range_code" && ranges++ == 0) set_bit(at, false), set_bit(at + 1, false);  // plane 1: range 0
    if (element == "next_start_code" && stuffings++ == 3) set_bit(at, true);                           // plane 3: stuffing
  }
  const CheckReport report = check_stream(stream);
  std::set<int64_t> planes;
  for (const Finding& f : report.findings)
    if (f.error) planes.insert(f.plane);
  EXPECT_EQ(planes, (std::set<int64_t>{1, 3})) << [&] {
    std::string all;
    for (const Finding& f : report.findings) all += format_finding(f) + "\n";
    return all;
  }();

  // A clockwise boundary with two coinciding nodes: both reported for plane 0.
  const std::vector<Point> nodes{{0, 0}, {100, 0}, {100, 100}, {0, 100}, {50, 50}, {50, 50}};
  MeshObject object;
  object.planes.resize(1);
  MeshGeometry& g = object.planes[0].geometry;
  g.mesh_type_code = kMeshTypeDelaunay;
  g.delaunay.nr_of_mesh_nodes = 6;
  g.delaunay.nr_of_boundary_nodes = 4;
  for (size_t i = 1; i < nodes.size(); ++i)
    g.delaunay.deltas.push_back({delta_code(nodes[i].x - nodes[i - 1].x), delta_code(nodes[i].y - nodes[i - 1].y)});
  const CheckReport geometry = check_stream(syntax::write_mesh_object(object));
  EXPECT_EQ(geometry.errors(), 2u);
  for (const Finding& f : geometry.findings) EXPECT_EQ(f.plane, 0);
}

TEST(Conformance, EmulationScan) {
  // 23 zeros then a one, at bit 3.
  const std::vector<uint8_t> bytes = test::bytes_from_bits("11100000 00000000 00000000 00110000");
  EXPECT_EQ(start_code_emulations(bytes, 0, 32), (std::vector<uint64_t>{3}));
  EXPECT_TRUE(start_code_emulations(bytes, 0, 26).empty());  // the '1' lies outside the range
  EXPECT_TRUE(start_code_emulations(test::bytes_from_bits("00000000 00000000 00000010"), 0, 24).empty());  // 22 zeros
}

}  // namespace
}  // namespace m4mesh
