#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>
#include <set>

#include "cli/gltf.h"
#include "cli/gltf_asset.h"
#include "common/error.h"

namespace m4mesh {

std::vector<int> gltf_parents(const GltfAsset& asset) {
  const tinygltf::Model& m = asset.model();
  std::vector<int> parent(m.nodes.size(), -1);
  for (size_t n = 0; n < m.nodes.size(); ++n)
    for (int child : m.nodes[n].children) {
      if (child < 0 || static_cast<size_t>(child) >= m.nodes.size() || parent[static_cast<size_t>(child)] >= 0 || static_cast<size_t>(child) == n)
        throw asset.error("node " + std::to_string(n) + ": child " + std::to_string(child) + " is not a node of one parent");
      parent[static_cast<size_t>(child)] = static_cast<int>(n);
    }
  for (size_t n = 0; n < m.nodes.size(); ++n) {  // a cycle would never reach a root
    size_t steps = 0;
    for (int at = parent[n]; at >= 0; at = parent[static_cast<size_t>(at)])
      if (++steps > m.nodes.size()) throw asset.error("node " + std::to_string(n) + " is its own ancestor");
  }
  return parent;
}

namespace {

constexpr uint64_t kMostVertices = uint64_t{1} << 24;
using Matrix = Eigen::Matrix4d;

// The animated parts of the scene at one time: per node, its animated
// translation, rotation, scale and morph weights.
struct Channels {
  std::map<std::pair<int, std::string>, GltfSampler> samplers;  // (node, path)

  const GltfSampler* find(int node, const std::string& path) const {
    const auto it = samplers.find({node, path});
    return it == samplers.end() ? nullptr : &it->second;
  }
};

Channels channels_of(const GltfAsset& asset, const tinygltf::Animation& animation) {
  Channels channels;
  const tinygltf::Model& model = asset.model();
  for (const tinygltf::AnimationChannel& channel : animation.channels) {
    if (channel.sampler < 0 || static_cast<size_t>(channel.sampler) >= animation.samplers.size())
      throw asset.error("animation '" + animation.name + "': a channel's sampler " + std::to_string(channel.sampler) + " does not exist");
    if (channel.target_node < 0 || static_cast<size_t>(channel.target_node) >= model.nodes.size()) continue;  // no node: nothing to move
    const tinygltf::AnimationSampler& s = animation.samplers[static_cast<size_t>(channel.sampler)];
    const std::string& path = channel.target_path;
    size_t width = path == "translation" || path == "scale" ? 3 : path == "rotation" ? 4 : 0;
    if (path == "weights") {
      const tinygltf::Node& node = model.nodes[static_cast<size_t>(channel.target_node)];
      if (node.mesh < 0 || static_cast<size_t>(node.mesh) >= model.meshes.size()) continue;
      const tinygltf::Mesh& mesh = model.meshes[static_cast<size_t>(node.mesh)];
      width = mesh.primitives.empty() ? 0 : mesh.primitives.front().targets.size();
    }
    if (width == 0) continue;
    const std::string what = "animation '" + animation.name + "', " + path + " of node " + std::to_string(channel.target_node);
    channels.samplers[{channel.target_node, path}] = GltfSampler::read(asset, s, width, path == "weights" ? width : 1, what);
  }
  return channels;
}

// A node's own transform at time t, its animated parts sampled.
Matrix local_transform(const tinygltf::Node& node, int index, const Channels& channels, double t) {
  if (node.matrix.size() == 16) return Eigen::Map<const Matrix>(node.matrix.data());
  Eigen::Vector3d translation = node.translation.size() == 3 ? Eigen::Vector3d(node.translation[0], node.translation[1], node.translation[2]) : Eigen::Vector3d::Zero();
  Eigen::Vector3d scale = node.scale.size() == 3 ? Eigen::Vector3d(node.scale[0], node.scale[1], node.scale[2]) : Eigen::Vector3d::Ones();
  Eigen::Quaterniond rotation = node.rotation.size() == 4 ? Eigen::Quaterniond(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2])
                                                          : Eigen::Quaterniond::Identity();
  if (const GltfSampler* s = channels.find(index, "translation")) {
    const std::vector<double> v = s->at(t);
    translation = {v[0], v[1], v[2]};
  }
  if (const GltfSampler* s = channels.find(index, "scale")) {
    const std::vector<double> v = s->at(t);
    scale = {v[0], v[1], v[2]};
  }
  if (const GltfSampler* s = channels.find(index, "rotation")) {
    auto quaternion = [](const std::vector<double>& v) { return Eigen::Quaterniond(v[3], v[0], v[1], v[2]); };
    const auto [k, u] = s->segment(t);
    // LINEAR rotations are spherical between the keys.
    rotation = s->interpolation == "LINEAR" && u != 0 ? quaternion(s->key(k)).slerp(u, quaternion(s->key(k + 1))) : quaternion(s->at(t));
  }
  Matrix m = Matrix::Identity();
  m.topLeftCorner<3, 3>() = rotation.normalized().toRotationMatrix() * scale.asDiagonal();
  m.topRightCorner<3, 1>() = translation;
  return m;
}

// Every node's transform in the scene at time t (parents first).
std::vector<Matrix> world_transforms(const tinygltf::Model& model, const std::vector<int>& parent, const Channels& channels, double t) {
  std::vector<Matrix> world(model.nodes.size());
  std::vector<bool> done(model.nodes.size(), false);
  for (size_t n = 0; n < model.nodes.size(); ++n) {
    std::vector<size_t> chain;  // n and its ancestors not yet placed
    for (int at = static_cast<int>(n); at >= 0 && !done[static_cast<size_t>(at)]; at = parent[static_cast<size_t>(at)]) chain.push_back(static_cast<size_t>(at));
    for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
      const Matrix local = local_transform(model.nodes[*it], static_cast<int>(*it), channels, t);
      world[*it] = parent[*it] >= 0 ? Matrix(world[static_cast<size_t>(parent[*it])] * local) : local;
      done[*it] = true;
    }
  }
  return world;
}

