// Tracing a stream one part at a time (the web analyzer, `m4mesh trace
// --part`) and its fixed fields alone (`--fields-only`) give exactly the
// lines of the whole trace that belong there.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "conformance/suite.h"
#include "conformance/suite3d/suite3d.h"
#include "decoder/stream_trace.h"
#include "syntax/mesh3d/container.h"
#include "syntax/mesh3d/cpca_wpt.h"
#include "syntax/trace.h"

namespace m4mesh {
namespace {

std::vector<std::string> trace_lines(std::span<const uint8_t> stream, const TraceSelection& selection = {}) {
  std::ostringstream text;
  trace_stream(stream, text, selection);
  std::vector<std::string> lines;
  std::istringstream in(text.str());
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// The whole trace's lines of part `part`, read from the text: a 3D line's
// unit, or the 2D planes counted at their start codes; no end code.
std::vector<std::string> lines_of_part(const std::vector<std::string>& whole, int64_t part) {
  std::vector<std::string> kept;
  int64_t plane = -1;
  for (const std::string& line : whole) {
    const std::optional<TraceLine> t = parse_trace_line(line);
    if (!t || t->name == "mesh_object_end_code") continue;
    if (t->name == "mesh_object_plane_start_code") ++plane;
    const bool mesh3d = line.starts_with("unit ") || line.starts_with("object ");
    if ((mesh3d ? t->unit : plane) == part) kept.push_back(line);
  }
  return kept;
}

// The parts to try: the header, the first two, one in the middle, the last, one past it.
std::vector<int64_t> parts_to_try(int64_t parts) { return {-1, 0, 1, parts / 2, parts - 1, parts}; }

// Returns whether the fields-only trace leaves lines out.
bool expect_parts_alike(const std::string& id, std::span<const uint8_t> stream, int64_t parts) {
  const std::vector<std::string> whole = trace_lines(stream);
  for (int64_t part : parts_to_try(parts)) {
    std::vector<std::string> traced = trace_lines(stream, {.part = part, .symbols = true});
    std::erase_if(traced, [](const std::string& line) { return line.find("mesh_object_end_code") != std::string::npos; });
    EXPECT_EQ(traced, lines_of_part(whole, part)) << id << " part " << part;
  }
  std::vector<std::string> fields = whole;
  std::erase_if(fields, [](const std::string& line) {
    const std::optional<TraceLine> t = parse_trace_line(line);
    return t && t->position.find(':') != std::string::npos;
  });
  const std::vector<std::string> fields_only = trace_lines(stream, {.part = std::nullopt, .symbols = false});
  EXPECT_EQ(fields_only, fields) << id << " fields only";
  return fields_only.size() < whole.size();
}

TEST(StreamTrace, A3dPartIsItsUnitsLinesOfTheWholeTrace) {
  size_t streams = 0, with_symbols = 0;
  for (const SuiteCase& c : build_suite3d()) {
    if (!c.valid) continue;
    const ContainerParts container = split_container(c.stream);
    with_symbols += expect_parts_alike(c.id, c.stream, static_cast<int64_t>(container.units.size()));
    ++streams;
  }
  EXPECT_GE(streams, 100u);
  EXPECT_GE(with_symbols, 100u);  // the fields-only traces do leave lines out
}

// The analyzer's unit names (unit_labels3d) against what the trace reads of
// each unit: its unit_type, frame_index, and a cpca-wpt refinement's cluster
// and unit_kind, or a group's size.
TEST(StreamTrace, UnitLabelsNameWhatEachUnitsHeaderSays) {
  size_t refinements = 0, groups = 0;
  for (const SuiteCase& c : build_suite3d()) {
    if (!c.valid) continue;
    const std::vector<std::string> labels = unit_labels3d(c.stream);
    ASSERT_EQ(labels.size(), split_container(c.stream).units.size()) << c.id;
    std::vector<std::map<std::string, std::string>> fields(labels.size());
    for (const std::string& line : trace_lines(c.stream))
      if (const std::optional<TraceLine> t = parse_trace_line(line); t && t->unit >= 0 && !fields[static_cast<size_t>(t->unit)].count(t->name))
        fields[static_cast<size_t>(t->unit)][t->name] = t->value;
    for (size_t k = 0; k < labels.size(); ++k) {
      const UnitType type = static_cast<UnitType>(std::stoul(fields[k].at("unit_type")));
      std::string expected = unit_type_name(type);
      if (type != UnitType::kRefinement) {
        expected += ", frame " + fields[k].at("frame_index");
      } else if (fields[k].count("group_size")) {
        expected += ", group of " + fields[k].at("group_size");
        ++groups;
      } else if (fields[k].count("unit_kind")) {
        expected += ", cluster " + fields[k].at("cluster") + " " + cpca_unit_kind_name(static_cast<uint32_t>(std::stoul(fields[k].at("unit_kind"))));
        ++refinements;
      }
      EXPECT_EQ(labels[k], expected) << c.id << " unit " << k;
    }
  }
  EXPECT_GT(refinements, 100u);
  EXPECT_GT(groups, 8u);
}

TEST(StreamTrace, A2dPartIsItsPlanesLinesOfTheWholeTrace) {
  size_t streams = 0;
  for (const SuiteCase& c : build_suite()) {
    if (!c.valid) continue;
    const std::vector<std::string> whole = trace_lines(c.stream);
    const int64_t planes = std::count_if(whole.begin(), whole.end(), [](const std::string& l) { return l.find("mesh_object_plane_start_code") != std::string::npos; });
    expect_parts_alike(c.id, c.stream, planes);
    ++streams;
  }
  EXPECT_GE(streams, 30u);
}

}  // namespace
}  // namespace m4mesh
