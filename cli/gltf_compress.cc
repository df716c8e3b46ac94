#include "cli/gltf_compress.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <optional>
#include <nlohmann/json.hpp>
#include <set>

#include "cli/console.h"
#include "cli/gltf_asset.h"
#include "cli/sequence_files.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "encoder/mesh3d/container_encoder.h"
#include "encoder/mesh3d/quality_target.h"

namespace m4mesh {

namespace {

using Json = nlohmann::ordered_json;
using console::say;

constexpr uint32_t kGlbMagic = 0x46546C67, kJsonChunk = 0x4E4F534A, kBinChunk = 0x004E4942;

uint32_t load_u32(const uint8_t* at) { return uint32_t{at[0]} | uint32_t{at[1]} << 8 | uint32_t{at[2]} << 16 | uint32_t{at[3]} << 24; }
void append_u32(std::string& out, uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<char>(v >> (8 * i)));
}

// The JSON text of a GLB's first chunk.
std::string glb_json(std::span<const uint8_t> file, const GltfAsset& asset) {
  // tinygltf has read it as a GLB already; its header is checked again for the offsets used here.
  if (file.size() < 20 || load_u32(file.data()) != kGlbMagic || load_u32(file.data() + 16) != kJsonChunk ||
      load_u32(file.data() + 12) > file.size() - 20)
    throw asset.error("not a GLB of a JSON chunk first");
  return {file.begin() + 20, file.begin() + 20 + load_u32(file.data() + 12)};
}

// Extensions whose objects hold no index of an accessor or a buffer view
// other than those renumbered below: the compressor can drop accessors and
// buffer views without breaking them.
bool keeps_references(const std::string& name) {
  static const std::set<std::string> known = {
      "KHR_texture_transform", "KHR_lights_punctual",  "KHR_mesh_quantization",  "KHR_texture_basisu", "EXT_texture_webp",
      "EXT_texture_avif",      "KHR_xmp_json_ld",      "KHR_draco_mesh_compression", "EXT_mesh_gpu_instancing", "KHR_animation_pointer",
      "KHR_materials_variants", kGltfExtensionName};
  return known.count(name) || name.starts_with("KHR_materials_");
}

Json* member(Json& object, const char* key) { return object.is_object() && object.contains(key) ? &object[key] : nullptr; }

template <class F>
void each_index(Json* at, F& f) {
  if (at && at->is_number_integer()) f(*at);
}

// Every place of the document that holds an accessor's index.
template <class F>
void for_each_accessor_index(Json& doc, F&& f) {
  if (Json* meshes = member(doc, "meshes"))
    for (Json& mesh : *meshes)
      if (Json* primitives = member(mesh, "primitives"))
        for (Json& p : *primitives) {
          if (Json* attributes = member(p, "attributes"))
            for (Json& a : *attributes) each_index(&a, f);
          each_index(member(p, "indices"), f);
          if (Json* targets = member(p, "targets"))
            for (Json& target : *targets)
              for (Json& a : target) each_index(&a, f);
        }
  if (Json* animations = member(doc, "animations"))
    for (Json& animation : *animations) {
      if (Json* samplers = member(animation, "samplers"))
        for (Json& s : *samplers) each_index(member(s, "input"), f), each_index(member(s, "output"), f);
      if (Json* ours = member(animation, "extensions"); ours && (ours = member(*ours, kGltfExtensionName)))
        if (Json* channels = member(*ours, "channels"))
          for (Json& c : *channels) each_index(member(c, "input"), f);
    }
  if (Json* skins = member(doc, "skins"))
    for (Json& skin : *skins) each_index(member(skin, "inverseBindMatrices"), f);
  if (Json* nodes = member(doc, "nodes"))
    for (Json& node : *nodes)
      if (Json* e = member(node, "extensions"); e && (e = member(*e, "EXT_mesh_gpu_instancing")))
        if (Json* attributes = member(*e, "attributes"))
          for (Json& a : *attributes) each_index(&a, f);
}

// Every place of the document that holds a buffer view's index.
template <class F>
void for_each_view_index(Json& doc, F&& f) {
  if (Json* accessors = member(doc, "accessors"))
    for (Json& a : *accessors) {
      each_index(member(a, "bufferView"), f);
      if (Json* sparse = member(a, "sparse")) {
        if (Json* indices = member(*sparse, "indices")) each_index(member(*indices, "bufferView"), f);
        if (Json* values = member(*sparse, "values")) each_index(member(*values, "bufferView"), f);
      }
    }
  if (Json* images = member(doc, "images"))
    for (Json& image : *images) each_index(member(image, "bufferView"), f);
  if (Json* meshes = member(doc, "meshes"))
    for (Json& mesh : *meshes)
      if (Json* primitives = member(mesh, "primitives"))
        for (Json& p : *primitives)
          if (Json* e = member(p, "extensions"); e && (e = member(*e, "KHR_draco_mesh_compression"))) each_index(member(*e, "bufferView"), f);
  if (Json* animations = member(doc, "animations"))
    for (Json& animation : *animations)
      if (Json* ours = member(animation, "extensions"); ours && (ours = member(*ours, kGltfExtensionName)))
        if (Json* channels = member(*ours, "channels"))
          for (Json& c : *channels)
            if (Json* primitives = member(c, "primitives"))
              for (Json& p : *primitives) each_index(member(p, "bufferView"), f);
}

template <class Walk>
std::set<int64_t> referenced(Json& doc, Walk walk) {
  std::set<int64_t> found;
  walk(doc, [&](Json& index) { found.insert(index.get<int64_t>()); });
  return found;
}

// Drops the entries of doc[array] in `dropped`, renumbering every index
// `walk` visits; per old index, its new one (−1: dropped).
template <class Walk>
std::vector<int64_t> drop_entries(Json& doc, const char* array, const std::set<int64_t>& dropped, Walk walk) {
  Json& entries = doc[array];
  std::vector<int64_t> renumbered(entries.size());
  int64_t next = 0;
  for (size_t i = 0; i < entries.size(); ++i) renumbered[i] = dropped.count(static_cast<int64_t>(i)) ? -1 : next++;
  walk(doc, [&](Json& index) { index = renumbered.at(static_cast<size_t>(index.get<int64_t>())); });
  Json kept = Json::array();
  for (size_t i = 0; i < entries.size(); ++i)
    if (renumbered[i] >= 0) kept.push_back(std::move(entries[i]));
  entries = std::move(kept);
  return renumbered;
}

// A float32 VEC3 or SCALAR accessor over a new buffer view of `values`; its index.
int64_t add_floats(Json& doc, std::map<int64_t, std::vector<uint8_t>>& new_views, const std::vector<float>& values, const char* type, bool bounds) {
  std::vector<uint8_t> bytes(values.size() * 4);
  std::memcpy(bytes.data(), values.data(), bytes.size());
  const auto view = static_cast<int64_t>(doc["bufferViews"].size());
  doc["bufferViews"].push_back(Json{{"buffer", 0}, {"byteLength", bytes.size()}});
  new_views[view] = std::move(bytes);
  Json accessor{{"bufferView", view}, {"componentType", 5126}, {"count", values.size() / (std::string(type) == "VEC3" ? 3 : 1)}, {"type", type}};
  if (bounds) accessor["min"] = {*std::min_element(values.begin(), values.end())}, accessor["max"] = {*std::max_element(values.begin(), values.end())};
  doc["accessors"].push_back(accessor);
  return static_cast<int64_t>(doc["accessors"].size() - 1);
}

// One vertex animation replaced: the animation, its weights channel (−1: none), the channel's node and the node's
// mesh; `skin`: the node's skin baked too (--bake-skins), so that the stream holds every pose of the mesh.
struct Replacement {
  int animation, channel, node, mesh;
  bool skin = false;
};

std::string mesh_name(const tinygltf::Model& model, int mesh) {
  const std::string& name = model.meshes[static_cast<size_t>(mesh)].name;
  return "mesh " + std::to_string(mesh) + (name.empty() ? "" : " '" + name + "'");
}

std::string animation_name(const tinygltf::Model& model, int animation) {
  const std::string& name = model.animations[static_cast<size_t>(animation)].name;
  return "animation " + std::to_string(animation) + (name.empty() ? "" : " '" + name + "'");
}

bool has_node(const tinygltf::Model& m, int node) { return node >= 0 && static_cast<size_t>(node) < m.nodes.size(); }

// Whether a node carries a skin m4mesh may bake: a mesh with primitives, and a skin of the asset.
bool bakes_skin(const tinygltf::Model& m, const tinygltf::Node& node) {
  return node.skin >= 0 && static_cast<size_t>(node.skin) < m.skins.size() && node.mesh >= 0 && static_cast<size_t>(node.mesh) < m.meshes.size() &&
         !m.meshes[static_cast<size_t>(node.mesh)].primitives.empty();
}

// Whether an animation moves a skin: a translation, rotation or scale channel on one of its joints or their
// ancestors (`parent`: each node's, −1 for none).
bool moves_skin(const tinygltf::Model& m, const std::vector<int>& parent, const tinygltf::Animation& animation, const tinygltf::Skin& skin) {
  std::set<int> movers;
  for (int joint : skin.joints)
    for (int at = joint; has_node(m, at) && movers.insert(at).second;) at = parent[static_cast<size_t>(at)];
  return std::any_of(animation.channels.begin(), animation.channels.end(), [&](const tinygltf::AnimationChannel& c) {
    return c.target_path != "weights" && movers.count(c.target_node);
  });
}

// Every weights channel that drives a node's morph targets; with `skins`, every skinned node an animation moves
// (with its weights channel there, if any).
std::vector<Replacement> replacements_of(const GltfAsset& asset, bool skins) {
  const tinygltf::Model& m = asset.model();
  const std::vector<int> parent = skins ? gltf_parents(asset) : std::vector<int>();
  std::vector<Replacement> found;
  for (size_t a = 0; a < m.animations.size(); ++a) {
    std::set<int> skinned;  // the nodes of this animation whose skin is baked
    for (size_t c = 0; c < m.animations[a].channels.size(); ++c) {
      const tinygltf::AnimationChannel& channel = m.animations[a].channels[c];
      if (channel.target_path != "weights" || !has_node(m, channel.target_node)) continue;
      const tinygltf::Node& node = m.nodes[static_cast<size_t>(channel.target_node)];
      const int mesh = node.mesh;
      if (mesh < 0 || static_cast<size_t>(mesh) >= m.meshes.size() || m.meshes[static_cast<size_t>(mesh)].primitives.empty() ||
          m.meshes[static_cast<size_t>(mesh)].primitives.front().targets.empty())
        continue;
      if (channel.sampler < 0 || static_cast<size_t>(channel.sampler) >= m.animations[a].samplers.size())
        throw asset.error(animation_name(m, static_cast<int>(a)) + ", channel " + std::to_string(c) + ": no sampler " + std::to_string(channel.sampler));
      const bool skin = skins && bakes_skin(m, node);
      if (skin) skinned.insert(channel.target_node);
      found.push_back({static_cast<int>(a), static_cast<int>(c), channel.target_node, mesh, skin});
    }
    if (!skins) continue;
    for (size_t n = 0; n < m.nodes.size(); ++n)
      if (bakes_skin(m, m.nodes[n]) && !skinned.count(static_cast<int>(n)) &&
          moves_skin(m, parent, m.animations[a], m.skins[static_cast<size_t>(m.nodes[n].skin)]))
        found.push_back({static_cast<int>(a), -1, static_cast<int>(n), m.nodes[n].mesh, true});
  }
  return found;
}

// A primitive's frames at its weights channel's keys: base + Σ weight × target, rounded to float32.
MeshSequence bake_primitive(const GltfAsset& asset, const tinygltf::Primitive& p, const GltfSampler& weights, const GltfLimits& limits,
                            const std::string& what) {
  if (p.mode != -1 && p.mode != TINYGLTF_MODE_TRIANGLES)
    throw asset.error(what + " is not of triangles (mode " + std::to_string(p.mode) + "): m4mesh codes triangle meshes");
  const auto position = p.attributes.find("POSITION");
  if (position == p.attributes.end()) throw asset.error(what + " has no POSITION");
  const std::vector<double> base = asset.numbers(position->second, 3, what + ", POSITION");
  const size_t vertices = base.size() / 3;
  std::vector<std::vector<double>> targets;
  for (size_t t = 0; t < p.targets.size(); ++t) {
    const auto moves = p.targets[t].find("POSITION");
    if (moves == p.targets[t].end()) {
      targets.emplace_back(base.size(), 0.0);
      continue;
    }
    targets.push_back(asset.numbers(moves->second, 3, what + ", morph target " + std::to_string(t)));
    if (targets.back().size() != base.size())
      throw asset.error(what + ", morph target " + std::to_string(t) + ": " + std::to_string(targets.back().size() / 3) + " positions for " +
                        std::to_string(vertices) + " vertices");
  }
  // Bounded as encode3d's baking is: frames × vertices kept, and the weighted targets' work.
  const double keys = static_cast<double>(weights.times.size());
  if (keys * static_cast<double>(vertices) > static_cast<double>(limits.most_positions) ||
      keys * static_cast<double>(vertices) * static_cast<double>(targets.size() + 1) > static_cast<double>(limits.most_work))
    throw asset.error(what + ": " + std::to_string(weights.times.size()) + " keys of " + std::to_string(vertices) + " vertices and " +
                      std::to_string(targets.size()) + " morph targets are past what m4mesh bakes at once (" + std::to_string(limits.most_positions) +
                      " positions, " + std::to_string(limits.most_work) + " vertex operations)");
  MeshSequence s;
  s.vertex_count = static_cast<uint32_t>(vertices);
  std::vector<uint32_t> indices;
  if (p.indices >= 0) {
    indices = asset.integers(p.indices, 1, what + ", indices");
  } else {
    indices.resize(vertices);
    for (uint32_t v = 0; v < indices.size(); ++v) indices[v] = v;
  }
  if (indices.size() % 3 != 0) throw asset.error(what + ": " + std::to_string(indices.size()) + " indices are not whole triangles");
  for (size_t i = 0; i < indices.size(); i += 3) {
    for (size_t c = 0; c < 3; ++c)
      if (indices[i + c] >= vertices) throw asset.error(what + ": index " + std::to_string(indices[i + c]) + " past its " + std::to_string(vertices) + " vertices");
    s.faces.push_back({{NodeIndex{indices[i]}, NodeIndex{indices[i + 1]}, NodeIndex{indices[i + 2]}}});
  }
  for (size_t k = 0; k < weights.times.size(); ++k) {
    const std::vector<double> w = weights.key(k);
    std::vector<Vec3> frame(vertices);
    for (size_t v = 0; v < vertices; ++v) {
      double xyz[3] = {base[3 * v], base[3 * v + 1], base[3 * v + 2]};
      for (size_t t = 0; t < targets.size(); ++t)
        if (w[t] != 0)
          for (size_t c = 0; c < 3; ++c) xyz[c] += w[t] * targets[t][3 * v + c];
      for (double x : xyz)
        if (!(std::abs(x) <= std::numeric_limits<float>::max()))
          throw asset.error(what + ": vertex " + std::to_string(v) + " at key " + std::to_string(k) + " is not a finite float32 position");
      frame[v] = {static_cast<float>(xyz[0]), static_cast<float>(xyz[1]), static_cast<float>(xyz[2])};
    }
    s.frames.push_back(std::move(frame));
  }
  return s;
}

// The bytes of accessor `index`'s buffer view the first time that view is named in `counted`, else 0 (a view
// shared by several accessors, or a sparse accessor's parts, counted whole, once).
uint64_t view_bytes(const tinygltf::Model& m, int accessor, std::set<int>& counted) {
  if (accessor < 0 || static_cast<size_t>(accessor) >= m.accessors.size()) return 0;
  const int view = m.accessors[static_cast<size_t>(accessor)].bufferView;
  if (view < 0 || static_cast<size_t>(view) >= m.bufferViews.size() || !counted.insert(view).second) return 0;
  return m.bufferViews[static_cast<size_t>(view)].byteLength;
}

// The container's frame rate of keys spread from first to last (the key times themselves are the extension's).
std::pair<uint32_t, uint32_t> key_rate(const std::vector<double>& times) {
  const double fps = times.size() < 2 ? 25 : std::clamp(static_cast<double>(times.size() - 1) / (times.back() - times.front()), 0.001, 65535.0);
  return frame_rate_fraction(fps);
}

Encode3dResult encode(const MeshSequence& frames, const Encode3dArgs& args, const std::vector<double>& times, std::string& codec) {
  Encode3dOptions options = encode3d_options(args);
  options.measure = true;
  std::tie(options.frame_rate_num, options.frame_rate_den) = key_rate(times);
  console::Progress progress("encoding", frames.frames.size());
  options.progress = [&](size_t done, size_t total) { progress.update(done, total); };
  const QualityTarget target{args.target_kg, args.target_psnr, args.max_error};
  const auto ignore = [](const TargetTrial&) {};
  Encode3dResult result;
  if (args.codec == "auto") {
    result = encode_smallest(frames, options, target, ignore, options.codec);
  } else if (target.set()) {
    result = encode_to_target(frames, options, target, ignore);
  } else {
    result = encode_mesh3d(frames, options);
  }
  progress.finish();
  codec = options.codec;
  return result;
}

GltfCompressResult compress(const GltfAsset& asset, const std::string& json_text, const GltfCompressArgs& args) {
  const tinygltf::Model& m = asset.model();
  const std::string& path = asset.path();
  Json doc = Json::parse(json_text);
  if (!doc.is_object()) throw asset.error("its JSON is not an object");
  for (const char* list : {"extensionsUsed", "extensionsRequired"})
    if (Json* names = member(doc, list))
      for (const Json& name : *names) {
        const std::string text = name.is_string() ? name.get<std::string>() : name.dump();
        if (text == kGltfExtensionName) throw asset.error(std::string("it uses ") + kGltfExtensionName + " already: compressed once is enough");
        if (!keeps_references(text))
          throw asset.error("it uses " + text + ", whose accessor and buffer view indices m4mesh cannot keep right when it drops the morph targets" +
                            (text == "EXT_meshopt_compression" ? " (decompress it first: gltfpack without -c)" : ""));
      }

  GltfCompressResult result;
  const std::vector<Replacement> replacements = replacements_of(asset, args.bake_skins);
  if (replacements.empty()) {
    const bool skinned = std::any_of(m.nodes.begin(), m.nodes.end(), [&](const tinygltf::Node& n) { return bakes_skin(m, n); });
    throw asset.error(args.bake_skins ? "no animation drives morph targets (a weights channel) or moves a skin: nothing to compress"
                                      : std::string("no animation drives morph targets (a weights channel): nothing to compress") +
                                            (skinned ? " (its skins' animations are baked with --bake-skins)" : ""));
  }

  const std::set<int64_t> accessors_before = referenced(doc, [](Json& d, auto f) { for_each_accessor_index(d, f); });
  const std::set<int64_t> views_before = referenced(doc, [](Json& d, auto f) { for_each_view_index(d, f); });
  std::map<int64_t, std::vector<uint8_t>> new_views;  // by index in doc's bufferViews: the bytes of views the compressor adds
  if (!doc.contains("bufferViews")) doc["bufferViews"] = Json::array();
  if (!doc.contains("accessors")) doc["accessors"] = Json::array();

  std::set<int> meshes;
  std::map<int, std::set<int>> removed_channels;            // per animation
  std::map<int, std::tuple<int, double, double>> held_spans;  // per animation: its first replaced node, its keys' first and last time
  std::set<int> replaced_views;  // the views whose bytes a stream's report counts already
  std::set<int> unskinned;  // the nodes whose skin is baked
  for (const Replacement& r : replacements) {
    const tinygltf::Animation& animation = m.animations[static_cast<size_t>(r.animation)];
    const tinygltf::Mesh& mesh = m.meshes[static_cast<size_t>(r.mesh)];
    const std::string where = animation_name(m, r.animation) + (r.channel >= 0 ? ", weights of node " : ", skin of node ") + std::to_string(r.node);
    const size_t targets = mesh.primitives.front().targets.size();
    // The keys: the weights channel's, or (a skin baked) every key of the animation, LINEAR unless each channel is STEP.
    std::vector<double> times;
    std::string interpolation = "LINEAR";
    int64_t input = -1;
    int64_t replaced_output = -1;
    std::optional<GltfSampler> weights;
    if (r.channel >= 0) {
      const tinygltf::AnimationSampler& s = animation.samplers[static_cast<size_t>(animation.channels[static_cast<size_t>(r.channel)].sampler)];
      weights = GltfSampler::read(asset, s, targets, targets, where);
      if (weights->interpolation == "CUBICSPLINE")
        result.warnings.push_back(where + ": CUBICSPLINE weights are kept at their keys and played LINEAR between them");
      if (weights->interpolation == "STEP") interpolation = "STEP";
      times = weights->times, input = s.input, replaced_output = s.output;
    }
    GltfNodeFrames baked;
    if (r.skin) {
      baked = bake_in_node_space(asset, r.animation, r.node, args.limits);
      times = baked.times;
      const bool steps = std::all_of(animation.samplers.begin(), animation.samplers.end(), [](const tinygltf::AnimationSampler& s) { return s.interpolation == "STEP"; });
      interpolation = steps ? "STEP" : "LINEAR";
      input = add_floats(doc, new_views, std::vector<float>(times.begin(), times.end()), "SCALAR", true);
      unskinned.insert(r.node);
    }
    Json entry{{"node", r.node}, {"input", input}, {"interpolation", interpolation}, {"primitives", Json::array()}};
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
      const std::string what = mesh_name(m, r.mesh) + ", primitive " + std::to_string(p);
      if (mesh.primitives[p].targets.size() != targets)
        throw asset.error(what + " has " + std::to_string(mesh.primitives[p].targets.size()) + " morph targets, primitive 0 " + std::to_string(targets));
      const MeshSequence frames = r.skin ? std::move(baked.primitives[p]) : bake_primitive(asset, mesh.primitives[p], *weights, args.limits, what);
      GltfStreamReport report{r.animation, r.node, r.mesh, static_cast<int>(p), "", static_cast<uint32_t>(frames.frames.size()), frames.vertex_count};
      Encode3dResult encoded;
      try {
        encoded = encode(frames, args.encoding, times, report.codec);
      } catch (const Error& e) {
        throw Error(e.kind(), "", kNoPlane, kNoOffset, path + ": " + what + ", " + where + ": " + e.message());
      }
      report.stream_bytes = encoded.stream.size();
      for (const std::map<std::string, int>& target : mesh.primitives[p].targets)
        for (const auto& attribute : target) report.replaced_bytes += view_bytes(m, attribute.second, replaced_views);
      report.kg = encoded.kg, report.psnr = encoded.psnr, report.max_error = encoded.max_error;
      const auto view = static_cast<int64_t>(doc["bufferViews"].size());
      doc["bufferViews"].push_back(Json{{"buffer", 0}, {"byteLength", encoded.stream.size()}});
      new_views[view] = std::move(encoded.stream);
      entry["primitives"].push_back(Json{{"bufferView", view}});
      result.streams.push_back(report);
    }
    if (replaced_output >= 0) result.streams.back().replaced_bytes += view_bytes(m, static_cast<int>(replaced_output), replaced_views);
    doc["animations"][static_cast<size_t>(r.animation)]["extensions"][kGltfExtensionName]["channels"].push_back(entry);
    if (r.channel >= 0) removed_channels[r.animation].insert(r.channel);
    held_spans.try_emplace(r.animation, r.node, times.front(), times.back());
    meshes.insert(r.mesh);
  }

