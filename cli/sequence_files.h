// What the commands read and write: sequences and streams in every form
// the command line takes, the frames asked for, and the rules for the
// files a user names (an output that is an input, or that exists).
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <utility>

#include "cli/gltf.h"
#include "mesh3d/frame_source.h"
#include "mesh3d/sequence.h"
#include "syntax/mesh3d/container.h"

namespace m4mesh {

// A sequence output's form from its name: a folder of OBJ frames (no
// extension, or a trailing '/'), .m4seq, .pc2 (with its .obj), PLY frames
// (a .ply name, with a '*' for the frame number when there are several),
// a glTF animation (.glb, or .gltf with its buffer inside: cli/gltf.h) or
// .f32; anything else is a usage error, not a folder. Standard output ("-")
// takes `format`: m4seq (the default) or f32.
enum class SequenceOutput { kObjFolder, kM4seq, kPc2, kPly, kGltf, kF32 };
SequenceOutput sequence_output(const std::string& output, bool f32_allowed, const std::string& format = "");

// The OBJ frames written into `staging` become the frames of `folder`:
// its earlier frame files (0001.obj, …) go, its other files stay.
void install_obj_frames(const std::filesystem::path& staging, const std::filesystem::path& output);

// A staging folder beside `output` (a trailing '/' is not part of the
// name), of this process's own: nothing the user did not name is touched.
std::filesystem::path staging_folder(const std::string& output);

// Per unit_type, the units of a mesh3d stream and their bytes (start codes included).
struct UnitSizes {
  uint64_t bytes[kUnitTypes] = {};
  uint64_t count[kUnitTypes] = {};
};
UnitSizes unit_sizes(const ContainerParts& parts, uint64_t stream_size);

// What a stream tells besides its frames; an empty codec for a sequence.
struct StreamFacts {
  std::string codec;
  uint64_t bytes = 0;
  bool coding_order = false;  // its vertices numbered in coding order (encode3d --reorder)
};

// A sequence's frames in any form load_sequence reads, or a glTF animation
// (cli/gltf.h) baked at its keyframes.
MeshSequence load_frames(const std::string& path);

// The same, read frame by frame when large (open_sequence); a glTF
// animation in memory, the mesh, animation and rate `selection` chooses
// (for another input, naming a mesh or an animation is a usage error).
std::unique_ptr<FrameSource> open_frames(const std::string& path, const GltfSelection& selection = {});

// A sequence's frames (load_frames), or a mesh3d stream's decoded frames (read once),
// with the stream's facts in `facts`.
MeshSequence load_sequence_or_stream(const std::string& path, StreamFacts* facts = nullptr);


// A usage error when the trace and the stream would share standard output.
void refuse_trace_to_output(bool trace, const std::string& output);
// Before anything is read, usage errors for an output that is an input or
// one of its files (a folder's or a pattern's frames, a PC2 cache's OBJ),
// -y or not; that exists without -y (console::check_output), a PC2
// cache's OBJ too; or that is a folder where a file is written.
enum class OutputForm { kFile, kFileOrFolder };
void refuse_overwriting(const std::string& input, const std::string& output, OutputForm form = OutputForm::kFile);

// --frames A:B (both included; "A:" to the end, ":B" from the first; empty: all).
std::pair<uint32_t, uint32_t> frame_range(const std::string& text);

}  // namespace m4mesh
