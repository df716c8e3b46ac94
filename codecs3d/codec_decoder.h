// The decoding half of a 3D codec, unit by unit. The container decoder
// (decoder/mesh3d/container_decoder.h) splits the stream, reads each unit's header and
// hands the codec every unit but hash units; the codec says which frames
// that unit (re)decoded and gives their positions. Frame-by-frame,
// out-of-order, progressive (every unit refines every frame) and
// floating-point codecs all fit this interface.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "common/point3.h"
#include "mesh/topology.h"
#include "mesh3d/base_mesh.h"
#include "syntax/io.h"
#include "syntax/mesh3d/container.h"

namespace m4mesh {

class CodecDecoder3d {
 public:
  virtual ~CodecDecoder3d() = default;

  // Decodes a unit's data: `io` reads the unit payload from just after its
  // header, with the frame set for errors (offsets count from the payload's
  // start; the container adds the unit's). Appends every frame whose
  // decoded state the unit set or changed to `decoded`.
  virtual void decode_unit(const UnitHeader& unit, syntax::ReadIO& io, std::vector<uint32_t>& decoded) = 0;

  // The connectivity, known after the first unit.
  virtual const std::vector<Triangle>& faces() const = 0;
  // A frame's decoded positions. Valid for the frames the last unit
  // reported; with holds_frames(), for every frame it holds.
  virtual void frame(uint32_t index, std::span<Float3> positions) const = 0;
  // frame() for frames first, first + 1, … into positions[0], [1], …: a
  // codec whose frames share their work gives them at once.
  virtual void frames(uint32_t first, std::span<const std::span<Float3>> positions) const {
    for (size_t k = 0; k < positions.size(); ++k) frame(first + static_cast<uint32_t>(k), positions[k]);
  }
  // Whether the codec keeps frames after the unit that decoded them (a
  // progressive codec, whose units refine frames already decoded);
  // otherwise the container copies each reported frame out before the
  // next unit.
  virtual bool holds_frames() const { return false; }
  // With holds_frames(): frames 0 … this − 1 are decoded.
  virtual uint32_t frames_decoded() const { return 0; }
  // With holds_frames(): the first frame the codec holds once `next` (a
  // unit whose container rules hold) is decoded. The frames before it are
  // final, and the container copies them out before `next` is decoded.
  virtual uint32_t first_held_frame(const UnitHeader& /*next*/) const { return 0; }
  // Before any unit: makes the codec's first unit the base mesh unit of
  // `frame`, an intra refresh; false when the codec cannot start there.
  virtual bool start_at(uint32_t frame) { return frame == 0; }

  // Symbols of arithmetic-coded sections are traced here when set.
  void set_trace(Trace* trace) { trace_ = trace; }

 protected:
  Trace* trace_ = nullptr;
};

// A rule on a value reconstructed after the unit's sections are decoded,
// placed at the unit data's first bit (docs/container3d.md, "Errors").
[[noreturn]] inline void fail_reconstruction(const syntax::ReadIO& io, ErrorKind kind, const char* element, const std::string& message) {
  io.fail_at(kind, element, syntax::unit_data_offset() - 32, message);
}

// A base mesh unit's data: the faces and the first frame's grid positions
// (docs/base_mesh.md), its symbols traced when `trace` is set.
BaseMesh read_base_mesh(syntax::ReadIO& io, const ObjectHeader& header, Trace* trace);

// An error of the object payload (its offset counted from the payload's
// start) found while a unit is decoded, as when a header's section is read
// late: placed in the object payload, outside any unit.
Error in_object_payload(const Error& e);

}  // namespace m4mesh