  // A baked skin goes from its node; its mesh's joints and weights go when no node keeps a skin over it. The
  // skin itself and its joints' channels stay (other nodes may hang from the joints).
  for (int node : unskinned) doc["nodes"][static_cast<size_t>(node)].erase("skin");
  for (int mesh : meshes) {
    const bool still_skinned = std::any_of(m.nodes.begin(), m.nodes.end(), [&](const tinygltf::Node& n) {
      return n.mesh == mesh && n.skin >= 0 && !unskinned.count(static_cast<int>(&n - m.nodes.data()));
    });
    if (still_skinned || std::none_of(replacements.begin(), replacements.end(), [&](const Replacement& r) { return r.mesh == mesh && r.skin; })) continue;
    GltfStreamReport& report = *std::find_if(result.streams.begin(), result.streams.end(), [&](const GltfStreamReport& r) { return r.mesh == mesh; });
    for (const tinygltf::Primitive& p : m.meshes[static_cast<size_t>(mesh)].primitives)
      for (const auto& [name, accessor] : p.attributes)
        if (name.starts_with("JOINTS_") || name.starts_with("WEIGHTS_")) report.replaced_bytes += view_bytes(m, accessor, replaced_views);
    for (Json& p : doc["meshes"][static_cast<size_t>(mesh)]["primitives"])
      if (Json* attributes = member(p, "attributes"))
        for (auto it = attributes->begin(); it != attributes->end();)
          it = it.key().starts_with("JOINTS_") || it.key().starts_with("WEIGHTS_") ? attributes->erase(it) : std::next(it);
  }

