// The 3D documents and the code cannot drift: every syntax table in the
// docs is the one the description writes (syntax/table_io.h), and every
// symbol of the arithmetic-coded data is named in its document.
#include <gtest/gtest.h>

#include <filesystem>

#include "codecs3d/registry.h"
#include "common/atomic_file.h"
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

TEST(Docs, EverySymbolOfTheCodedDataIsNamed) {
  for (const syntax::ResidualNames& n : {syntax::kMotionResidual})
    for (const char* name : {n.nonzero, n.prefix, n.sign_suffix, n.element}) EXPECT_NE(document("codec_bfs3d.md").find(name), std::string::npos) << name;
  for (const syntax::ResidualNames& n : {syntax::kMatrixResidual, syntax::kDirectMotion})
    for (const char* name : {n.nonzero, n.prefix, n.sign_suffix, n.element})
      EXPECT_NE(document("codec_affine_octree.md").find(name), std::string::npos) << name;
  for (const char* name : {"split_flag", "direct_flag"}) EXPECT_NE(document("codec_affine_octree.md").find(name), std::string::npos) << name;
  for (const syntax::ResidualNames& n : {syntax::kLccDirect, syntax::kLccTheta, syntax::kLccRadius, syntax::kLccHeight})
    for (const char* name : {n.nonzero, n.prefix, n.sign_suffix, n.element}) EXPECT_NE(document("codec_lcc.md").find(name), std::string::npos) << name;
  for (const syntax::ResidualNames& n : {syntax::kCpcaCluster, syntax::kCpcaTranslation, syntax::kCpcaBasis, syntax::kCpcaCoefficient})
    for (const char* name : {n.nonzero, n.prefix, n.sign_suffix, n.element})
      EXPECT_NE(document("codec_cpca_wpt.md").find(name), std::string::npos) << name;
  for (const syntax::ResidualNames& n : {syntax::kPositionNames, syntax::kOrderNames, syntax::kFarNames})
    for (const char* name : {n.nonzero, n.prefix, n.sign_suffix, n.element}) EXPECT_NE(document("base_mesh.md").find(name), std::string::npos) << name;
  for (const char* name : {"seed_new_vertex", "seed_vertex", "gate_new_vertex", "gate_candidate", "candidate_index", "gate_border", "loose_vertex"})
    EXPECT_NE(document("base_mesh.md").find(name), std::string::npos) << name;
}

TEST(Docs, EveryCodecHasItsDocument) {
  for (const Codec3d& c : codecs3d()) {
    if (c.doc.rfind("docs/", 0) != 0) continue;
    EXPECT_TRUE(fs::exists(fs::path(M4MESH_SOURCE_DIR) / c.doc)) << c.name << ": " << c.doc;
  }
}

}  // namespace
}  // namespace m4mesh
