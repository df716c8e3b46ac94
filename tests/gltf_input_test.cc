// glTF animations in (encode3d anim.glb): assets built here with
// tinygltf, morph targets and a skin, baked to the positions worked out by
// hand, and the errors for what cannot be taken. (m4mesh's own glTF read
// back: gltf_test.cc.) And `m4mesh gltf` (compress_gltf) on such assets:
// the streams it writes for a morph-target animation, and its errors.
#include <gtest/gtest.h>
#include <tiny_gltf.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <optional>
#include <sstream>

#include "cli/app.h"
#include "cli/gltf.h"
#include "cli/gltf_compress.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "decoder/mesh3d/container_decoder.h"
#include "encoder/mesh3d/container_encoder.h"
#include "tests/test_util.h"

namespace m4mesh {
namespace {

namespace fs = std::filesystem;

const std::vector<float> kTetrahedron{0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
// save_morphing_tetrahedron's two morph targets.
const std::vector<float> kUp{0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}, kOut{1, 0, 0, 2, 0, 0, 3, 0, 0, 4, 0, 0};

class GltfInput : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ = fs::temp_directory_path() / ("m4mesh-gltf-in-" + std::to_string(::getpid()));
    fs::create_directories(folder_);
    model_.asset.version = "2.0";
    model_.buffers.resize(1);
  }
  void TearDown() override { fs::remove_all(folder_); }

