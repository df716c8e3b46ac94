#include "cli/sequence_writer.h"

#include <filesystem>
#include <vector>

#include "cli/console.h"
#include "cli/gltf.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "mesh3d/little_endian.h"
#include "mesh3d/ply.h"
#include "mesh3d/sequence.h"

namespace m4mesh {

namespace {

namespace fs = std::filesystem;

// Frames written into a staging folder beside the output, moved into
// place on commit; the folder goes if the writer is abandoned.
class StagedFrames : public SequenceWriter {
 public:
  explicit StagedFrames(const std::string& output) : staging_(staging_folder(output)) { fs::create_directories(staging_); }
  ~StagedFrames() override {
    std::error_code ignored;
    if (!committed_) fs::remove_all(staging_, ignored);
  }

 protected:
  fs::path staging_;
  bool committed_ = false;
};

// A folder of OBJ frames (0001.obj, …); its earlier frame files are replaced.
class ObjFolderWriter final : public StagedFrames {
 public:
  ObjFolderWriter(const std::string& output, std::span<const Triangle> faces) : StagedFrames(output), output_(output), faces_(faces) {}
  void frame(uint32_t index, std::span<const Vec3> positions) override {
    write_obj_frame(positions, faces_, (staging_ / obj_frame_name(index)).string());
  }
  void commit() override {
    install_obj_frames(staging_, fs::path(output_));
    committed_ = true;
  }

 private:
  std::string output_;
  std::span<const Triangle> faces_;
};

// PLY frames: the '*' of the name replaced by 0001, 0002, …; a name
// without '*' takes one frame. An existing file is refused (without -y)
// when its frame comes, before anything is moved into place.
class PlyWriter final : public StagedFrames {
 public:
  PlyWriter(const std::string& output, std::span<const Triangle> faces)
      : StagedFrames(output), output_(output), star_(fs::path(output).filename().string().find('*')), faces_(faces) {}
  void frame(uint32_t, std::span<const Vec3> positions) override {
    if (star_ == std::string::npos && !targets_.empty())
      throw usage_error(output_ + ": several frames need a name with '*' for the frame number (frames/*.ply)");
    std::string path = output_;
    if (star_ != std::string::npos) {
      char number[24];
      std::snprintf(number, sizeof number, "%04zu", targets_.size() + 1);
      path.replace(output_.size() - fs::path(output_).filename().string().size() + star_, 1, number);
    }
    console::check_output(path);
    write_ply_frame(positions, faces_, (staging_ / fs::path(path).filename()).string());
    targets_.push_back(path);
  }
  void commit() override {
    if (const fs::path folder = fs::path(output_).parent_path(); !folder.empty()) fs::create_directories(folder);
    for (const std::string& target : targets_) fs::rename(staging_ / fs::path(target).filename(), target);
    fs::remove(staging_);
    committed_ = true;
  }

 private:
  std::string output_;
  size_t star_;
  std::span<const Triangle> faces_;
  std::vector<std::string> targets_;
};

// Every frame's binary32 x, y, z (.f32), after a .m4seq header, or a PC2
// file's frames with its OBJ beside it (frame 0 and the faces). Without a
// frame count in advance, the .m4seq and PC2 forms keep the frames until
// commit(), which writes the header with the count.
class PackedWriter final : public SequenceWriter {
 public:
  PackedWriter(SequenceOutput form, const std::string& output, const SequenceShape& shape) : form_(form), output_(output), shape_(shape) {
    if (form_ != SequenceOutput::kF32 && !shape.frame_count) return;
    file_.emplace(output);
    std::string head;
    if (form_ == SequenceOutput::kM4seq) {
      head.assign("M4SEQ1\n");
      put_u32(head, shape.vertex_count);
      put_u32(head, static_cast<uint32_t>(shape.faces.size()));
      put_u32(head, *shape.frame_count);
      for (const Triangle& t : shape.faces)
        for (NodeIndex v : t.v) put_u32(head, v);
    } else if (form_ == SequenceOutput::kPc2) {
      head.assign("POINTCACHE2", 12);
      put_u32(head, 1);
      put_u32(head, shape.vertex_count);
      put_f32(head, 0.0f);  // start frame
      put_f32(head, 1.0f);  // sample rate
      put_u32(head, *shape.frame_count);
    }
    file_->write(head);
  }

  ~PackedWriter() override {
    std::error_code ignored;
    if (faces_written_) fs::remove(faces_file_temp(), ignored);
  }

  void frame(uint32_t, std::span<const Vec3> positions) override {
    if (form_ == SequenceOutput::kPc2 && frames_ == 0 && file_) {
      write_obj_frame(positions, shape_.faces, faces_file_temp());
      faces_written_ = true;
    }
    ++frames_;
    if (!file_) {
      kept_.frames.emplace_back(positions.begin(), positions.end());
      return;
    }
    std::string bytes;
    bytes.reserve(12 * positions.size());
    for (const Vec3& p : positions)
      for (double c : {p.x, p.y, p.z}) put_f32(bytes, static_cast<float>(c));
    file_->write(bytes);
  }

  void commit() override {
    if (!file_) {
      kept_.vertex_count = shape_.vertex_count;
      kept_.faces.assign(shape_.faces.begin(), shape_.faces.end());
      if (form_ == SequenceOutput::kPc2)
        write_pc2_sequence(kept_, output_);
      else
        write_binary_sequence(kept_, output_);
      return;
    }
    if (shape_.frame_count && frames_ != *shape_.frame_count)
      throw Error(ErrorKind::kIo, "", kNoPlane, kNoOffset,
                  output_ + ": " + std::to_string(frames_) + " frames written where its header says " + std::to_string(*shape_.frame_count));
    file_->commit();
    if (faces_written_) {
      std::error_code failed;
      fs::rename(faces_file_temp(), pc2_faces_path(output_), failed);
      if (failed) throw Error(ErrorKind::kIo, "", kNoPlane, kNoOffset, pc2_faces_path(output_) + ": cannot rename into place");
      faces_written_ = false;
    }
  }

 private:
  // The PC2's OBJ is written beside its final name and moved there on commit.
  std::string faces_file_temp() const { return pc2_faces_path(output_) + ".partial-obj"; }

  SequenceOutput form_;
  std::string output_;
  SequenceShape shape_;
  std::optional<AtomicFile> file_;
  bool faces_written_ = false;
  MeshSequence kept_;
  uint32_t frames_ = 0;
};

// A glTF animation: its buffer holds every frame, written on commit.
class GltfWriter final : public SequenceWriter {
 public:
  GltfWriter(const std::string& output, const SequenceShape& shape) : output_(output), fps_(shape.fps) {
    kept_.vertex_count = shape.vertex_count;
    kept_.faces.assign(shape.faces.begin(), shape.faces.end());
  }
  void frame(uint32_t, std::span<const Vec3> positions) override { kept_.frames.emplace_back(positions.begin(), positions.end()); }
  void commit() override { write_gltf(kept_, fps_, output_); }

 private:
  std::string output_;
  double fps_;
  MeshSequence kept_;
};

}  // namespace

std::unique_ptr<SequenceWriter> sequence_writer(SequenceOutput form, const std::string& output, const SequenceShape& shape) {
  switch (form) {
    case SequenceOutput::kObjFolder:
      return std::make_unique<ObjFolderWriter>(output, shape.faces);
    case SequenceOutput::kPly:
      return std::make_unique<PlyWriter>(output, shape.faces);
    case SequenceOutput::kGltf:
      return std::make_unique<GltfWriter>(output, shape);
    default:
      return std::make_unique<PackedWriter>(form, output, shape);
  }
}

}  // namespace m4mesh