  // The morph targets go, with the weights that chose among them.
  for (int mesh : meshes) {
    Json& j = doc["meshes"][static_cast<size_t>(mesh)];
    for (Json& p : j["primitives"]) p.erase("targets");
    j.erase("weights");
    if (Json* extras = member(j, "extras"); extras && extras->is_object()) {
      extras->erase("targetNames");
      if (extras->empty()) j.erase("extras");
    }
    const std::vector<double>& rest = m.meshes[static_cast<size_t>(mesh)].weights;
    if (std::any_of(rest.begin(), rest.end(), [](double w) { return w != 0; }))
      result.warnings.push_back(mesh_name(m, mesh) + ": its default weights are not all 0; where no animation plays, it shows its base POSITION");
  }
  for (size_t n = 0; n < m.nodes.size(); ++n)
    if (meshes.count(m.nodes[n].mesh)) doc["nodes"][n].erase("weights");

  // The replaced channels go, and the samplers no channel uses. An
  // animation keeps one channel (glTF asks for at least one): its first
  // replaced node's own translation, held over the keys' span.
  for (const auto& [a, removed] : removed_channels) {
    Json& animation = doc["animations"][static_cast<size_t>(a)];
    Json channels = Json::array();
    for (size_t c = 0; c < animation["channels"].size(); ++c)
      if (!removed.count(static_cast<int>(c))) channels.push_back(animation["channels"][c]);
    if (channels.empty()) {
      const auto& [node, first, last] = held_spans.at(a);
      const tinygltf::Node& n = m.nodes[static_cast<size_t>(node)];
      if (n.matrix.size() == 16)
        throw asset.error(animation_name(m, a) + " would keep no channel, and node " + std::to_string(node) +
                          " has a matrix, which no channel may animate: give the animation another channel");
      std::vector<float> keys{static_cast<float>(first)}, held(3, 0.0f);
      if (last > first) keys.push_back(static_cast<float>(last));
      for (size_t i = 0; i < n.translation.size() && i < 3; ++i) held[i] = static_cast<float>(n.translation[i]);
      if (keys.size() == 2) held.insert(held.end(), held.begin(), held.end());
      const int64_t input = add_floats(doc, new_views, keys, "SCALAR", true), output = add_floats(doc, new_views, held, "VEC3", false);
      animation["samplers"].push_back(Json{{"input", input}, {"output", output}, {"interpolation", "STEP"}});
      channels.push_back(Json{{"sampler", animation["samplers"].size() - 1}, {"target", {{"node", node}, {"path", "translation"}}}});
    }
    animation["channels"] = std::move(channels);
    std::set<int64_t> unused;
    for (size_t i = 0; i < animation["samplers"].size(); ++i) unused.insert(static_cast<int64_t>(i));
    for (const Json& c : animation["channels"])
      if (const Json* sampler = c.is_object() && c.contains("sampler") ? &c["sampler"] : nullptr; sampler && sampler->is_number_integer())
        unused.erase(sampler->get<int64_t>());
    drop_entries(animation, "samplers", unused, [](Json& an, auto f) {
      for (Json& c : an["channels"]) each_index(member(c, "sampler"), f);
    });
  }

