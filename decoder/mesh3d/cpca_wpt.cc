// The clustered-PCA codec (codec_id 4) decoding (docs/codec_cpca_wpt.md):
// the cluster map from the header (read with it, or after the base mesh
// when its prediction needs the faces), the mean shape from the base mesh, then
// every refinement unit adds a cluster's mean trajectory (its start) or one
// of its operators to every frame.
#include "decoder/mesh3d/cpca_wpt.h"

#include <algorithm>
#include <array>
#include <memory>
#include <optional>

#include "codecs3d/codec_decoder.h"
#include "mesh3d/cpca_wpt.h"
#include "syntax/mesh3d/cpca_wpt.h"
#include "syntax/mesh3d/entropy_io.h"

namespace m4mesh {

namespace {

// The segment length from which a decoder keeps its members' fits over the mesh (CpcaMeshPrediction::keep_fits).
constexpr uint32_t kKeptFitFrames = 9;


// The header's cluster map sections and where they are, kept to be read
// once the base mesh gives the faces (cluster_map_prediction 1).
struct MapSections {
  std::vector<uint8_t> bins, raw;
  syntax::SectionPlace place;
  uint64_t cluster_count_offset = 0;  // where an empty cluster is reported
};

// A component decoded in a segment, which the next segment may continue.
struct ListedComponent {
  std::shared_ptr<const std::vector<int32_t>> basis;
  bool trajectory = false;  // a component of the members' trajectories (unit_kind 3, or one continuing it)
  CpcaCarried coefficients;
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
        trajectories_(header.cluster_count, 0),
        listed_(header.cluster_count),
        previous_(header.cluster_count),
        start_(header.cluster_count),
        previous_start_(header.cluster_count) {
    header_.map_bins = map_.bins;
    header_.map_raw = map_.raw;
    if (header_.map_prediction == kCpcaMapByDifference) read_map(MeshPredictor({}, 0), header_trace);
  }

  void decode_unit(const UnitHeader& unit, syntax::ReadIO& io, std::vector<uint32_t>& decoded) override {
    if (unit.type() == UnitType::kBaseMesh) {
      if (animation_) io.fail(ErrorKind::kStructure, "unit_type", "a second base mesh unit: the mean shape is sent once");
      BaseMesh base = read_base_mesh(io, object_, trace_);
      MeshPredictor around(base.faces, object_.vertex_count);
      if (header_.map_prediction == kCpcaMapByNeighbours) {
        try {
          if (trace_) {
            Trace in_object = trace_->in_object();
            read_map(around, &in_object);
          } else {
            read_map(around, nullptr);
          }
        } catch (const Error& e) {
          throw in_object_payload(e);
        }
      }
      mesh_.emplace(std::move(around), base.coding_order, cluster_of_, header_.cluster_count, base.positions);
      faces_ = std::move(base.faces);
      animation_.emplace(header_, base.positions, members_, frames_of(0));
      report(decoded);
      return;
    }
    if (!animation_) io.fail(ErrorKind::kStructure, "unit_type", "a refinement unit before the base mesh");
    enter_segment(io, unit.frame_index);
    CpcaRefinement r;
    syntax::describe(io, r, [&](const CpcaRefinementHeader& h, bool grouped) { admit(io, h, grouped); });
    const uint8_t* payload = io.reader().data();
    const syntax::SectionPlace place{"bins", "raw", 8 * static_cast<uint64_t>(r.bins.data() - payload),
                                     8 * static_cast<uint64_t>(r.raw.data() - payload), io.plane()};
    if (trace_) {
      syntax::EntropyReadIO<true> symbols(r.bins, r.raw, place, trace_);
      read_refinements(symbols, r);
    } else {
      syntax::EntropyReadIO<false> symbols(r.bins, r.raw, place);
      read_refinements(symbols, r);
    }
    report(decoded);
  }

  const std::vector<Triangle>& faces() const override { return faces_; }
  void frame(uint32_t index, std::span<Float3> positions) const override {
    if (index < first_frame_ + animation_->frames())
      animation_->frame(index - first_frame_, positions);
    else
      animation_->mean_frame(positions);
  }
  void frames(uint32_t first, std::span<const std::span<Float3>> positions) const override {
    // Those of the segment at once, then any beyond it.
    const uint32_t end = first_frame_ + animation_->frames();
    const size_t within = first >= end ? 0 : std::min<size_t>(positions.size(), end - first);
    if (within > 0) animation_->frames(first - first_frame_, positions.first(within));
    for (size_t k = within; k < positions.size(); ++k) frame(first + static_cast<uint32_t>(k), positions[k]);
  }
  bool holds_frames() const override { return true; }
  uint32_t frames_decoded() const override { return animation_ ? object_.frame_count : 0; }
  uint32_t first_held_frame(const UnitHeader& next) const override {
    const uint32_t first = next.frame_index - next.frame_index % header_.segment_frames;
    return next.type() == UnitType::kRefinement && animation_ && first > first_frame_ ? first : first_frame_;
  }