// The mesh's geometry gathered over its primitives.
struct Geometry {
  std::vector<Vec3> base;
  std::vector<std::vector<Vec3>> targets;  // per morph target, per vertex
  std::vector<Triangle> faces;
  std::vector<std::array<uint32_t, 4>> joints;  // per vertex and influence set
  std::vector<std::array<double, 4>> weights;
  size_t influence_sets = 0;
  std::vector<uint32_t> first_vertex, first_face;  // per primitive, then one past the last
};

std::vector<Vec3> vec3s(const std::vector<double>& xyz) {
  std::vector<Vec3> out(xyz.size() / 3);
  for (size_t v = 0; v < out.size(); ++v) out[v] = {xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2]};
  return out;
}

Geometry geometry_of(const GltfAsset& asset, const tinygltf::Mesh& mesh, bool skinned) {
  Geometry g;
  const std::string name = "mesh '" + mesh.name + "'";
  if (mesh.primitives.empty()) throw asset.error(name + " has no primitive");
  const size_t targets = mesh.primitives.front().targets.size();
  g.targets.resize(targets);
  for (size_t k = 0; k < mesh.primitives.size(); ++k) {
    const tinygltf::Primitive& p = mesh.primitives[k];
    const std::string what = name + ", primitive " + std::to_string(k);
    if (p.mode != -1 && p.mode != TINYGLTF_MODE_TRIANGLES)
      throw asset.error(what + " is not of triangles (mode " + std::to_string(p.mode) + "): m4mesh codes triangle meshes");
    if (p.targets.size() != targets) throw asset.error(what + " has " + std::to_string(p.targets.size()) + " morph targets, primitive 0 " + std::to_string(targets));
    const auto position = p.attributes.find("POSITION");
    if (position == p.attributes.end()) throw asset.error(what + " has no POSITION");
    const std::vector<Vec3> base = vec3s(asset.numbers(position->second, 3, what + ", POSITION"));
    const auto first = static_cast<uint32_t>(g.base.size());
    g.first_vertex.push_back(first), g.first_face.push_back(static_cast<uint32_t>(g.faces.size()));
    if (g.base.size() + base.size() > kMostVertices) throw asset.error(name + ": over " + std::to_string(kMostVertices) + " vertices");
    g.base.insert(g.base.end(), base.begin(), base.end());
    for (size_t t = 0; t < targets; ++t) {
      const auto target = p.targets[t].find("POSITION");
      std::vector<Vec3> moves(base.size());
      if (target != p.targets[t].end()) {
        moves = vec3s(asset.numbers(target->second, 3, what + ", morph target " + std::to_string(t)));
        if (moves.size() != base.size()) throw asset.error(what + ", morph target " + std::to_string(t) + ": not one position per vertex");
      }
      g.targets[t].insert(g.targets[t].end(), moves.begin(), moves.end());
    }
    std::vector<uint32_t> indices;
    if (p.indices >= 0) {
      indices = asset.integers(p.indices, 1, what + ", indices");
    } else {
      indices.resize(base.size());
      for (uint32_t v = 0; v < indices.size(); ++v) indices[v] = v;
    }
    if (indices.size() % 3 != 0) throw asset.error(what + ": " + std::to_string(indices.size()) + " indices are not whole triangles");
    for (size_t i = 0; i < indices.size(); i += 3) {
      for (size_t c = 0; c < 3; ++c)
        if (indices[i + c] >= base.size()) throw asset.error(what + ": index " + std::to_string(indices[i + c]) + " past its " + std::to_string(base.size()) + " vertices");
      g.faces.push_back({{NodeIndex{first + indices[i]}, NodeIndex{first + indices[i + 1]}, NodeIndex{first + indices[i + 2]}}});
    }
    if (!skinned) continue;
    size_t sets = 0;
    while (p.attributes.count("JOINTS_" + std::to_string(sets)) && p.attributes.count("WEIGHTS_" + std::to_string(sets))) ++sets;
    if (sets == 0) throw asset.error(what + " belongs to a skin and has no JOINTS_0 and WEIGHTS_0");
    if (k == 0) g.influence_sets = sets;
    if (sets != g.influence_sets) throw asset.error(what + ": " + std::to_string(sets) + " sets of joints, primitive 0 " + std::to_string(g.influence_sets));
    // Vertex-major: vertex v's sets at v × sets … v × sets + sets − 1.
    g.joints.resize(g.base.size() * sets);
    g.weights.resize(g.base.size() * sets);
    for (size_t s = 0; s < sets; ++s) {
      const std::string set = std::to_string(s);
      const std::vector<uint32_t> joints = asset.integers(p.attributes.at("JOINTS_" + set), 4, what + ", JOINTS_" + set);
      const std::vector<double> weights = asset.numbers(p.attributes.at("WEIGHTS_" + set), 4, what + ", WEIGHTS_" + set);
      if (joints.size() != 4 * base.size() || weights.size() != 4 * base.size()) throw asset.error(what + ": not one set of joints and weights per vertex");
      for (size_t v = 0; v < base.size(); ++v) {
        const size_t at = (first + v) * sets + s;
        g.joints[at] = {joints[4 * v], joints[4 * v + 1], joints[4 * v + 2], joints[4 * v + 3]};
        g.weights[at] = {weights[4 * v], weights[4 * v + 1], weights[4 * v + 2], weights[4 * v + 3]};
      }
    }
  }
  g.first_vertex.push_back(static_cast<uint32_t>(g.base.size())), g.first_face.push_back(static_cast<uint32_t>(g.faces.size()));
  return g;
}

