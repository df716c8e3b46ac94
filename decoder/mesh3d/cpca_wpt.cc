// The clustered-PCA codec (codec_id 4) decoding (docs/codec_cpca_wpt.md):
// the cluster map from the header (read with it, or after the base mesh
// when its prediction needs the faces), the mean shape from the base mesh, then
// every refinement unit adds a cluster's mean trajectory (its start) or one
// of its operators to every frame.
#include "decoder/mesh3d/cpca_wpt.h"

#include <optional>

#include "codecs3d/codec_decoder.h"
#include "mesh3d/cpca_wpt.h"
#include "syntax/mesh3d/cpca_wpt.h"
#include "syntax/mesh3d/entropy_io.h"

namespace m4mesh {

namespace {

// The header's cluster map sections and where they are, kept to be read
// once the base mesh gives the faces (cluster_map_prediction 1).
struct MapSections {
  std::vector<uint8_t> bins, raw;
  syntax::SectionPlace place;
  uint64_t cluster_count_offset = 0;  // where an empty cluster is reported
};

class CpcaDecoder final : public CodecDecoder3d {
 public:
  // header_trace: where the header's symbols are traced (the map of prediction 0).
  CpcaDecoder(const ObjectHeader& object, const CpcaHeader& header, MapSections map, Trace* header_trace)
      : object_(object),
        header_(header),
        map_(std::move(map)),
        started_(header.cluster_count, 0),
        components_(header.cluster_count, 0),
        trajectories_(header.cluster_count, 0) {
    header_.map_bins = map_.bins;
    header_.map_raw = map_.raw;
    if (header_.map_prediction == kCpcaMapByDifference) read_map({}, header_trace);
  }

  void decode_unit(const UnitHeader& unit, syntax::ReadIO& io, std::vector<uint32_t>& decoded) override {
    if (unit.type() == UnitType::kBaseMesh) {
      if (animation_) io.fail(ErrorKind::kStructure, "unit_type", "a second base mesh unit: the mean shape is sent once");
      BaseMesh base = read_base_mesh(io, object_, trace_);
      if (header_.map_prediction == kCpcaMapByNeighbours) {
        try {
          if (trace_) {
            Trace in_object = trace_->in_object();
            read_map(base.faces, &in_object);
          } else {
            read_map(base.faces, nullptr);
          }
        } catch (const Error& e) {
          throw in_object_payload(e);
        }
      }
      mesh_.emplace(base.faces, base.coding_order, cluster_of_, header_.cluster_count, object_.version, base.positions);
      faces_ = std::move(base.faces);
      animation_.emplace(header_, base.positions, object_.frame_count);
      for (uint32_t f = 0; f < object_.frame_count; ++f) decoded.push_back(f);
      return;
    }
    if (!animation_) io.fail(ErrorKind::kStructure, "unit_type", "a refinement unit before the base mesh");
    if (unit.frame_index != 0) io.fail(ErrorKind::kStructure, "frame_index", "a refinement unit refines every frame and names frame 0");
    CpcaRefinement r;
    r.version = object_.version;
    syntax::describe(io, r, [&](const CpcaRefinementHeader& h, bool grouped) { admit(io, h, grouped); });
    const uint8_t* payload = io.reader().data();
    const syntax::SectionPlace place{"bins", "raw", 8 * static_cast<uint64_t>(r.bins.data() - payload),
                                     8 * static_cast<uint64_t>(r.raw.data() - payload), io.plane(),
                                     object_.version};
    if (trace_) {
      syntax::EntropyReadIO<true> symbols(r.bins, r.raw, place, trace_);
      read_refinements(symbols, r);
    } else {
      syntax::EntropyReadIO<false> symbols(r.bins, r.raw, place);
      read_refinements(symbols, r);
    }
    for (uint32_t f = 0; f < object_.frame_count; ++f) decoded.push_back(f);
  }

  const std::vector<Triangle>& faces() const override { return faces_; }
  void frame(uint32_t index, std::span<Float3> positions) const override {
    const std::span<const Float3> frame = animation_->frame(index);
    std::copy(frame.begin(), frame.end(), positions.begin());
  }
  bool holds_all_frames() const override { return true; }

 private:
  // The cluster map's symbols, placed in the object payload; every cluster must have a vertex.
  void read_map(std::span<const Triangle> faces, Trace* trace) {
    cluster_of_ = trace ? read_cluster_map<true>(header_, faces, object_.vertex_count, map_.place, trace)
                        : read_cluster_map<false>(header_, faces, object_.vertex_count, map_.place);
    members_ = cpca_members(cluster_of_, header_.cluster_count);
    for (uint32_t c = 0; c < header_.cluster_count; ++c)
      if (members_[c].empty())
        throw Error(ErrorKind::kStructure, "cluster_count", kNoPlane, static_cast<int64_t>(map_.cluster_count_offset),
                    "cluster " + std::to_string(c) + " has no vertex");
  }

