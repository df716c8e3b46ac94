#include "mesh3d/frame_source.h"

#include <algorithm>
#include <cmath>

#include "common/error.h"
#include "syntax/mesh3d/container.h"

namespace m4mesh {

namespace {

Error input(const std::string& message) { return Error(ErrorKind::kInput, "", kNoPlane, kNoOffset, message); }

double diagonal(const Box3& box) {
  const double dx = box.hi.x - box.lo.x, dy = box.hi.y - box.lo.y, dz = box.hi.z - box.lo.z;
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

SequenceScan scan_frames(const FrameSource& source) {
  if (source.frame_count() == 0 || source.vertex_count() < 3 || source.faces().empty())
    throw input("a sequence needs frames, vertices and faces");
  if (source.vertex_count() > kMaxVertices3d || source.faces().size() > kMaxFaces3d) throw input("the mesh exceeds the container's limits");
  SequenceScan scan;
  FrameReader reader(source);
  for (uint32_t f = 0; f < source.frame_count(); ++f) {
    const std::span<const Vec3> frame = reader.get(f);
    Box3 box;
    for (size_t v = 0; v < frame.size(); ++v) {
      const Vec3& p = frame[v];
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
        throw input("frame " + std::to_string(f) + ", vertex " + std::to_string(v) + ": a position that is not a finite number (" +
                    std::to_string(p.x) + ", " + std::to_string(p.y) + ", " + std::to_string(p.z) + ")");
      box.add(p);
    }
    scan.box.add(box.lo);
    scan.box.add(box.hi);
    scan.largest_frame_diagonal = std::max(scan.largest_frame_diagonal, diagonal(box));
  }
  const std::span<const Triangle> faces = source.faces();
  for (size_t k = 0; k < faces.size(); ++k)
    for (NodeIndex v : faces[k].v)
      if (v >= source.vertex_count())
        throw input("face " + std::to_string(k) + " names vertex " + std::to_string(v) + " of " + std::to_string(source.vertex_count()));
  return scan;
}

}  // namespace

const SequenceScan& FrameSource::scan() const {
  std::call_once(scanned_, [this] { scan_ = scan_frames(*this); });
  return scan_;
}

std::span<const Vec3> FrameReader::get(uint32_t index) {
  if (const std::span<const Vec3> frame = source_.view(index); !frame.empty()) return frame;
  buffer_.resize(source_.vertex_count());
  source_.read(index, buffer_);
  return buffer_;
}

void SequenceSource::read(uint32_t index, std::span<Vec3> out) const {
  const std::vector<Vec3>& frame = sequence_.frames.at(index);
  if (frame.size() != sequence_.vertex_count)
    throw input("frame " + std::to_string(index) + " has " + std::to_string(frame.size()) + " vertices, not " +
                std::to_string(sequence_.vertex_count));
  std::copy(frame.begin(), frame.end(), out.begin());
}

std::span<const Vec3> SequenceSource::view(uint32_t index) const {
  const std::vector<Vec3>& frame = sequence_.frames.at(index);
  return frame.size() == sequence_.vertex_count ? std::span<const Vec3>(frame) : std::span<const Vec3>();
}

void RenumberedSource::read(uint32_t index, std::span<Vec3> out) const {
  if (input_of_.empty()) return source_.read(index, out);
  std::vector<Vec3> frame(source_.vertex_count());
  source_.read(index, frame);
  for (size_t v = 0; v < input_of_.size(); ++v) out[v] = frame[input_of_[v]];
}

MeshSequence read_all_frames(const FrameSource& source) {
  MeshSequence s;
  s.vertex_count = source.vertex_count();
  s.faces.assign(source.faces().begin(), source.faces().end());
  s.frames.resize(source.frame_count());
  for (uint32_t f = 0; f < source.frame_count(); ++f) {
    s.frames[f].resize(s.vertex_count);
    source.read(f, s.frames[f]);
  }
  return s;
}

}  // namespace m4mesh
