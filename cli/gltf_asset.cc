#include "cli/gltf_asset.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>

namespace m4mesh {

namespace {

// The most numbers an accessor without a buffer view (all zeros) may stand for.
constexpr size_t kMostUnbackedNumbers = size_t{1} << 24;

double component(const unsigned char* at, int type, bool normalized) {
  auto load = [at]<class T>(T) {
    T value;
    std::memcpy(&value, at, sizeof value);
    return value;
  };
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return load(float{});
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return normalized ? load(uint8_t{}) / 255.0 : load(uint8_t{});
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return normalized ? load(uint16_t{}) / 65535.0 : load(uint16_t{});
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
      return load(uint32_t{});
    case TINYGLTF_COMPONENT_TYPE_BYTE:
      return normalized ? std::max(load(int8_t{}) / 127.0, -1.0) : load(int8_t{});
    default:  // TINYGLTF_COMPONENT_TYPE_SHORT (check_elements let no other in)
      return normalized ? std::max(load(int16_t{}) / 32767.0, -1.0) : load(int16_t{});
  }
}

// Images are not needed: left undecoded.
tinygltf::TinyGLTF loader() {
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader([](tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) { return true; }, nullptr);
  return loader;
}

Error unreadable(const std::string& path, const std::string& error, const std::string& warning) {
  return Error(ErrorKind::kInput, "", kNoPlane, kNoOffset, path + ": not a glTF 2.0 asset m4mesh can read: " + (error.empty() ? warning : error));
}

}  // namespace

std::vector<double> GltfAsset::numbers(int index, int components, const std::string& what) const {
  const tinygltf::Accessor& a = accessor(index, what);
  if (tinygltf::GetNumComponentsInType(static_cast<uint32_t>(a.type)) != components)
    throw error(what + ": accessor " + std::to_string(index) + " has " + std::to_string(tinygltf::GetNumComponentsInType(static_cast<uint32_t>(a.type))) +
                " components an element, not " + std::to_string(components));
  // Memory only for what the buffers hold: elements without a buffer view (zeros) are capped.
  if (a.bufferView >= 0)
    check_elements(a.bufferView, a.byteOffset, a.count, a.componentType, components, what);
  else if (a.count * static_cast<size_t>(components) > kMostUnbackedNumbers)
    throw error(what + ": accessor " + std::to_string(index) + " holds " + std::to_string(a.count) + " elements and no buffer view");
  std::vector<double> out(a.count * static_cast<size_t>(components), 0.0);
  if (a.bufferView >= 0) read_elements(a.bufferView, a.byteOffset, a.count, a.componentType, components, a.normalized, what, out.data());
  if (a.sparse.isSparse) {
    const auto count = static_cast<size_t>(a.sparse.count);
    if (a.sparse.count < 1 || count > a.count) throw error(what + ": a sparse accessor of " + std::to_string(a.sparse.count) + " values");
    check_elements(a.sparse.indices.bufferView, static_cast<size_t>(a.sparse.indices.byteOffset), count, a.sparse.indices.componentType, 1, what);
    check_elements(a.sparse.values.bufferView, static_cast<size_t>(a.sparse.values.byteOffset), count, a.componentType, components, what);
    std::vector<double> at(count), values(count * static_cast<size_t>(components));
    read_elements(a.sparse.indices.bufferView, static_cast<size_t>(a.sparse.indices.byteOffset), count, a.sparse.indices.componentType, 1, false,
                  what + " (sparse indices)", at.data());
    read_elements(a.sparse.values.bufferView, static_cast<size_t>(a.sparse.values.byteOffset), count, a.componentType, components, a.normalized,
                  what + " (sparse values)", values.data());
    for (size_t k = 0; k < count; ++k) {
      if (at[k] >= static_cast<double>(a.count)) throw error(what + ": a sparse index past the accessor's " + std::to_string(a.count) + " elements");
      std::copy_n(values.begin() + static_cast<ptrdiff_t>(k) * components, components, out.begin() + static_cast<ptrdiff_t>(at[k]) * components);
    }
  }
  return out;
}