  // Accessors and buffer views nothing refers to any more go (those the
  // input itself left unused stay); the rest are renumbered.
  const auto accessor_walk = [](Json& d, auto f) { for_each_accessor_index(d, f); };
  const auto view_walk = [](Json& d, auto f) { for_each_view_index(d, f); };
  std::set<int64_t> dropped;
  const std::set<int64_t> accessors_after = referenced(doc, accessor_walk);
  std::set_difference(accessors_before.begin(), accessors_before.end(), accessors_after.begin(), accessors_after.end(), std::inserter(dropped, dropped.end()));
  drop_entries(doc, "accessors", dropped, accessor_walk);
  dropped.clear();
  const std::set<int64_t> views_after = referenced(doc, view_walk);
  std::set_difference(views_before.begin(), views_before.end(), views_after.begin(), views_after.end(), std::inserter(dropped, dropped.end()));
  const std::vector<int64_t> renumbered = drop_entries(doc, "bufferViews", dropped, view_walk);

  // One buffer, the GLB's: every view kept, byte for byte, 4-byte aligned.
  std::string bin;
  for (size_t old = 0; old < renumbered.size(); ++old) {
    if (renumbered[old] < 0) continue;
    Json& view = doc["bufferViews"][static_cast<size_t>(renumbered[old])];
    bin.resize((bin.size() + 3) / 4 * 4, '\0');
    const size_t offset = bin.size();
    if (const auto added = new_views.find(static_cast<int64_t>(old)); added != new_views.end()) {
      bin.append(added->second.begin(), added->second.end());
    } else {
      const tinygltf::BufferView& v = m.bufferViews.at(old);
      if (v.buffer < 0 || static_cast<size_t>(v.buffer) >= m.buffers.size() || v.byteOffset > m.buffers[static_cast<size_t>(v.buffer)].data.size() ||
          v.byteLength > m.buffers[static_cast<size_t>(v.buffer)].data.size() - v.byteOffset)
        throw asset.error("buffer view " + std::to_string(old) + " lies outside its buffer");
      const auto from = m.buffers[static_cast<size_t>(v.buffer)].data.begin() + static_cast<ptrdiff_t>(v.byteOffset);
      bin.append(from, from + static_cast<ptrdiff_t>(v.byteLength));
    }
    view["buffer"] = 0;
    view["byteOffset"] = offset;
  }
  bin.resize((bin.size() + 3) / 4 * 4, '\0');
  Json buffer = doc.contains("buffers") && doc["buffers"].is_array() && !doc["buffers"].empty() ? doc["buffers"][0] : Json::object();
  buffer.erase("uri");
  buffer["byteLength"] = bin.size();
  doc["buffers"] = Json::array({buffer});
  doc["extensionsUsed"].push_back(kGltfExtensionName);
  if (args.required) doc["extensionsRequired"].push_back(kGltfExtensionName);