struct Choice {
  int node = -1;
  std::string name;
};

// The nodes that carry a mesh; the one the user named, or the only one.
Choice choose_mesh(const GltfAsset& asset, const std::string& wanted) {
  const tinygltf::Model& model = asset.model();
  std::vector<Choice> found;
  for (size_t n = 0; n < model.nodes.size(); ++n) {
    const tinygltf::Node& node = model.nodes[n];
    if (node.mesh < 0) continue;
    if (static_cast<size_t>(node.mesh) >= model.meshes.size()) throw asset.error("node " + std::to_string(n) + ": no mesh " + std::to_string(node.mesh));
    const std::string& mesh_name = model.meshes[static_cast<size_t>(node.mesh)].name;
    const std::string name = !node.name.empty() ? node.name : !mesh_name.empty() ? mesh_name : "node " + std::to_string(n);
    if (!wanted.empty() && wanted != node.name && wanted != mesh_name) continue;
    found.push_back({static_cast<int>(n), name});
  }
  if (found.size() == 1) return found.front();
  if (found.empty() && !wanted.empty()) throw asset.error("no node or mesh is named '" + wanted + "'");
  if (found.empty()) throw asset.error("no mesh");
  std::string names;
  for (const Choice& c : found) names += (names.empty() ? "'" : ", '") + c.name + "'";
  throw asset.error(std::to_string(found.size()) + " meshes (" + names + "): choose one with --mesh NAME");
}

