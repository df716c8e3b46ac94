#include "cli/sequence_files.h"

#include <unistd.h>

#include <algorithm>
#include <charconv>

#include "cli/console.h"
#include "cli/gltf.h"
#include "codecs3d/registry.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "decoder/mesh3d/container_decoder.h"
#include "mesh/obj.h"
#include "mesh3d/ply.h"

namespace m4mesh {

namespace {

namespace fs = std::filesystem;

// Whether a file name is one obj_frame_name gives (0001.obj, …).
bool is_obj_frame_name(const std::string& name) {
  const std::string stem = name.size() > 4 ? name.substr(0, name.size() - 4) : "";
  return name.ends_with(".obj") && stem.size() >= 4 && std::all_of(stem.begin(), stem.end(), [](char c) { return c >= '0' && c <= '9'; });
}

}  // namespace

SequenceOutput sequence_output(const std::string& output, bool f32_allowed, const std::string& format) {
  if (output == "-") {
    if (format.empty() || format == "m4seq") return SequenceOutput::kM4seq;
    if (format == "f32" && f32_allowed) return SequenceOutput::kF32;
    throw usage_error("--format " + format + ": standard output takes m4seq" + std::string(f32_allowed ? " or f32" : ""));
  }
  if (!format.empty())
    throw usage_error("--format is for -o - (standard output); a file's form comes from its name");
  const fs::path path(output);
  const std::string extension = path.filename().empty() ? "" : path.extension().string();
  if (extension.empty()) return SequenceOutput::kObjFolder;
  if (extension == ".m4seq") return SequenceOutput::kM4seq;
  if (extension == ".pc2") return SequenceOutput::kPc2;
  if (extension == ".ply") return SequenceOutput::kPly;
  if (extension == ".glb" || extension == ".gltf") return SequenceOutput::kGltf;
  if (extension == ".f32" && f32_allowed) return SequenceOutput::kF32;
  throw usage_error(output + ": unknown output format '" + extension + "' (a folder of OBJ frames, .m4seq, .pc2, .ply, .glb, .gltf" + (f32_allowed ? ", .f32" : "") +
                  "; a folder whose name holds a dot takes a trailing '/')");
}

void install_obj_frames(const fs::path& staging, const fs::path& output) {
  fs::path folder = output.lexically_normal();
  if (folder.filename().empty()) folder = folder.parent_path();
  if (!fs::is_directory(folder)) {
    fs::remove(folder);  // a file the user named as the output (-y)
    fs::rename(staging, folder);
    return;
  }
  for (const fs::directory_entry& entry : fs::directory_iterator(folder))
    if (entry.is_regular_file() && is_obj_frame_name(entry.path().filename().string())) fs::remove(entry.path());
  for (const fs::directory_entry& entry : fs::directory_iterator(staging)) fs::rename(entry.path(), folder / entry.path().filename());
  fs::remove(staging);
}

fs::path staging_folder(const std::string& output) {
  fs::path folder = fs::path(output).lexically_normal();
  if (folder.filename().empty()) folder = folder.parent_path();
  return folder.string() + ".partial-" + std::to_string(getpid());
}

MeshSequence load_sequence_or_stream(const std::string& path, StreamFacts* facts) {
  console::set_input(path);
  if (facts) *facts = StreamFacts{};
  if (path == "-" || fs::is_regular_file(path)) {
    const std::vector<uint8_t> bytes = read_file(path);
    if (is_mesh3d_stream(bytes)) {
      if (facts) {
        const Mesh3dDecoder header(bytes);
        *facts = {header.codec().name, bytes.size(), header.vertex_order() == kVertexOrderCoding};
      }
      return decode_mesh3d(bytes);
    }
  }
  return load_frames(path);
}

MeshSequence load_frames(const std::string& path) {
  if (is_gltf_path(path) && fs::is_regular_file(path)) return read_gltf(path, {}).sequence;
  return load_sequence(path, !console::quiet());
}

std::unique_ptr<FrameSource> open_frames(const std::string& path, const GltfSelection& selection) {
  if (is_gltf_path(path) && fs::is_regular_file(path)) return std::make_unique<SequenceSource>(read_gltf(path, selection).sequence);
  if (!selection.mesh.empty() || !selection.animation.empty()) throw usage_error("--mesh and --animation choose in a glTF input (.glb or .gltf)");
  return open_sequence(path, !console::quiet());
}

namespace {

// A path and, for a PC2 cache, the OBJ beside it (its faces): both are read, and both are written.
std::vector<fs::path> with_faces(const std::string& path) {
  std::vector<fs::path> paths{path};
  if (fs::path(path).extension() == ".pc2") paths.push_back(pc2_faces_path(path));
  return paths;
}

bool is_pattern(const std::string& path) { return fs::path(path).filename().string().find('*') != std::string::npos; }

// The files a command reads: the input, or a folder's or pattern's frame files.
std::vector<fs::path> input_files(const std::string& input) {
  std::vector<fs::path> files = with_faces(input);
  if (fs::is_directory(input) || is_pattern(input)) {
    try {
      for (const std::string& f : frame_files(input, {".obj", ".off", ".ply"})) files.emplace_back(f);
    } catch (const Error&) {
      // Reading the input reports it.
    }
  }
  return files;
}

// The files an output replaces: the output, or a folder's OBJ frames, or the existing files of a pattern's frames.
std::vector<fs::path> output_files(const std::string& output) {
  std::vector<fs::path> files = with_faces(output);
  std::error_code ignored;
  if (fs::is_directory(output, ignored)) {
    for (const fs::directory_entry& entry : fs::directory_iterator(output, ignored))
      if (is_obj_frame_name(entry.path().filename().string())) files.push_back(entry.path());
  } else if (is_pattern(output) && fs::is_directory(fs::path(output).parent_path().empty() ? "." : fs::path(output).parent_path(), ignored)) {
    try {
      for (const std::string& f : frame_files(output, {".ply"})) files.emplace_back(f);
    } catch (const Error&) {
      // No such frames yet.
    }
  }
  return files;
}

}  // namespace

void refuse_overwriting(const std::string& input, const std::string& output, OutputForm form) {
  std::error_code ignored;
  if (form == OutputForm::kFile && output != "-" && fs::is_directory(output, ignored))
    throw usage_error(output + ": a folder; the output is a file");
  if (input != "-" && output != "-") {
    const std::vector<fs::path> inputs = input_files(input);
    for (const fs::path& out : output_files(output))
      for (const fs::path& in : inputs)
        if (fs::equivalent(in, out, ignored))
          throw usage_error(out.string() + (in == fs::path(input) ? ": the output is the input" : ": the output is one of the input's files (" + input + ")") +
                            "; refusing to overwrite it");
  }
  // Every file the command writes exists only with -y: a PC2 cache's OBJ too.
  for (const fs::path& out : with_faces(output)) console::check_output(out.string());
}

void refuse_trace_to_output(bool trace, const std::string& output) {
  if (trace && output == "-")
    throw usage_error("--trace prints to standard output, which -o - takes: write the stream to a file");
}

std::pair<uint32_t, uint32_t> frame_range(const std::string& text) {
  if (text.empty()) return {0, UINT32_MAX};
  const size_t colon = text.find(':');
  auto number = [&](const std::string& part, uint32_t otherwise) {
    if (part.empty()) return otherwise;
    uint32_t value = 0;
    const auto [end, error] = std::from_chars(part.data(), part.data() + part.size(), value);
    if (error != std::errc() || end != part.data() + part.size())
      throw usage_error("--frames " + text + ": frames A:B, A: or :B");
    return value;
  };
  if (colon == std::string::npos) throw usage_error("--frames " + text + ": frames A:B, A: or :B");
  const std::pair<uint32_t, uint32_t> range{number(text.substr(0, colon), 0), number(text.substr(colon + 1), UINT32_MAX)};
  if (range.first > range.second) throw usage_error("--frames " + text + ": A is after B");
  return range;
}

UnitSizes unit_sizes(const ContainerParts& parts, uint64_t stream_size) {
  UnitSizes sizes;
  for (size_t k = 0; k < parts.units.size(); ++k) {
    const uint64_t end = k + 1 < parts.units.size() ? parts.units[k + 1].byte_offset : stream_size - (parts.has_end_code ? 4 : 0);
    const uint32_t type = parts.units[k].payload.empty() ? kUnitTypes : parts.units[k].payload[0];
    if (type < kUnitTypes) {
      sizes.bytes[type] += end - parts.units[k].byte_offset;
      ++sizes.count[type];
    }
  }
  return sizes;
}

}  // namespace m4mesh