std::vector<uint32_t> GltfAsset::integers(int index, int components, const std::string& what) const {
  const tinygltf::Accessor& a = accessor(index, what);
  if (a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
      a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
    throw error(what + ": accessor " + std::to_string(index) + " is not of unsigned integers");
  const std::vector<double> values = numbers(index, components, what);
  return {values.begin(), values.end()};
}

const tinygltf::Accessor& GltfAsset::accessor(int index, const std::string& what) const {
  if (index < 0 || static_cast<size_t>(index) >= model_.accessors.size()) throw error(what + ": no accessor " + std::to_string(index));
  const tinygltf::Accessor& a = model_.accessors[static_cast<size_t>(index)];
  if (a.count > (size_t{1} << 32)) throw error(what + ": an accessor of " + std::to_string(a.count) + " elements");
  return a;
}

void GltfAsset::check_elements(int view_index, size_t offset, size_t count, int type, int components, const std::string& what) const {
  if (view_index < 0 || static_cast<size_t>(view_index) >= model_.bufferViews.size()) throw error(what + ": no buffer view " + std::to_string(view_index));
  const tinygltf::BufferView& view = model_.bufferViews[static_cast<size_t>(view_index)];
  if (view.buffer < 0 || static_cast<size_t>(view.buffer) >= model_.buffers.size()) throw error(what + ": no buffer " + std::to_string(view.buffer));
  const size_t data = model_.buffers[static_cast<size_t>(view.buffer)].data.size();
  if (type != TINYGLTF_COMPONENT_TYPE_BYTE && type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && type != TINYGLTF_COMPONENT_TYPE_SHORT &&
      type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT && type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT && type != TINYGLTF_COMPONENT_TYPE_FLOAT)
    throw error(what + ": component type " + std::to_string(type) + " is not glTF's");
  const int size = tinygltf::GetComponentSizeInBytes(static_cast<uint32_t>(type));
  const uint64_t element = uint64_t{static_cast<uint32_t>(size)} * static_cast<uint32_t>(components);
  const uint64_t stride = view.byteStride != 0 ? view.byteStride : element;
  // count ≤ 2³² and stride < 2⁸ (glTF caps it at 252): no overflow.
  const uint64_t needed = count == 0 ? 0 : std::min<uint64_t>(offset, uint64_t{1} << 48) + (count - 1) * std::min<uint64_t>(stride, 256) + element;
  if (stride < element || stride > 252 || view.byteOffset > data || view.byteLength > data - view.byteOffset || needed > view.byteLength)
    throw error(what + ": " + std::to_string(count) + " elements past the end of buffer view " + std::to_string(view_index));
}

void GltfAsset::read_elements(int view_index, size_t offset, size_t count, int type, int components, bool normalized, const std::string& what,
                              double* out) const {
  check_elements(view_index, offset, count, type, components, what);
  const tinygltf::BufferView& view = model_.bufferViews[static_cast<size_t>(view_index)];
  const std::vector<unsigned char>& data = model_.buffers[static_cast<size_t>(view.buffer)].data;
  const int size = tinygltf::GetComponentSizeInBytes(static_cast<uint32_t>(type));
  const size_t element = static_cast<size_t>(size) * static_cast<size_t>(components);
  const size_t stride = view.byteStride != 0 ? view.byteStride : element;
  const unsigned char* base = data.data() + view.byteOffset + offset;
  for (size_t k = 0; k < count; ++k)
    for (int c = 0; c < components; ++c) {
      const unsigned char* at = base + k * stride + static_cast<size_t>(c * size);
      out[k * static_cast<size_t>(components) + static_cast<size_t>(c)] = component(at, type, normalized);
    }
}

GltfAsset load_gltf_asset(const std::string& path) {
  if (!std::filesystem::is_regular_file(path)) throw Error(ErrorKind::kIo, "", kNoPlane, kNoOffset, path + ": no such file");
  tinygltf::Model model;
  std::string error, warning;
  tinygltf::TinyGLTF reader = loader();
  const bool loaded =
      path.ends_with(".glb") ? reader.LoadBinaryFromFile(&model, &error, &warning, path) : reader.LoadASCIIFromFile(&model, &error, &warning, path);
  if (!loaded) throw unreadable(path, error, warning);
  return GltfAsset(path, std::move(model));
}

GltfAsset load_glb_asset(std::span<const uint8_t> bytes, const std::string& name) {
  if (bytes.size() > UINT32_MAX) throw Error(ErrorKind::kInput, "", kNoPlane, kNoOffset, name + ": over 4 GB, past GLB's own limit");
  tinygltf::Model model;
  std::string error, warning;
  tinygltf::TinyGLTF reader = loader();
  // No base folder: a GLB read from memory takes no file beside it.
  if (!reader.LoadBinaryFromMemory(&model, &error, &warning, bytes.data(), static_cast<unsigned int>(bytes.size()), "/nonexistent"))
    throw unreadable(name, error, warning);
  return GltfAsset(name, std::move(model));
}

GltfSampler GltfSampler::read(const GltfAsset& asset, const tinygltf::AnimationSampler& s, size_t width, size_t elements, const std::string& what) {
  GltfSampler sampler;
  sampler.interpolation = s.interpolation.empty() ? "LINEAR" : s.interpolation;
  if (sampler.interpolation != "LINEAR" && sampler.interpolation != "STEP" && sampler.interpolation != "CUBICSPLINE")
    throw asset.error(what + ": unknown interpolation " + sampler.interpolation);
  sampler.times = asset.numbers(s.input, 1, what + " (times)");
  sampler.width = width;
  if (sampler.times.empty()) throw asset.error(what + ": no keyframe");
  for (size_t k = 0; k < sampler.times.size(); ++k)
    if (!std::isfinite(sampler.times[k]) || (k > 0 && sampler.times[k] <= sampler.times[k - 1])) throw asset.error(what + ": key times must increase");
  const size_t per_key = sampler.interpolation == "CUBICSPLINE" ? 3 : 1;
  const size_t output = asset.count(s.output, what);
  if (output != sampler.times.size() * per_key * elements)
    throw asset.error(what + ": " + std::to_string(output) + " output values for " + std::to_string(sampler.times.size()) + " keys");
  sampler.values = asset.numbers(s.output, static_cast<int>(width / elements), what + " (values)");
  return sampler;
}

std::pair<size_t, double> GltfSampler::segment(double t) const {
  const size_t after = static_cast<size_t>(std::upper_bound(times.begin(), times.end(), t) - times.begin());
  if (after == 0) return {0, 0.0};
  if (after == times.size() || interpolation == "STEP" || times[after - 1] == t) return {after - 1, 0.0};
  return {after - 1, (t - times[after - 1]) / (times[after] - times[after - 1])};
}

std::vector<double> GltfSampler::key(size_t k, size_t part) const {
  const size_t start = interpolation == "CUBICSPLINE" ? (3 * k + part) * width : k * width;
  return std::vector<double>(values.begin() + static_cast<ptrdiff_t>(start), values.begin() + static_cast<ptrdiff_t>(start + width));
}

std::vector<double> GltfSampler::at(double t) const {
  const auto [k, u] = segment(t);
  if (u == 0) return key(k);
  const std::vector<double> a = key(k), b = key(k + 1);
  std::vector<double> out(width);
  if (interpolation != "CUBICSPLINE") {
    for (size_t i = 0; i < width; ++i) out[i] = a[i] + u * (b[i] - a[i]);
    return out;
  }
  const double span = times[k + 1] - times[k], u2 = u * u, u3 = u2 * u;
  const std::vector<double> out_tangent = key(k, 2), in_tangent = key(k + 1, 0);
  for (size_t i = 0; i < width; ++i)
    out[i] = (2 * u3 - 3 * u2 + 1) * a[i] + (u3 - 2 * u2 + u) * span * out_tangent[i] + (-2 * u3 + 3 * u2) * b[i] + (u3 - u2) * span * in_tangent[i];
  return out;
}

}  // namespace m4mesh