  // A refinement's rules, checked as soon as its fields are read (the
  // unit's own, or a group's `group_*`), and counted: the later ones of a
  // group see the earlier ones as decoded.
  template <class IO>
  void admit(IO& io, const CpcaRefinementHeader& h, bool grouped) {
    const char* cluster_field = grouped ? "group_cluster" : "cluster";
    const char* kind_field = grouped ? "group_kind" : "unit_kind";
    if (h.cluster >= header_.cluster_count)
      io.fail(ErrorKind::kOutOfRange, cluster_field, "cluster " + std::to_string(h.cluster) + " of " + std::to_string(header_.cluster_count));
    const std::string cluster = std::to_string(h.cluster);
    if (h.kind == kCpcaStart) {
      if (started_[h.cluster]) io.fail(ErrorKind::kStructure, kind_field, "a second start of cluster " + cluster);
      started_[h.cluster] = 1;
      return;
    }
    if (!started_[h.cluster]) io.fail(ErrorKind::kStructure, kind_field, "a component of cluster " + cluster + ", whose basis has not started");
    const bool trajectory = h.kind == kCpcaTrajectory;
    uint64_t& count = trajectory ? trajectories_[h.cluster] : components_[h.cluster];
    const uint64_t limit = cpca_component_limit(h.kind, members_[h.cluster].size(), object_.frame_count);
    if (count >= limit)
      io.fail(ErrorKind::kStructure, cluster_field,
              "a refinement beyond cluster " + cluster + "'s " + std::to_string(limit) + (trajectory ? " trajectory components" : " components"));
    ++count;
  }

  // A group's list (from version 5), then the unit's refinements in order, each
  // applied once its symbols are read, with one set of coders; then the end
  // of the sections.
  template <class IO>
  void read_refinements(IO& io, CpcaRefinement& r) {
    if (r.kind == kCpcaGroup && cpca_group_list_in_bins(r.version)) {
      syntax::CpcaGroupContexts contexts;
      syntax::describe_group_list(
          io, contexts, r.group, header_.cluster_count, [&](uint32_t cluster) { return started_[cluster] != 0; },
          [&](const CpcaRefinementHeader& h, bool grouped) { admit(io, h, grouped); });
    }
    const std::vector<CpcaRefinementHeader> refinements = r.refinements();
    syntax::CpcaCoders coders;
    for (const CpcaRefinementHeader& h : refinements) {
      const size_t members = members_[h.cluster].size(), frames = object_.frame_count;
      const size_t per_member = h.kind == kCpcaTrajectory ? 1 : 3;
      translation_.resize(h.kind == kCpcaStart ? 3 * frames : 0);
      basis_.resize(h.kind == kCpcaStart ? 0 : per_member * members);
      coefficients_.resize(h.kind == kCpcaStart ? 0 : 3 / per_member * frames);
      describe_refinement(io, coders, *mesh_, h, translation_, basis_, coefficients_);
      if (h.kind == kCpcaStart)
        animation_->translate(members_[h.cluster], translation_, h.shift);
      else
        animation_->refine(members_[h.cluster], basis_, coefficients_, h.shift, h.kind == kCpcaTrajectory);
    }
    io.finish(syntax::cpca_last_element(refinements.back().kind));
  }

  ObjectHeader object_;
  CpcaHeader header_;
  MapSections map_;
  std::vector<uint32_t> cluster_of_;
  std::vector<std::vector<NodeIndex>> members_;
  std::vector<uint8_t> started_;      // per cluster: its start decoded
  std::vector<uint64_t> components_;    // per cluster: its components of unit_kind 1 and 2 decoded
  std::vector<uint64_t> trajectories_;  // per cluster: its components of unit_kind 3 decoded
  std::vector<Triangle> faces_;
  std::optional<CpcaAnimation> animation_;
  std::optional<CpcaMeshPrediction> mesh_;
  std::vector<int32_t> translation_, basis_, coefficients_;
};

}  // namespace

std::unique_ptr<CodecDecoder3d> make_cpca_wpt_decoder(const ObjectHeader& object, syntax::ReadIO& io) {
  CpcaHeader header;
  header.version = object.version;
  syntax::describe(io, header);
  if (object.frame_count == 0) io.fail(ErrorKind::kStructure, "frame_count", "the clustered-PCA codec needs the frame count");
  if (uint64_t{object.vertex_count} * object.frame_count > kCpcaMaxVertexFrames)
    io.fail(ErrorKind::kLimit, "frame_count", "more than 2^22 vertex-frames");
  const uint8_t* payload = io.reader().data();
  MapSections map{{header.map_bins.begin(), header.map_bins.end()},
                  {header.map_raw.begin(), header.map_raw.end()},
                  {"cluster_map_bins", "cluster_map_raw", 8 * static_cast<uint64_t>(header.map_bins.data() - payload),
                   8 * static_cast<uint64_t>(header.map_raw.data() - payload), kNoPlane, object.version},
                  io.start_of("cluster_count")};
  return std::make_unique<CpcaDecoder>(object, header, std::move(map), io.trace());
}

std::vector<uint32_t> cpca_cluster_map(const ContainerParts& parts) {
  const auto [object, header] = read_headers<CpcaHeader>(parts);
  std::vector<Triangle> faces;
  if (header.map_prediction == kCpcaMapByNeighbours) {
    const std::vector<uint8_t>& base = parts.units.at(0).payload;
    BitReader reader(base.data(), base.size());
    syntax::ReadIO io(reader);
    UnitHeader unit;
    syntax::describe(io, unit);
    faces = read_base_mesh(io, object, nullptr).faces;
  }
  return read_cluster_map<false>(header, faces, object.vertex_count, syntax::SectionPlace{.version = object.version});
}

}  // namespace m4mesh