const tinygltf::Animation& choose_animation(const GltfAsset& asset, const std::string& wanted) {
  const std::vector<tinygltf::Animation>& animations = asset.model().animations;
  if (animations.empty()) throw asset.error("no animation: nothing moves, so there is no sequence to code");
  std::string names;
  for (const tinygltf::Animation& a : animations) {
    if (!wanted.empty() && a.name == wanted) return a;
    names += (names.empty() ? "'" : ", '") + a.name + "'";
  }
  if (!wanted.empty()) throw asset.error("no animation is named '" + wanted + "' (it has " + names + ")");
  if (animations.size() > 1) throw asset.error(std::to_string(animations.size()) + " animations (" + names + "): choose one with --animation NAME");
  return animations.front();
}

// The times frames are taken at: every key of the channels, or `fps` over their span.
// Every key of the channels, each once, in order.
std::set<double> keys_of(const Channels& channels) {
  std::set<double> keys;
  for (const auto& [target, sampler] : channels.samplers) keys.insert(sampler.times.begin(), sampler.times.end());
  return keys;
}

std::pair<std::vector<double>, double> sample_times(const GltfAsset& asset, const Channels& channels, std::optional<double> fps, uint64_t most) {
  const std::set<double> keys = keys_of(channels);
  if (keys.empty()) throw asset.error("the animation moves nothing of the scene");
  const double start = *keys.begin(), end = *keys.rbegin();
  std::vector<double> times;
  if (fps) {
    const double frames = std::floor((end - start) * *fps + 1e-6) + 1;
    if (frames > static_cast<double>(most)) throw asset.error("over " + std::to_string(most) + " frames at --fps " + std::to_string(*fps) + ": too many to bake");
    for (double k = 0; k < frames; ++k) times.push_back(start + k / *fps);
    return {times, *fps};
  }
  times.assign(keys.begin(), keys.end());
  if (times.size() == 1) return {times, 25};
  // Evenly spaced keys (within float32's precision) give the rate; others need --fps.
  const double step = (end - start) / static_cast<double>(times.size() - 1);
  for (size_t k = 1; k < times.size(); ++k)
    if (std::abs(times[k] - times[k - 1] - step) > 1e-4 * step + 1e-6)
      throw asset.error("its keyframes are not evenly spaced (" + std::to_string(times[k - 1]) + " s, then " + std::to_string(times[k]) +
                        " s): give --fps F to sample the animation at F frames a second");
  return {times, 1 / step};
}

// A node's mesh at each time, every primitive's vertices after the last one's.
struct Baked {
  MeshSequence sequence;
  Geometry geometry;
};