  int accessor(const std::vector<float>& values, int type) {
    return add(values.data(), values.size() * sizeof(float), values.size() / static_cast<size_t>(tinygltf::GetNumComponentsInType(static_cast<uint32_t>(type))), type,
               TINYGLTF_COMPONENT_TYPE_FLOAT);
  }
  int accessor(const std::vector<uint16_t>& values, int type) {
    return add(values.data(), values.size() * sizeof(uint16_t), values.size() / static_cast<size_t>(tinygltf::GetNumComponentsInType(static_cast<uint32_t>(type))), type,
               TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
  }

  // A tetrahedron's primitive: positions (x y z per vertex) and its four faces.
  tinygltf::Primitive tetrahedron(const std::vector<float>& positions) {
    tinygltf::Primitive p;
    p.mode = TINYGLTF_MODE_TRIANGLES;
    p.attributes["POSITION"] = accessor(positions, TINYGLTF_TYPE_VEC3);
    p.indices = accessor(std::vector<uint16_t>{0, 1, 2, 0, 3, 1, 0, 2, 3, 1, 3, 2}, TINYGLTF_TYPE_SCALAR);
    return p;
  }

  int add_node(tinygltf::Node node) {
    model_.nodes.push_back(std::move(node));
    return static_cast<int>(model_.nodes.size() - 1);
  }

  void animate(int node, const std::string& path, const std::vector<float>& times, const std::vector<float>& values, const std::string& interpolation = "LINEAR") {
    if (model_.animations.empty()) model_.animations.emplace_back().name = "move";
    tinygltf::Animation& a = model_.animations.back();
    tinygltf::AnimationSampler s;
    s.input = accessor(times, TINYGLTF_TYPE_SCALAR);
    const int width = path == "rotation" ? TINYGLTF_TYPE_VEC4 : path == "weights" ? TINYGLTF_TYPE_SCALAR : TINYGLTF_TYPE_VEC3;
    s.output = accessor(values, width);
    s.interpolation = interpolation;
    a.samplers.push_back(s);
    tinygltf::AnimationChannel c;
    c.sampler = static_cast<int>(a.samplers.size() - 1);
    c.target_node = node;
    c.target_path = path;
    a.channels.push_back(c);
  }

  std::string save(const std::string& name) {
    tinygltf::Scene scene;
    for (size_t n = 0; n < model_.nodes.size(); ++n) {
      bool child = false;
      for (const tinygltf::Node& other : model_.nodes) child |= std::count(other.children.begin(), other.children.end(), static_cast<int>(n)) > 0;
      if (!child) scene.nodes.push_back(static_cast<int>(n));
    }
    model_.scenes = {scene};
    model_.defaultScene = 0;
    const std::string path = (folder_ / name).string();
    std::ostringstream out;
    tinygltf::TinyGLTF writer;
    EXPECT_TRUE(writer.WriteGltfSceneToStream(&model_, out, false, name.ends_with(".glb")));
    write_file_atomically(path, out.str());
    return path;
  }

  // A tetrahedron (in `mesh`) with the morph targets kUp and kOut weighted 0, 1
  // then ½ each (LINEAR) at 0, 1 and 2 s, on node 0, moved by (1, 2, 3); saved as morph.glb.
  std::string save_morphing_tetrahedron(tinygltf::Mesh mesh) {
    tinygltf::Primitive p = tetrahedron(kTetrahedron);
    p.targets = {{{"POSITION", accessor(kUp, TINYGLTF_TYPE_VEC3)}}, {{"POSITION", accessor(kOut, TINYGLTF_TYPE_VEC3)}}};
    mesh.primitives.push_back(p);
    model_.meshes.push_back(mesh);
    tinygltf::Node node;
    node.mesh = 0;
    node.translation = {1, 2, 3};
    animate(add_node(node), "weights", {0, 1, 2}, {0, 0, 1, 0, 0.5f, 0.5f});
    return save("morph.glb");
  }

  // A tetrahedron ("arm", on node 2, itself moved by (100, 100, 100), which a skin ignores) skinned to two joints:
  // a root that slides (0, 0, 0) → (2, 0, 0) and its child, one up, that turns 90° about z, over 0 … 1 s.
  std::string save_skinned_arm(const std::string& name) {
    tinygltf::Mesh mesh;
    mesh.name = "arm";
    tinygltf::Primitive p = tetrahedron({0, 0, 0, 1, 1, 0, 0, 1, 0, 0, 2, 1});
    p.attributes["JOINTS_0"] = accessor(std::vector<uint16_t>{0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 1, 0, 0, 0}, TINYGLTF_TYPE_VEC4);
    p.attributes["WEIGHTS_0"] = accessor(std::vector<float>{1, 0, 0, 0, 1, 0, 0, 0, 0.5f, 0.5f, 0, 0, 1, 0, 0, 0}, TINYGLTF_TYPE_VEC4);
    mesh.primitives.push_back(p);
    model_.meshes.push_back(mesh);
    tinygltf::Node root, child, skinned;
    root.name = "root";
    child.name = "child";
    child.translation = {0, 1, 0};
    const int c = add_node(child);
    root.children = {c};
    const int r = add_node(root);
    skinned.mesh = 0;
    skinned.skin = 0;
    skinned.translation = {100, 100, 100};  // a skinned mesh's own node transform is ignored (glTF 2.0, 3.7.3)
    add_node(skinned);
    tinygltf::Skin skin;
    skin.joints = {r, c};
    const std::vector<float> inverse_bind{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1,   // root: bound at the origin
                                          1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -1, 0, 1};  // child: bound one up
    skin.inverseBindMatrices = accessor(inverse_bind, TINYGLTF_TYPE_MAT4);
    model_.skins.push_back(skin);
    animate(r, "translation", {0, 1}, {0, 0, 0, 2, 0, 0});
    const float s = static_cast<float>(std::sqrt(0.5));
    animate(c, "rotation", {0, 1}, {0, 0, 0, 1, 0, 0, s, s});
    return save(name);
  }

  // The error reading `path` gives, or "" when it reads.
  static std::string error_of(const std::string& path, const GltfSelection& selection = {}) {
    try {
      read_gltf(path, selection);
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  }

  static void expect_near(const Vec3& p, double x, double y, double z, const std::string& where) {
    EXPECT_NEAR(p.x, x, 1e-6) << where;
    EXPECT_NEAR(p.y, y, 1e-6) << where;
    EXPECT_NEAR(p.z, z, 1e-6) << where;
  }

  fs::path folder_;
  tinygltf::Model model_;

 private:
  int add(const void* data, size_t bytes, size_t count, int type, int component) {
    std::vector<unsigned char>& buffer = model_.buffers[0].data;
    const size_t offset = buffer.size();
    buffer.resize(offset + bytes + (4 - bytes % 4) % 4);
    std::memcpy(buffer.data() + offset, data, bytes);
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = offset;
    view.byteLength = bytes;
    model_.bufferViews.push_back(view);
    tinygltf::Accessor a;
    a.bufferView = static_cast<int>(model_.bufferViews.size() - 1);
    a.componentType = component;
    a.count = count;
    a.type = type;
    if (type == TINYGLTF_TYPE_SCALAR && component == TINYGLTF_COMPONENT_TYPE_FLOAT && count > 0) {
      const auto* f = static_cast<const float*>(data);
      a.minValues = {*std::min_element(f, f + count)};
      a.maxValues = {*std::max_element(f, f + count)};
    }
    model_.accessors.push_back(a);
    return static_cast<int>(model_.accessors.size() - 1);
  }
};

GltfSelection pick(const std::string& mesh, std::optional<double> fps = std::nullopt) { return {.mesh = mesh, .animation = "", .fps = fps}; }

// Two morph targets weighted 0, 1 then ½ each (LINEAR), on a node moved by
// (1, 2, 3): at 2 frames a second, every frame is base + Σ wₖ targetₖ + (1, 2, 3).
TEST_F(GltfInput, MorphTargetsBakeAsTheirWeightsSay) {
  tinygltf::Mesh mesh;
  mesh.name = "blob";
  const std::string path = save_morphing_tetrahedron(mesh);

  const GltfAnimation baked = read_gltf(path, pick("", 2.0));
  EXPECT_EQ(baked.fps, 2.0);
  ASSERT_EQ(baked.sequence.frames.size(), 5u);  // 0, 0.5, 1, 1.5, 2 s
  EXPECT_EQ(baked.sequence.faces.size(), 4u);
  const double w_up[] = {0, 0.5, 1, 0.75, 0.5}, w_out[] = {0, 0, 0, 0.25, 0.5};
  for (size_t f = 0; f < 5; ++f)
    for (size_t v = 0; v < 4; ++v)
      expect_near(baked.sequence.frames[f][v], kTetrahedron[3 * v] + w_out[f] * kOut[3 * v] + 1, kTetrahedron[3 * v + 1] + 2,
                  kTetrahedron[3 * v + 2] + w_up[f] + 3, "frame " + std::to_string(f) + " vertex " + std::to_string(v));
  // At its keyframes (evenly spaced, one a second): three frames at 1 fps.
  const GltfAnimation keys = read_gltf(path, {});
  EXPECT_EQ(keys.fps, 1.0);
  EXPECT_EQ(keys.sequence.frames.size(), 3u);
  // Within limits: 5 frames of 4 vertices are 20 positions; the weights make 4 × (1 + 0, 1, 1, 2, 2) vertex operations.
  EXPECT_NO_THROW(read_gltf(path, pick("", 2.0), {.most_positions = 20, .most_work = 4 * 11}));
  EXPECT_THROW(read_gltf(path, pick("", 2.0), {.most_positions = 19, .most_work = 4 * 11}), Error);
  try {
    read_gltf(path, pick("", 2.0), {.most_positions = 20, .most_work = 4 * 11 - 1});
    ADD_FAILURE() << "baked past the limit";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("over 43 vertex operations to bake"), std::string::npos) << e.what();
  }
}

// Two joints: the root slides by (2, 0, 0) over a second, its child (bound
// one up) turns 90° about z. Vertex 0 follows the root, 1 and 3 the child,
// 2 half each; at t = 1 the child's vertex (1, 1, 0) is at (2, 2, 0).
TEST_F(GltfInput, ASkinBakesByLinearBlendSkinning) {
  const std::string path = save_skinned_arm("skin.gltf");
  const GltfAnimation baked = read_gltf(path, {});
  ASSERT_EQ(baked.sequence.frames.size(), 2u);
  const std::vector<Vec3>& rest = baked.sequence.frames[0];
  expect_near(rest[0], 0, 0, 0, "rest 0");
  expect_near(rest[1], 1, 1, 0, "rest 1");
  expect_near(rest[3], 0, 2, 1, "rest 3");
  const std::vector<Vec3>& moved = baked.sequence.frames[1];
  expect_near(moved[0], 2, 0, 0, "moved 0");
  expect_near(moved[1], 2, 2, 0, "moved 1");  // (1, 0, 0) from the joint turned to (0, 1, 0), plus (2, 1, 0)
  expect_near(moved[3], 1, 1, 1, "moved 3");  // (0, 1, 1) from the joint turned to (−1, 0, 1), plus (2, 1, 0)
  // Half on each: the root takes (0, 1, 0) to (2, 1, 0); the child to (2 − 0, 1 + 0, 0) = (2, 1, 0) too: (0, 1, 0) is the joint itself.
  expect_near(moved[2], 2, 1, 0, "moved 2");
  // Between the keys: half the slide, the turn by 45° (spherical).
  const float s = static_cast<float>(std::sqrt(0.5));
  const GltfAnimation half = read_gltf(path, pick("", 2.0));
  ASSERT_EQ(half.sequence.frames.size(), 3u);
  expect_near(half.sequence.frames[1][1], 1 + s, 1 + s, 0, "half-way 1");
}

// The skinned arm compressed with --bake-skins: the node loses its skin and its mesh the joints and weights; the
// joints keep their channels; the stream's frames are the skinned positions in the node's own space (less its
// (100, 100, 100)), so that its transform puts them where the skin did. Without --bake-skins, the error says so.
TEST_F(GltfInput, ABakedSkinIsAStreamInItsNodesSpace) {
  const std::string path = save_skinned_arm("skin.glb");
  GltfCompressArgs args;
  args.encoding.codec = "bfs3d";
  try {
    compress_gltf(path, args);
    ADD_FAILURE() << "a skin compressed without --bake-skins";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("baked with --bake-skins"), std::string::npos) << e.what();
  }
  args.bake_skins = true;
  const GltfCompressResult compressed = compress_gltf(path, args);
  ASSERT_EQ(compressed.streams.size(), 1u);
  EXPECT_EQ(compressed.streams[0].replaced_bytes, 16 * sizeof(uint16_t) + 16 * sizeof(float));  // JOINTS_0 and WEIGHTS_0
  tinygltf::Model model;
  std::string error, warning;
  ASSERT_TRUE(tinygltf::TinyGLTF().LoadBinaryFromMemory(&model, &error, &warning, compressed.glb.data(), static_cast<unsigned>(compressed.glb.size())))
      << error;
  EXPECT_EQ(model.nodes[2].skin, -1);
  EXPECT_EQ(model.skins.size(), 1u);
  EXPECT_EQ(model.meshes[0].primitives[0].attributes.count("JOINTS_0"), 0u);
  EXPECT_EQ(model.meshes[0].primitives[0].attributes.count("WEIGHTS_0"), 0u);
  EXPECT_EQ(model.animations[0].channels.size(), 2u);
  const tinygltf::Value& channel = model.animations[0].extensions.at(kGltfExtensionName).Get("channels").Get(0);
  EXPECT_EQ(channel.Get("node").GetNumberAsInt(), 2);
  EXPECT_EQ(channel.Get("interpolation").Get<std::string>(), "LINEAR");
  EXPECT_EQ(model.accessors[static_cast<size_t>(channel.Get("input").GetNumberAsInt())].count, 2u);
  const tinygltf::BufferView& view = model.bufferViews[static_cast<size_t>(channel.Get("primitives").Get(0).Get("bufferView").GetNumberAsInt())];
  const MeshSequence decoded = decode_mesh3d(std::span<const uint8_t>(model.buffers[0].data.data() + view.byteOffset, view.byteLength));
  ASSERT_EQ(decoded.frames.size(), 2u);
  const double world[2][4][3] = {{{0, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 2, 1}}, {{2, 0, 0}, {2, 2, 0}, {2, 1, 0}, {1, 1, 1}}};
  for (size_t f = 0; f < 2; ++f)
    for (size_t v = 0; v < 4; ++v) {
      EXPECT_NEAR(decoded.frames[f][v].x, world[f][v][0] - 100, 1e-2) << f << " " << v;
      EXPECT_NEAR(decoded.frames[f][v].y, world[f][v][1] - 100, 1e-2) << f << " " << v;
      EXPECT_NEAR(decoded.frames[f][v].z, world[f][v][2] - 100, 1e-2) << f << " " << v;
    }
}

TEST_F(GltfInput, WhatCannotBeTakenIsNamed) {
  tinygltf::Mesh a, b;
  a.name = "left";
  b.name = "right";
  a.primitives.push_back(tetrahedron(kTetrahedron));
  b.primitives.push_back(tetrahedron(kTetrahedron));
  model_.meshes = {a, b};
  tinygltf::Node left, right;
  left.mesh = 0;
  right.mesh = 1;
  right.name = "right node";
  const int l = add_node(left);
  add_node(right);
  const std::string still = save("still.glb");
  EXPECT_NE(error_of(still).find("2 meshes ('left', 'right node'): choose one with --mesh NAME"), std::string::npos) << error_of(still);
  EXPECT_NE(error_of(still, pick("left")).find("no animation"), std::string::npos) << error_of(still, pick("left"));
  EXPECT_NE(error_of(still, pick("middle")).find("no node or mesh is named 'middle'"), std::string::npos);

  animate(l, "translation", {0, 1, 3}, {0, 0, 0, 1, 0, 0, 2, 0, 0});
  const std::string uneven = save("uneven.glb");
  EXPECT_NE(error_of(uneven, pick("right")).find("keyframes are not evenly spaced"), std::string::npos) << error_of(uneven, pick("right"));
  EXPECT_EQ(error_of(uneven, pick("right", 10.0)), "");
  EXPECT_EQ(read_gltf(uneven, pick("left", 10.0)).sequence.frames.size(), 31u);

  model_.meshes[1].primitives[0].mode = TINYGLTF_MODE_LINE;
  const std::string lines = save("lines.glb");
  EXPECT_NE(error_of(lines, pick("right", 10.0)).find("mesh 'right', primitive 0 is not of triangles (mode 1)"), std::string::npos);

  model_.meshes[1].primitives[0].mode = TINYGLTF_MODE_TRIANGLES;
  model_.accessors[static_cast<size_t>(model_.meshes[1].primitives[0].attributes["POSITION"])].count = 1000;
  const std::string short_buffer = save("short.gltf");
  const std::string message = error_of(short_buffer, pick("right", 10.0));
  EXPECT_TRUE(message.find("past the end") != std::string::npos || message.find("not a glTF 2.0 asset m4mesh can read") != std::string::npos) << message;

  // A component type glTF does not have (INT, 4 bytes): refused, not read as another's size (found by fuzzing).
  model_.accessors[static_cast<size_t>(model_.meshes[1].primitives[0].attributes["POSITION"])].count = 4;
  model_.accessors[static_cast<size_t>(model_.meshes[1].primitives[0].attributes["POSITION"])].componentType = 5124;
  const std::string int_positions = save("int.glb");
  EXPECT_NE(error_of(int_positions, pick("right", 10.0)).find("component type 5124 is not glTF's"), std::string::npos) << error_of(int_positions, pick("right", 10.0));

  // A position that is not a number: refused, not coded.
  model_.accessors[static_cast<size_t>(model_.meshes[1].primitives[0].attributes["POSITION"])].componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
  const float not_a_number = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(model_.buffers[0].data.data() + model_.bufferViews[static_cast<size_t>(model_.accessors[static_cast<size_t>(
      model_.meshes[1].primitives[0].attributes["POSITION"])].bufferView)].byteOffset, &not_a_number, sizeof not_a_number);
  const std::string nan = save("nan.glb");
  EXPECT_NE(error_of(nan, pick("right", 10.0)).find("vertex 0 at 0.000000 s is not a finite float32 position"), std::string::npos) << error_of(nan, pick("right", 10.0));

  EXPECT_NE(error_of((folder_ / "none.glb").string()).find("no such file"), std::string::npos);
  write_file_atomically((folder_ / "text.glb").string(), std::string("not a glb"));
  EXPECT_NE(error_of((folder_ / "text.glb").string()).find("not a glTF 2.0 asset"), std::string::npos);
}

// The morph animation above, compressed: the weights channel, the targets
// and the default weights go; the extension names the node, the times and
// a stream whose frames are base + Σ wₖ targetₖ at the keys (within the
// codec's error), the node's translation not applied.
TEST_F(GltfInput, CompressedMorphTargetsAreStreamsOfTheFramesAtTheirKeys) {
  tinygltf::Mesh mesh;
  mesh.weights = {0, 0};
  const std::string path = save_morphing_tetrahedron(mesh);

  GltfCompressArgs args;
  args.encoding.codec = "bfs3d";
  const GltfCompressResult compressed = compress_gltf(path, args);
  ASSERT_EQ(compressed.streams.size(), 1u);
  EXPECT_EQ(compressed.streams[0].frames, 3u);
  tinygltf::Model model;
  std::string error, warning;
  ASSERT_TRUE(tinygltf::TinyGLTF().LoadBinaryFromMemory(&model, &error, &warning, compressed.glb.data(), static_cast<unsigned>(compressed.glb.size())))
      << error;
  EXPECT_TRUE(model.meshes[0].primitives[0].targets.empty());
  EXPECT_TRUE(model.meshes[0].weights.empty());
  EXPECT_EQ(std::count(model.extensionsUsed.begin(), model.extensionsUsed.end(), kGltfExtensionName), 1);
  EXPECT_TRUE(model.extensionsRequired.empty());
  // The animation keeps one channel, the node's translation held.
  ASSERT_EQ(model.animations[0].channels.size(), 1u);
  EXPECT_EQ(model.animations[0].channels[0].target_path, "translation");
  const tinygltf::Value& channel = model.animations[0].extensions.at(kGltfExtensionName).Get("channels").Get(0);
  EXPECT_EQ(channel.Get("node").GetNumberAsInt(), 0);
  EXPECT_EQ(channel.Get("interpolation").Get<std::string>(), "LINEAR");
  const tinygltf::Accessor& times = model.accessors[static_cast<size_t>(channel.Get("input").GetNumberAsInt())];
  EXPECT_EQ(times.count, 3u);
  const tinygltf::BufferView& view = model.bufferViews[static_cast<size_t>(channel.Get("primitives").Get(0).Get("bufferView").GetNumberAsInt())];
  const std::span<const uint8_t> stream(model.buffers[0].data.data() + view.byteOffset, view.byteLength);
  const MeshSequence decoded = decode_mesh3d(stream);
  ASSERT_EQ(decoded.frames.size(), 3u);
  const double w_up[] = {0, 1, 0.5}, w_out[] = {0, 0, 0.5};
  for (size_t f = 0; f < 3; ++f)
    for (size_t v = 0; v < 4; ++v) {
      const Vec3 q = decoded.frames[f][v];
      EXPECT_NEAR(q.x, kTetrahedron[3 * v] + w_out[f] * kOut[3 * v], 1e-2) << f << " " << v;
      EXPECT_NEAR(q.y, kTetrahedron[3 * v + 1], 1e-2) << f << " " << v;
      EXPECT_NEAR(q.z, kTetrahedron[3 * v + 2] + w_up[f], 1e-2) << f << " " << v;
    }
  // Compressed once is enough.
  const std::string again = (folder_ / "again.glb").string();
  write_file_atomically(again, std::string(compressed.glb.begin(), compressed.glb.end()));
  try {
    compress_gltf(again, args);
    ADD_FAILURE() << "compressed twice";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("uses M4MESH_vertex_animation already"), std::string::npos) << e.what();
  }
}

