// The 3D documents and the code cannot drift: every syntax table in the
// docs is the one the description writes (syntax/table_io.h), and every
// symbol of the arithmetic-coded data is named in its document.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <set>
#include <sstream>

#include "codecs3d/registry.h"
#include "common/atomic_file.h"
#include "conformance/manifest.h"
#include "syntax/mesh3d/affine_octree.h"
#include "syntax/mesh3d/base_mesh.h"
#include "syntax/mesh3d/bfs3d.h"
#include "syntax/mesh3d/container.h"
#include "syntax/mesh3d/cpca_wpt.h"
#include "syntax/mesh3d/lcc.h"
#include "syntax/table_io.h"

namespace m4mesh {
namespace {

namespace fs = std::filesystem;

std::string document(const std::string& name) {
  const std::vector<uint8_t> text = read_file((fs::path(M4MESH_SOURCE_DIR) / "docs" / name).string());
  return std::string(text.begin(), text.end());
}

// The table the description of T writes.
template <class T>
std::string table(const std::string& title) {
  syntax::TableIO io;
  T value;
  syntax::describe(io, value);
  return io.table(title);
}

template <class T>
void expect_table(const std::string& doc, const std::string& title) {
  const std::string expected = table<T>(title);
  EXPECT_NE(document(doc).find("```\n" + expected + "```"), std::string::npos)
      << "docs/" << doc << " lacks the table of " << title << "; the code describes it as:\n```\n" << expected << "```";
}

TEST(Docs, ContainerTablesMatchTheDescriptions) {
  expect_table<ObjectHeader>("container3d.md", "object_header");
  expect_table<UnitHeader>("container3d.md", "unit_header");
  expect_table<BaseMeshData>("base_mesh.md", "base_mesh_data");
  expect_table<FrameHash>("container3d.md", "frame_hash_data");
}

TEST(Docs, CodecTablesMatchTheDescriptions) {
  expect_table<Bfs3dHeader>("codec_bfs3d.md", "bfs3d_header");
  expect_table<Bfs3dFrame>("codec_bfs3d.md", "bfs3d_frame_data");
  expect_table<AffineOctreeHeader>("codec_affine_octree.md", "affine_octree_header");
  expect_table<AffineFrame>("codec_affine_octree.md", "affine_octree_frame_data");
  expect_table<LccHeader>("codec_lcc.md", "lcc_header");
  expect_table<LccFrameData>("codec_lcc.md", "lcc_frame_data");
  expect_table<CpcaHeader>("codec_cpca_wpt.md", "cpca_wpt_header");
  expect_table<CpcaRefinement>("codec_cpca_wpt.md", "cpca_wpt_refinement_data");
}

// A residual family is named by its element and its symbols: X_nonzero or
// X_* for every symbol (container3d.md names X_nonzero … X_suffix).
void expect_family(const char* doc, const syntax::ResidualNames& n) {
  const std::string text = document(doc), nonzero = n.nonzero;
  const std::string stem = nonzero.substr(0, nonzero.size() - std::string("_nonzero").size());
  EXPECT_TRUE(text.find(nonzero) != std::string::npos || text.find(stem + "_*") != std::string::npos) << doc << ": " << stem;
  EXPECT_NE(text.find(n.element), std::string::npos) << doc << ": " << n.element;
}

TEST(Docs, EverySymbolOfTheCodedDataIsNamed) {
  for (const char* symbol : {"X_nonzero", "X_prefix", "X_sign", "X_top", "X_suffix"})
    EXPECT_NE(document("container3d.md").find(symbol), std::string::npos) << symbol;
  expect_family("codec_bfs3d.md", syntax::kMotionResidual);
  for (const syntax::ResidualNames& n : {syntax::kMatrixResidual, syntax::kDirectMotion}) expect_family("codec_affine_octree.md", n);
  for (const char* name : {"split_flag", "direct_flag"}) EXPECT_NE(document("codec_affine_octree.md").find(name), std::string::npos) << name;
  for (const syntax::ResidualNames& n : {syntax::kLccDirect, syntax::kLccTheta, syntax::kLccRadius, syntax::kLccHeight}) expect_family("codec_lcc.md", n);
  for (const syntax::ResidualNames& n : {syntax::kCpcaCluster, syntax::kCpcaTranslation, syntax::kCpcaBasis, syntax::kCpcaCoefficient})
    expect_family("codec_cpca_wpt.md", n);
  for (const syntax::ResidualNames& n : {syntax::kPositionNames, syntax::kOrderNames, syntax::kFarNames}) expect_family("base_mesh.md", n);
  for (const char* name : {"seed_new_vertex", "seed_vertex", "gate_new_vertex", "gate_candidate", "candidate_index", "gate_border", "loose_vertex"})
    EXPECT_NE(document("base_mesh.md").find(name), std::string::npos) << name;
}

// The requirement lists of the docs ("| id | requirement | expect |
// streams |"): every stream a row names is in a suite and expects what the
// row says, or the row says why it has none.
TEST(Docs, EveryRequirementHasItsStreams) {
  std::map<std::string, ManifestEntry> streams;
  for (const char* suite : {"manifest.json", "mesh3d/manifest.json"})
    for (ManifestEntry& e : read_manifest((fs::path(M4MESH_SOURCE_DIR) / "conformance" / suite).string()).entries) streams[e.id] = e;
  const std::string header = "| id | requirement | expect | streams |";
  std::set<std::string> ids;
  size_t rows = 0, without = 0;
  for (const fs::directory_entry& doc : fs::directory_iterator(fs::path(M4MESH_SOURCE_DIR) / "docs")) {
    if (doc.path().extension() != ".md") continue;
    std::istringstream text(document(doc.path().filename().string()));
    bool in_table = false;
    for (std::string line; std::getline(text, line);) {
      if (line == header) {
        in_table = true;
        continue;
      }
      if (!in_table || line.rfind("|---", 0) == 0) continue;
      if (line.rfind("| ", 0) != 0) {
        in_table = false;
        continue;
      }
      std::vector<std::string> cells;
      for (size_t at = 2, bar; (bar = line.find(" |", at)) != std::string::npos; at = bar + 3) cells.push_back(line.substr(at, bar - at));
      ASSERT_EQ(cells.size(), 4u) << doc.path().filename() << ": " << line;
      const std::string where = doc.path().filename().string() + " " + cells[0];
      EXPECT_TRUE(ids.insert(cells[0]).second) << where << ": the id is taken";
      ++rows;
      if (cells[3].rfind("none: ", 0) == 0) {
        ++without;
        continue;
      }
      std::istringstream expect(cells[2]);
      std::string verdict, kind, element;
      expect >> verdict >> kind >> element;
      ASSERT_TRUE(verdict == "decode" || (verdict == "reject" && !element.empty())) << where << ": expect is 'decode' or 'reject KIND ELEMENT'";
      std::istringstream names(cells[3]);
      for (std::string id; std::getline(names >> std::ws, id, ',');) {
        const auto found = streams.find(id);
        if (found == streams.end()) {
          ADD_FAILURE() << where << ": no stream " << id;
          continue;
        }
        const ManifestEntry& e = found->second;
        if (verdict == "decode")
          EXPECT_TRUE(e.valid) << where << ": " << id << " is a stream to reject";
        else
          EXPECT_TRUE(!e.valid && e.error_kind == kind && e.error_element == element)
              << where << ": " << id << " expects " << (e.valid ? "to decode" : e.error_kind + " " + e.error_element);
      }
    }
  }
  EXPECT_GE(rows, 30u);
  std::printf("%zu requirements listed, %zu with streams\n", rows, rows - without);
}

TEST(Docs, EveryCodecHasItsDocument) {
  for (const Codec3d& c : codecs3d()) {
    if (c.doc.rfind("docs/", 0) != 0) continue;
    EXPECT_TRUE(fs::exists(fs::path(M4MESH_SOURCE_DIR) / c.doc)) << c.name << ": " << c.doc;
  }
}

}  // namespace
}  // namespace m4mesh