  std::string json = doc.dump();
  json.resize((json.size() + 3) / 4 * 4, ' ');
  const uint64_t length = 12 + 8 + json.size() + 8 + bin.size();
  if (length > kMostGltfBytes) throw asset.error("the compressed file would take " + std::to_string(length) + " bytes, past GLB's 4 GB");
  std::string glb;
  append_u32(glb, kGlbMagic), append_u32(glb, 2), append_u32(glb, static_cast<uint32_t>(length));
  append_u32(glb, static_cast<uint32_t>(json.size())), append_u32(glb, kJsonChunk), glb += json;
  append_u32(glb, static_cast<uint32_t>(bin.size())), append_u32(glb, kBinChunk), glb += bin;
  result.glb.assign(glb.begin(), glb.end());
  return result;
}

// tinygltf has read the asset; what its JSON still holds wrong (a member of another type, an index past its array) is named here.
GltfCompressResult compress_checked(const GltfAsset& asset, const std::string& json_text, const GltfCompressArgs& args) {
  try {
    return compress(asset, json_text, args);
  } catch (const Json::exception& e) {
    throw asset.error(std::string("its JSON: ") + e.what());
  } catch (const std::out_of_range&) {
    throw asset.error("an index past the array it refers to");
  }
}

}  // namespace