// Node `index`'s mesh at `times`, moved by `channels`: its morph targets, then its skin (linear blend) or, without
// one, its node's world transform. in_node_space: in the node's own space instead (a skin's positions taken back
// through the node's world transform, a mesh without one left as its morph targets make it).
Baked bake_node(const GltfAsset& asset, const Channels& channels, int index, std::span<const double> times, bool in_node_space, const GltfLimits& limits) {
  const tinygltf::Model& m = asset.model();
  const tinygltf::Node& node = m.nodes[static_cast<size_t>(index)];
  const std::string name = "node " + std::to_string(index) + (node.name.empty() ? "" : " '" + node.name + "'");
  const bool skinned = node.skin >= 0;
  if (skinned && static_cast<size_t>(node.skin) >= m.skins.size()) throw asset.error(name + ": no skin " + std::to_string(node.skin));
  const tinygltf::Mesh& mesh = m.meshes[static_cast<size_t>(node.mesh)];
  Baked baked{{}, geometry_of(asset, mesh, skinned)};
  const Geometry& g = baked.geometry;
  const std::vector<int> parent = gltf_parents(asset);

  std::vector<Matrix> inverse_bind;
  std::vector<int> joints;
  if (skinned) {
    const tinygltf::Skin& skin = m.skins[static_cast<size_t>(node.skin)];
    joints = skin.joints;
    for (int j : joints)
      if (j < 0 || static_cast<size_t>(j) >= m.nodes.size()) throw asset.error("skin '" + skin.name + "': joint " + std::to_string(j) + " is not a node");
    inverse_bind.assign(joints.size(), Matrix::Identity());
    if (skin.inverseBindMatrices >= 0) {
      const std::vector<double> values = asset.numbers(skin.inverseBindMatrices, 16, "skin '" + skin.name + "', inverseBindMatrices");
      if (values.size() != 16 * joints.size()) throw asset.error("skin '" + skin.name + "': not one inverse bind matrix per joint");
      for (size_t j = 0; j < joints.size(); ++j) inverse_bind[j] = Eigen::Map<const Matrix>(values.data() + 16 * j);
    }
    for (const std::array<uint32_t, 4>& set : g.joints)
      for (uint32_t j : set)
        if (j >= joints.size()) throw asset.error("mesh '" + mesh.name + "': joint " + std::to_string(j) + " past the skin's " + std::to_string(joints.size()));
  }

  if (static_cast<double>(times.size()) * static_cast<double>(g.base.size()) > static_cast<double>(limits.most_positions))
    throw asset.error(std::to_string(times.size()) + " frames of " + std::to_string(g.base.size()) + " vertices are too many to bake: give a lower --fps");
  uint64_t work = 0;
  baked.sequence.vertex_count = static_cast<uint32_t>(g.base.size());
  baked.sequence.faces = g.faces;
  const std::vector<double> rest_weights(mesh.weights.begin(), mesh.weights.end());
  for (const double t : times) {
    std::vector<double> weights = rest_weights;
    if (const GltfSampler* s = channels.find(index, "weights")) weights = s->at(t);
    weights.resize(g.targets.size(), 0.0);
    // Per vertex: its morph targets of weight ≠ 0 and its joints.
    work += g.base.size() * (1 + static_cast<uint64_t>(std::count_if(weights.begin(), weights.end(), [](double w) { return w != 0; })) + 4 * g.influence_sets);
    if (work > limits.most_work) throw asset.error("the animation takes over " + std::to_string(limits.most_work) + " vertex operations to bake: give a lower --fps");
    const std::vector<Matrix> world = world_transforms(m, parent, channels, t);
    std::vector<Matrix> skinning;
    Matrix back = Matrix::Identity();  // from the world to the node's own space, when asked for
    if (skinned && in_node_space) {
      const Matrix& placed = world[static_cast<size_t>(index)];
      const double determinant = placed.determinant();
      if (!(std::abs(determinant) > 1e-300) || !std::isfinite(determinant))
        throw asset.error(name + ": its transform at " + std::to_string(t) + " s has no inverse, so its skin's positions have no place in its own space");
      back = placed.inverse();
    }
    for (size_t j = 0; j < joints.size(); ++j) skinning.push_back(back * world[static_cast<size_t>(joints[j])] * inverse_bind[j]);
    std::vector<Vec3> frame(g.base.size());
    for (size_t v = 0; v < g.base.size(); ++v) {
      Eigen::Vector4d p(g.base[v].x, g.base[v].y, g.base[v].z, 1);
      for (size_t k = 0; k < g.targets.size(); ++k)
        if (weights[k] != 0) p.head<3>() += weights[k] * Eigen::Vector3d(g.targets[k][v].x, g.targets[k][v].y, g.targets[k][v].z);
      Eigen::Vector4d q = Eigen::Vector4d::Zero();
      if (skinned) {
        for (size_t s = 0; s < g.influence_sets; ++s) {
          const size_t at = v * g.influence_sets + s;
          for (size_t i = 0; i < 4; ++i)
            if (g.weights[at][i] != 0) q += g.weights[at][i] * (skinning[g.joints[at][i]] * p);
        }
      } else {
        q = in_node_space ? p : Eigen::Vector4d(world[static_cast<size_t>(index)] * p);
      }
      for (int c = 0; c < 3; ++c)
        if (!(std::abs(q[c]) <= std::numeric_limits<float>::max()))
          throw asset.error("vertex " + std::to_string(v) + " at " + std::to_string(t) + " s is not a finite float32 position");
      frame[v] = {static_cast<float>(q.x()), static_cast<float>(q.y()), static_cast<float>(q.z())};
    }
    baked.sequence.frames.push_back(std::move(frame));
  }
  return baked;
}

