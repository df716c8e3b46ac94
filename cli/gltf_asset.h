// A glTF 2.0 asset as read for baking and compressing (cli/gltf_read.cc,
// cli/gltf_compress.cc): tinygltf's model, its accessors read with every
// element checked inside its buffer view and buffer, and its animation
// samplers evaluated as the glTF specification defines them.
#pragma once

#include <tiny_gltf.h>

#include <cstdint>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "cli/gltf.h"
#include "common/error.h"

namespace m4mesh {

class GltfAsset {
 public:
  GltfAsset(const std::string& path, tinygltf::Model model) : path_(path), model_(std::move(model)) {}

  // An input error naming the file.
  Error error(const std::string& message) const { return Error(ErrorKind::kInput, "", kNoPlane, kNoOffset, path_ + ": " + message); }
  const std::string& path() const { return path_; }
  const tinygltf::Model& model() const { return model_; }

  // Accessor `index` as `components` numbers per element (floats, or
  // integers, normalized when the accessor says so), sparse values applied.
  std::vector<double> numbers(int index, int components, const std::string& what) const;
  // Accessor `index` as whole numbers (indices, joints).
  std::vector<uint32_t> integers(int index, int components, const std::string& what) const;
  size_t count(int index, const std::string& what) const { return accessor(index, what).count; }

 private:
  const tinygltf::Accessor& accessor(int index, const std::string& what) const;
  // That `count` elements of `components` numbers lie inside a buffer view inside its buffer.
  void check_elements(int view_index, size_t offset, size_t count, int type, int components, const std::string& what) const;
  // `count` elements of `components` numbers from a buffer view (check_elements first).
  void read_elements(int view_index, size_t offset, size_t count, int type, int components, bool normalized, const std::string& what, double* out) const;

  std::string path_;
  tinygltf::Model model_;
};

// A .glb or .gltf file (.gltf: its buffers beside it or inside as data:
// URIs), or a GLB in memory (no file beside it). Images are left undecoded.
GltfAsset load_gltf_asset(const std::string& path);
GltfAsset load_glb_asset(std::span<const uint8_t> bytes, const std::string& name);

// One animation sampler: its key times and values (`width` numbers a key).
struct GltfSampler {
  std::vector<double> times;
  std::vector<double> values;  // CUBICSPLINE: in-tangent, value, out-tangent per key
  std::string interpolation;
  size_t width = 0;

  // Reads sampler `s` of `animation`, whose keys hold `width` numbers
  // (`elements` accessor elements of `width / elements` numbers each): its
  // interpolation known, its times increasing, its output one value per key.
  static GltfSampler read(const GltfAsset& asset, const tinygltf::AnimationSampler& s, size_t width, size_t elements, const std::string& what);

  // Where t falls: key k, and how far towards key k + 1 (0: at k; held before the first key and after the last).
  std::pair<size_t, double> segment(double t) const;
  // Key k's value (CUBICSPLINE: part 0 the in-tangent, 1 the value, 2 the out-tangent).
  std::vector<double> key(size_t k, size_t part = 1) const;
  // The value at time t.
  std::vector<double> at(double t) const;
};

// Every node's parent (−1: a root); an input error unless the nodes make trees.
std::vector<int> gltf_parents(const GltfAsset& asset);

struct GltfNodeFrames {
  std::vector<double> times;             // every key of the animation's channels, each once, in order
  std::vector<MeshSequence> primitives;  // per primitive: its triangles, its positions at each time
};

// Node `node`'s mesh as animation `animation` moves it, at every key of the
// animation: per primitive, its positions after its morph targets (the
// node's weights channel, else the mesh's default weights) and its skin
// (linear blend), in the node's own space: a skin's positions taken back
// through the node's world transform at each time, so that the node's
// transform, once the skin is gone, puts them where the skin did.
GltfNodeFrames bake_in_node_space(const GltfAsset& asset, int animation, int node, const GltfLimits& limits);

}  // namespace m4mesh
