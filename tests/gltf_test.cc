// A decoded stream as a glTF animation (decode3d -o anim.glb / .gltf),
// read back by tinygltf: every frame's positions bit for bit, in the
// stream's vertex order, the faces, and a STEP weights animation at the
// stream's frame rate; and by m4mesh's own glTF input, the same frames.
#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <cstring>
#include <filesystem>

#include "cli/app.h"
#include "cli/gltf.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "decoder/mesh3d/container_decoder.h"
#include "encoder/mesh3d/container_encoder.h"
#include "tests/test_util.h"

namespace m4mesh {
namespace {

namespace fs = std::filesystem;

template <class T>
std::vector<T> accessor_values(const tinygltf::Model& model, int index) {
  const tinygltf::Accessor& accessor = model.accessors.at(static_cast<size_t>(index));
  const tinygltf::BufferView& view = model.bufferViews.at(static_cast<size_t>(accessor.bufferView));
  const size_t components = accessor.type == TINYGLTF_TYPE_VEC3 ? 3 : 1;
  std::vector<T> values(accessor.count * components);
  std::memcpy(values.data(), model.buffers.at(static_cast<size_t>(view.buffer)).data.data() + view.byteOffset + accessor.byteOffset,
              values.size() * sizeof(T));
  return values;
}

TEST(Gltf, DecodedFramesPlayExactlyAsMorphTargets) {
  const MeshSequence original = test::test_sequence(7, 5);
  Encode3dOptions options;
  options.frame_rate_num = 30000;
  options.frame_rate_den = 1001;
  const std::vector<uint8_t> stream = encode_mesh3d(original, options).stream;
  const MeshSequence decoded = decode_mesh3d(stream);
  const fs::path folder = fs::temp_directory_path() / ("m4mesh-gltf-" + std::to_string(::getpid()));
  fs::create_directories(folder);
  const std::string input = (folder / "s.m4m").string();
  write_file_atomically(input, std::string(stream.begin(), stream.end()));
  for (const char* name : {"anim.glb", "anim.gltf"}) {
    const std::string output = (folder / name).string();
    std::vector<const char*> argv{"m4mesh", "-q", "decode3d", input.c_str(), "-o", output.c_str()};
    ASSERT_EQ(run_m4mesh(static_cast<int>(argv.size()), argv.data()), 0) << name;
    tinygltf::Model model;
    tinygltf::TinyGLTF loader;
    std::string error, warning;
    const bool loaded = std::string(name).ends_with(".glb") ? loader.LoadBinaryFromFile(&model, &error, &warning, output)
                                                             : loader.LoadASCIIFromFile(&model, &error, &warning, output);
    ASSERT_TRUE(loaded) << name << ": " << error;
    // The one file named: a .gltf carries its buffer inside.
    for (const fs::directory_entry& entry : fs::directory_iterator(folder))
      EXPECT_TRUE(entry.path().filename() == "s.m4m" || entry.path().filename() == "anim.glb" || entry.path().filename() == "anim.gltf") << entry.path();
    ASSERT_EQ(model.meshes.size(), 1u);
    const tinygltf::Primitive& primitive = model.meshes[0].primitives.at(0);
    const std::vector<uint32_t> indices = accessor_values<uint32_t>(model, primitive.indices);
    ASSERT_EQ(indices.size(), decoded.faces.size() * 3);
    for (size_t f = 0; f < decoded.faces.size(); ++f)
      for (size_t c = 0; c < 3; ++c) EXPECT_EQ(indices[3 * f + c], decoded.faces[f].v[c]);
    for (float zero : accessor_values<float>(model, primitive.attributes.at("POSITION"))) EXPECT_EQ(zero, 0.0f);
    ASSERT_EQ(primitive.targets.size(), decoded.frames.size()) << name;
    for (size_t k = 0; k < decoded.frames.size(); ++k) {
      const std::vector<float> xyz = accessor_values<float>(model, primitive.targets[k].at("POSITION"));
      ASSERT_EQ(xyz.size(), size_t{decoded.vertex_count} * 3);
      for (size_t v = 0; v < decoded.vertex_count; ++v) {
        const Vec3& p = decoded.frames[k][v];
        ASSERT_EQ(xyz[3 * v], static_cast<float>(p.x)) << "frame " << k << " vertex " << v;
        ASSERT_EQ(xyz[3 * v + 1], static_cast<float>(p.y)) << "frame " << k << " vertex " << v;
        ASSERT_EQ(xyz[3 * v + 2], static_cast<float>(p.z)) << "frame " << k << " vertex " << v;
      }
    }
    ASSERT_EQ(model.animations.size(), 1u);
    const tinygltf::AnimationSampler& sampler = model.animations[0].samplers.at(0);
    EXPECT_EQ(sampler.interpolation, "STEP");
    EXPECT_EQ(model.animations[0].channels.at(0).target_path, "weights");
    const std::vector<float> times = accessor_values<float>(model, sampler.input), weights = accessor_values<float>(model, sampler.output);
    const size_t frames = decoded.frames.size();
    ASSERT_EQ(times.size(), frames);
    ASSERT_EQ(weights.size(), frames * frames);
    for (size_t k = 0; k < frames; ++k) {
      EXPECT_FLOAT_EQ(times[k], static_cast<float>(static_cast<double>(k) * 1001.0 / 30000.0));
      for (size_t j = 0; j < frames; ++j) EXPECT_EQ(weights[k * frames + j], j == k ? 1.0f : 0.0f);
    }
    // Read back as an input (encode3d anim.glb): the decoded frames bit for bit, at the stream's rate.
    const GltfAnimation read = read_gltf(output, {});
    EXPECT_NEAR(read.fps, 30000.0 / 1001.0, 1e-3) << name;
    EXPECT_EQ(read.sequence.faces, decoded.faces) << name;
    ASSERT_EQ(read.sequence.frames.size(), frames) << name;
    for (size_t k = 0; k < frames; ++k) ASSERT_EQ(read.sequence.frames[k], decoded.frames[k]) << name << " frame " << k;
  }
  // And coded again: the stream takes the keyframes' rate.
  const std::string glb = (folder / "anim.glb").string(), again = (folder / "again.m4m").string();
  std::vector<const char*> encode{"m4mesh", "-q", "encode3d", glb.c_str(), "-o", again.c_str()};
  ASSERT_EQ(run_m4mesh(static_cast<int>(encode.size()), encode.data()), 0);
  const std::vector<uint8_t> coded = read_file(again);
  const Mesh3dDecoder header(coded);
  EXPECT_EQ(header.header().frame_count, decoded.frames.size());
  // 30000/1001 through float32 key times: 29.97, the smallest power-of-ten fraction that holds it.
  EXPECT_EQ(header.header().frame_rate_num, 2997u);
  EXPECT_EQ(header.header().frame_rate_den, 100u);
  fs::remove_all(folder);
}

// 33,000 frames of one vertex: their weights alone pass GLB's 4 GB. Refused
// before anything is allocated or written.
TEST(Gltf, AnAnimationPastFourGigabytesIsRefused) {
  MeshSequence sequence;
  sequence.vertex_count = 1;
  sequence.frames.assign(33000, {Vec3{0, 0, 0}});
  const fs::path output = fs::temp_directory_path() / ("m4mesh-gltf-big-" + std::to_string(::getpid()) + ".glb");
  try {
    write_gltf(sequence, 25, output.string());
    ADD_FAILURE() << "written";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("33000 frames of 1 vertex take 4356"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(output));
}

}  // namespace
}  // namespace m4mesh