// The chosen mesh baked at every sample time.
GltfAnimation bake(const GltfAsset& asset, const GltfSelection& selection, const GltfLimits& limits) {
  if (selection.fps && !(*selection.fps > 0 && *selection.fps <= 1000)) throw usage_error("--fps: a rate above 0 and at most 1000");
  const Choice choice = choose_mesh(asset, selection.mesh);
  const Channels channels = channels_of(asset, choose_animation(asset, selection.animation));
  const auto [times, fps] = sample_times(asset, channels, selection.fps, limits.most_positions);
  return {bake_node(asset, channels, choice.node, times, false, limits).sequence, fps};
}

}  // namespace

bool is_gltf_path(const std::string& path) { return path.ends_with(".glb") || path.ends_with(".gltf"); }

GltfAnimation read_gltf(const std::string& path, const GltfSelection& selection, const GltfLimits& limits) {
  return bake(load_gltf_asset(path), selection, limits);
}

GltfAnimation read_glb(std::span<const uint8_t> bytes, const std::string& name, const GltfSelection& selection, const GltfLimits& limits) {
  return bake(load_glb_asset(bytes, name), selection, limits);
}

GltfNodeFrames bake_in_node_space(const GltfAsset& asset, int animation, int node, const GltfLimits& limits) {
  const Channels channels = channels_of(asset, asset.model().animations.at(static_cast<size_t>(animation)));
  const std::set<double> keys = keys_of(channels);
  GltfNodeFrames out{{keys.begin(), keys.end()}, {}};
  const Baked baked = bake_node(asset, channels, node, out.times, true, limits);
  const Geometry& g = baked.geometry;
  out.primitives.resize(g.first_vertex.size() - 1);
  for (size_t p = 0; p < out.primitives.size(); ++p) {
    MeshSequence& s = out.primitives[p];
    const uint32_t first = g.first_vertex[p];
    s.vertex_count = g.first_vertex[p + 1] - first;
    for (uint32_t f = g.first_face[p]; f < g.first_face[p + 1]; ++f)
      s.faces.push_back({{NodeIndex{g.faces[f].v[0] - first}, NodeIndex{g.faces[f].v[1] - first}, NodeIndex{g.faces[f].v[2] - first}}});
    for (const std::vector<Vec3>& frame : baked.sequence.frames) s.frames.emplace_back(frame.begin() + first, frame.begin() + first + s.vertex_count);
  }
  return out;
}

}  // namespace m4mesh
