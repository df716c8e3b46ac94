#include "cli/gltf.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <cstring>
#include <limits>
#include <sstream>

#include "common/atomic_file.h"
#include "common/error.h"

namespace m4mesh {

namespace {

// Appends `values` to the one buffer as a view and an accessor of `count` elements of `type`; returns the accessor.
template <class T>
int add_accessor(tinygltf::Model& model, const std::vector<T>& values, size_t count, int type, int component, int target) {
  tinygltf::Buffer& buffer = model.buffers.front();
  const size_t offset = buffer.data.size();
  buffer.data.resize(offset + values.size() * sizeof(T));
  std::memcpy(buffer.data.data() + offset, values.data(), values.size() * sizeof(T));
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = offset;
  view.byteLength = values.size() * sizeof(T);
  view.target = target;
  model.bufferViews.push_back(view);
  tinygltf::Accessor accessor;
  accessor.bufferView = static_cast<int>(model.bufferViews.size() - 1);
  accessor.componentType = component;
  accessor.count = count;
  accessor.type = type;
  model.accessors.push_back(accessor);
  return static_cast<int>(model.accessors.size() - 1);
}

// A POSITION accessor (glTF asks for its bounds).
int add_positions(tinygltf::Model& model, const std::vector<float>& xyz) {
  const int index = add_accessor(model, xyz, xyz.size() / 3, TINYGLTF_TYPE_VEC3, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TARGET_ARRAY_BUFFER);
  std::vector<double> low(3, std::numeric_limits<double>::max()), high(3, std::numeric_limits<double>::lowest());
  for (size_t i = 0; i < xyz.size(); ++i) low[i % 3] = std::min<double>(low[i % 3], xyz[i]), high[i % 3] = std::max<double>(high[i % 3], xyz[i]);
  model.accessors[static_cast<size_t>(index)].minValues = low;
  model.accessors[static_cast<size_t>(index)].maxValues = high;
  return index;
}

}  // namespace

void write_gltf(const MeshSequence& sequence, double fps, const std::string& path) {
  const bool binary = path.ends_with(".glb");
  if (sequence.frames.empty()) throw usage_error(path + ": no frame to write");
  if (!(fps > 0)) throw usage_error(path + ": a frame rate above 0 is needed for the animation");
  const size_t frames = sequence.frames.size(), vertices = sequence.vertex_count;
  // A GLB counts its bytes in 32 bits; the weights grow as frames².
  const double bytes = 12.0 * static_cast<double>(sequence.faces.size()) + 12.0 * static_cast<double>(vertices) * static_cast<double>(frames + 1) +
                       4.0 * static_cast<double>(frames) * static_cast<double>(frames + 1);
  if (bytes > kMostGltfBytes)
    throw usage_error(path + ": " + std::to_string(frames) + " frames of " + std::to_string(vertices) + (vertices == 1 ? " vertex" : " vertices") + " take " +
                      std::to_string(static_cast<uint64_t>(bytes)) + " bytes, past a glTF buffer's " + std::to_string(kMostGltfBytes) +
                      ": write fewer frames (--frames A:B)");
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "m4mesh";
  model.buffers.resize(1);

  std::vector<uint32_t> indices;
  for (const Triangle& t : sequence.faces) indices.insert(indices.end(), t.v.begin(), t.v.end());
  tinygltf::Primitive primitive;
  primitive.mode = TINYGLTF_MODE_TRIANGLES;
  primitive.indices = add_accessor(model, indices, indices.size(), TINYGLTF_TYPE_SCALAR, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
  primitive.attributes["POSITION"] = add_positions(model, std::vector<float>(vertices * 3, 0.0f));
  std::vector<float> xyz(vertices * 3);
  for (const std::vector<Vec3>& frame : sequence.frames) {
    for (size_t v = 0; v < vertices; ++v) {
      xyz[3 * v] = static_cast<float>(frame[v].x), xyz[3 * v + 1] = static_cast<float>(frame[v].y), xyz[3 * v + 2] = static_cast<float>(frame[v].z);
    }
    primitive.targets.push_back({{"POSITION", add_positions(model, xyz)}});
  }
  tinygltf::Mesh mesh;
  mesh.name = "decoded";
  mesh.primitives.push_back(primitive);
  mesh.weights.assign(frames, 0.0);
  mesh.weights[0] = 1;  // without the animation, frame 0
  model.meshes.push_back(mesh);
  tinygltf::Node node;
  node.mesh = 0;
  node.name = "decoded";
  model.nodes.push_back(node);
  tinygltf::Scene scene;
  scene.nodes.push_back(0);
  model.scenes.push_back(scene);
  model.defaultScene = 0;

  // Frame k at k / fps, its target alone at weight 1, held until the next (STEP).
  std::vector<float> times(frames), weights(frames * frames, 0.0f);
  for (size_t k = 0; k < frames; ++k) times[k] = static_cast<float>(static_cast<double>(k) / fps), weights[k * frames + k] = 1;
  const int input = add_accessor(model, times, frames, TINYGLTF_TYPE_SCALAR, TINYGLTF_COMPONENT_TYPE_FLOAT, 0);
  model.accessors[static_cast<size_t>(input)].minValues = {times.front()};
  model.accessors[static_cast<size_t>(input)].maxValues = {times.back()};
  const int output = add_accessor(model, weights, frames * frames, TINYGLTF_TYPE_SCALAR, TINYGLTF_COMPONENT_TYPE_FLOAT, 0);
  tinygltf::Animation animation;
  animation.name = "frames";
  tinygltf::AnimationSampler sampler;
  sampler.input = input;
  sampler.output = output;
  sampler.interpolation = "STEP";
  animation.samplers.push_back(sampler);
  tinygltf::AnimationChannel channel;
  channel.sampler = 0;
  channel.target_node = 0;
  channel.target_path = "weights";
  animation.channels.push_back(channel);
  model.animations.push_back(animation);

  std::ostringstream out;
  tinygltf::TinyGLTF writer;
  if (!writer.WriteGltfSceneToStream(&model, out, !binary, binary)) throw Error(ErrorKind::kIo, "", kNoPlane, kNoOffset, path + ": the glTF could not be written");
  write_file_atomically(path, out.str());
}

}  // namespace m4mesh