// Two primitives sharing one morph target's accessor: the report counts its view once.
TEST_F(GltfInput, ReplacedBytesCountEachViewOnce) {
  tinygltf::Mesh mesh;
  tinygltf::Primitive p = tetrahedron(kTetrahedron);
  p.targets = {{{"POSITION", accessor(kUp, TINYGLTF_TYPE_VEC3)}}};
  mesh.primitives = {p, p};
  model_.meshes.push_back(mesh);
  tinygltf::Node node;
  node.mesh = 0;
  animate(add_node(node), "weights", {0, 1}, {0, 1});
  GltfCompressArgs args;
  args.encoding.codec = "bfs3d";
  const GltfCompressResult compressed = compress_gltf(save("shared.glb"), args);
  ASSERT_EQ(compressed.streams.size(), 2u);
  EXPECT_EQ(compressed.streams[0].replaced_bytes + compressed.streams[1].replaced_bytes, kUp.size() * sizeof(float) + 2 * sizeof(float));
}

TEST_F(GltfInput, WhatTheCompressorCannotTakeIsNamed) {
  auto error_compressing = [&](const std::string& path) -> std::string {
    try {
      GltfCompressArgs args;
      args.encoding.codec = "bfs3d";
      compress_gltf(path, args);
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  };
  tinygltf::Mesh mesh;
  mesh.name = "blob";
  tinygltf::Primitive p = tetrahedron(kTetrahedron);
  p.targets = {{{"POSITION", accessor(std::vector<float>(12, 0.5f), TINYGLTF_TYPE_VEC3)}}};
  mesh.primitives = {p, p};
  model_.meshes.push_back(mesh);
  tinygltf::Node node;
  node.mesh = 0;
  animate(add_node(node), "weights", {0, 1}, {0, 1});
  model_.meshes[0].primitives[1].mode = TINYGLTF_MODE_POINTS;
  const std::string points = save("points.glb");
  EXPECT_NE(error_compressing(points).find("mesh 0 'blob', primitive 1 is not of triangles (mode 0)"), std::string::npos) << error_compressing(points);

  model_.meshes[0].primitives[1].mode = TINYGLTF_MODE_TRIANGLES;
  model_.meshes[0].primitives[1].targets[0]["POSITION"] = accessor(std::vector<float>(9, 0.5f), TINYGLTF_TYPE_VEC3);
  const std::string short_target = save("short-target.glb");
  EXPECT_NE(error_compressing(short_target).find("mesh 0 'blob', primitive 1, morph target 0: 3 positions for 4 vertices"), std::string::npos)
      << error_compressing(short_target);

  model_.extensionsUsed = {"EXT_meshopt_compression"};
  const std::string meshopt = save("meshopt.glb");
  EXPECT_NE(error_compressing(meshopt).find("decompress it first"), std::string::npos) << error_compressing(meshopt);

  model_.extensionsUsed.clear();
  model_.animations.clear();
  const std::string still = save("still.glb");
  EXPECT_NE(error_compressing(still).find("no animation drives morph targets"), std::string::npos) << error_compressing(still);
}

}  // namespace
}  // namespace m4mesh