 private:
  // The frames of the segment that starts at `first`.
  uint32_t frames_of(uint32_t first) const { return std::min(header_.segment_frames, object_.frame_count - first); }

  void report(std::vector<uint32_t>& decoded) const {
    for (uint32_t f = first_frame_; f < first_frame_ + animation_->frames(); ++f) decoded.push_back(f);
  }

  // A refinement unit refines the segment its frame_index starts: the
  // current one, or a later one (the frames before it are then final).
  void enter_segment(syntax::ReadIO& io, uint32_t frame_index) {
    if (frame_index % header_.segment_frames != 0)
      io.fail(ErrorKind::kStructure, "frame_index",
              "a refinement unit names the first frame of its segment, a multiple of segment_frames (" + std::to_string(header_.segment_frames) +
                  ")");
    if (frame_index < first_frame_)
      io.fail(ErrorKind::kStructure, "frame_index",
              "a refinement unit of the segment at frame " + std::to_string(frame_index) + " after one of the segment at frame " +
                  std::to_string(first_frame_) + ": segments come in order");
    if (frame_index == first_frame_) return;
    // Components may continue those of the segment just before, when it had units.
    const bool adjacent = frame_index - first_frame_ == header_.segment_frames;
    first_frame_ = frame_index;
    animation_->reset(frames_of(frame_index));
    for (uint32_t c = 0; c < header_.cluster_count; ++c) {
      previous_[c] = adjacent ? std::move(listed_[c]) : std::vector<ListedComponent>();
      listed_[c].clear();
      previous_start_[c] = adjacent ? start_[c] : std::nullopt;
      start_[c].reset();
    }
    std::fill(started_.begin(), started_.end(), 0);
    std::fill(components_.begin(), components_.end(), 0);
    std::fill(trajectories_.begin(), trajectories_.end(), 0);
  }

  // The cluster map's symbols, placed in the object payload; every cluster must have a vertex.
  void read_map(const MeshPredictor& around, Trace* trace) {
    cluster_of_ = trace ? read_cluster_map<true>(header_, around, object_.vertex_count, map_.place, trace)
                        : read_cluster_map<false>(header_, around, object_.vertex_count, map_.place);
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
    bool trajectory = h.kind == kCpcaTrajectory;
    if (h.kind == kCpcaContinued) {
      const std::vector<ListedComponent>& previous = previous_[h.cluster];
      if (previous.empty())
        io.fail(ErrorKind::kStructure, kind_field, "a continued component of cluster " + cluster + ", which has none in the previous segment");
      if (h.reference >= previous.size())
        io.fail(ErrorKind::kOutOfRange, "reference",
                "component " + std::to_string(h.reference) + " of the " + std::to_string(previous.size()) + " the previous segment sent");
      trajectory = previous[h.reference].trajectory;
    }
    uint64_t& count = trajectory ? trajectories_[h.cluster] : components_[h.cluster];
    const uint64_t limit = cpca_component_limit(trajectory ? kCpcaTrajectory : kCpcaComponent, members_[h.cluster].size(), animation_->frames());
    if (count >= limit)
      io.fail(ErrorKind::kStructure, cluster_field,
              "a refinement beyond cluster " + cluster + "'s " + std::to_string(limit) + (trajectory ? " trajectory components" : " components"));
    ++count;
  }