GltfCompressResult compress_gltf(const std::string& path, const GltfCompressArgs& args) {
  const std::vector<uint8_t> file = read_file(path);
  if (path.ends_with(".glb")) return compress_glb(file, path, args);
  return compress_checked(load_gltf_asset(path), std::string(file.begin(), file.end()), args);
}

GltfCompressResult compress_glb(std::span<const uint8_t> bytes, const std::string& name, const GltfCompressArgs& args) {
  const GltfAsset asset = load_glb_asset(bytes, name);
  return compress_checked(asset, glb_json(bytes, asset), args);
}

int run_gltf_compress(const GltfCompressArgs& args) {
  refuse_overwriting(args.input, args.output);
  if (!args.output.ends_with(".glb")) throw usage_error(args.output + ": m4mesh gltf writes a .glb");
  if (!is_gltf_path(args.input)) throw usage_error(args.input + ": m4mesh gltf takes a .glb or .gltf");
  Encode3dArgs encoding = args.encoding;
  const QualityTarget target{encoding.target_kg, encoding.target_psnr, encoding.max_error};
  if (target.set()) check_target(target);
  if (encoding.codec == "auto" && !target.set()) encoding.target_kg = kDefaultGltfTargetKg;
  GltfCompressArgs used = args;
  used.encoding = encoding;
  const GltfCompressResult result = compress_gltf(args.input, used);
  for (const std::string& w : result.warnings) say("warning: %s", w.c_str());
  uint64_t streams = 0, replaced = 0;
  for (const GltfStreamReport& r : result.streams) {
    say("animation %d, node %d, mesh %d, primitive %d: %s of %s: %llu bytes (%s), KG %.4f %%, max error %.4g", r.animation, r.node, r.mesh,
        r.primitive, console::counted(r.frames, "frame", "frames").c_str(), console::counted(r.vertices, "vertex", "vertices").c_str(),
        static_cast<unsigned long long>(r.stream_bytes), r.codec.c_str(), r.kg, r.max_error);
    streams += r.stream_bytes, replaced += r.replaced_bytes;
  }
  write_file_atomically(args.output, {reinterpret_cast<const char*>(result.glb.data()), result.glb.size()});
  say("%s: %zu bytes (%s in %llu bytes, for %llu bytes of morph targets, weights, joints and skin weights)", args.output.c_str(), result.glb.size(),
      console::counted(result.streams.size(), "stream", "streams").c_str(), static_cast<unsigned long long>(streams),
      static_cast<unsigned long long>(replaced));
  return 0;
}

}  // namespace m4mesh