  // A group's list, then the unit's refinements in order, each
  // applied once its symbols are read, with one set of coders; then the end
  // of the sections.
  template <class IO>
  void read_refinements(IO& io, CpcaRefinement& r) {
    if (r.kind == kCpcaGroup) {
      syntax::CpcaGroupContexts contexts;
      syntax::describe_group_list(
          io, contexts, r.group, header_.cluster_count, [&](uint32_t cluster) { return started_[cluster] != 0; },
          [&](uint32_t cluster) { return static_cast<uint32_t>(previous_[cluster].size()); },
          [&](const CpcaRefinementHeader& h, bool grouped) { admit(io, h, grouped); });
    }
    const std::vector<CpcaRefinementHeader> refinements = r.refinements();
    syntax::CpcaCoders coders;
    for (const CpcaRefinementHeader& h : refinements) {
      const size_t members = members_[h.cluster].size(), frames = animation_->frames();
      const ListedComponent* continued = h.kind == kCpcaContinued ? &previous_[h.cluster][h.reference] : nullptr;
      const bool trajectory = h.kind == kCpcaTrajectory || (continued && continued->trajectory);
      const size_t lanes = trajectory ? 3 : 1;
      std::vector<int32_t> translation(h.kind == kCpcaStart ? 3 * frames : 0);
      std::vector<int32_t> basis(h.kind == kCpcaStart || continued ? 0 : (trajectory ? 1 : 3) * members);
      std::vector<int32_t> coefficients(h.kind == kCpcaStart ? 0 : lanes * frames);
      std::array<int64_t, 3> before{};
      if (h.kind == kCpcaStart && previous_start_[h.cluster]) before = previous_start_[h.cluster]->at(h.shift, kCpcaMaxTranslation);
      if (continued) before = continued->coefficients.at(h.shift, kCpcaMaxCoefficient);
      // A member's fit over the mesh is the same for every component of its cluster: found once and kept, when the
      // fits (about 200 bytes a member) take no more than 24 bytes a vertex-frame of the segment.
      if ((h.kind == kCpcaMeshComponent || h.kind == kCpcaTrajectory) && std::min(header_.segment_frames, object_.frame_count) >= kKeptFitFrames)
        mesh_->keep_fits(h.cluster);
      describe_refinement(io, coders, *mesh_, h, trajectory, before, translation, basis, coefficients);
      if (h.kind == kCpcaStart) {
        start_[h.cluster] = CpcaCarried::of(translation, 3, h.shift);
        animation_->translate(h.cluster, std::move(translation), h.shift);
        continue;
      }
      ListedComponent listed{continued ? continued->basis : std::make_shared<const std::vector<int32_t>>(std::move(basis)), trajectory,
                             CpcaCarried::of(coefficients, lanes, h.shift)};
      animation_->refine(h.cluster, listed.basis, std::move(coefficients), h.shift, trajectory);
      listed_[h.cluster].push_back(std::move(listed));
    }
    io.finish(syntax::cpca_last_element(refinements.back().kind));
  }

  ObjectHeader object_;
  CpcaHeader header_;
  MapSections map_;
  std::vector<uint32_t> cluster_of_;
  std::vector<std::vector<NodeIndex>> members_;
  // The segment being refined: its first frame; per cluster, whether it
  // has started and its components of unit_kind 1 and 2 (and 5 continuing
  // them) and of unit_kind 3 (and 5 continuing them) decoded.
  uint32_t first_frame_ = 0;
  std::vector<uint8_t> started_;
  std::vector<uint64_t> components_;
  std::vector<uint64_t> trajectories_;
  // Per cluster, the components of this segment and of the one before, in
  // the order decoded, and the starts of both.
  std::vector<std::vector<ListedComponent>> listed_, previous_;
  std::vector<std::optional<CpcaCarried>> start_, previous_start_;
  std::vector<Triangle> faces_;
  std::optional<CpcaSegment> animation_;
  std::optional<CpcaMeshPrediction> mesh_;
};

}  // namespace

std::unique_ptr<CodecDecoder3d> make_cpca_wpt_decoder(const ObjectHeader& object, syntax::ReadIO& io) {
  CpcaHeader header;
  syntax::describe(io, header);
  if (object.frame_count == 0) io.fail(ErrorKind::kStructure, "frame_count", "the clustered-PCA codec needs the frame count");
  if (uint64_t{object.vertex_count} * std::min(header.segment_frames, object.frame_count) > kCpcaMaxVertexFrames) {
    io.fail(ErrorKind::kLimit, "segment_frames", "a segment of more than 2^22 vertex-frames");
  }
  const uint8_t* payload = io.reader().data();
  MapSections map{{header.map_bins.begin(), header.map_bins.end()},
                  {header.map_raw.begin(), header.map_raw.end()},
                  {"cluster_map_bins", "cluster_map_raw", 8 * static_cast<uint64_t>(header.map_bins.data() - payload),
                   8 * static_cast<uint64_t>(header.map_raw.data() - payload), kNoPlane},
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
  return read_cluster_map<false>(header, MeshPredictor(faces, object.vertex_count), object.vertex_count, syntax::SectionPlace{});
}

}  // namespace m4mesh
