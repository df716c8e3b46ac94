// The clustered-PCA codec's segments (docs/codec_cpca_wpt.md, "Segments"): streams the encoder writes, streams written symbol by
// symbol for what it never writes, and those to reject.
#include <functional>
#include <optional>

#include "conformance/suite3d/cases.h"
#include "conformance/suite3d/inputs.h"
#include "conformance/suite3d/stream_edits.h"
#include "decoder/mesh3d/container_decoder.h"
#include "decoder/mesh3d/cpca_wpt.h"
#include "encoder/mesh3d/base_mesh.h"
#include "mesh3d/cpca_wpt.h"
#include "mesh3d/frame_hash.h"

namespace m4mesh::suite3d {

namespace {

// A refinement of a written segmented stream: what it carries and its
// values (a start's translation, a component's basis and coefficients, a
// continued component's coefficients).
struct Written {
  CpcaRefinementHeader h;
  std::vector<int32_t> translation, basis, coefficients;
  bool trajectory = false;  // a trajectory component, or one continuing it
};

// The values a segment's refinements carry over to the next (a start's
// last translation, each component's last coefficients, with their
// shifts), per cluster, as a decoder keeps them.
struct Carry {
  struct Lanes {
    std::array<int32_t, 3> last{};
    uint32_t shift = 0;
    bool trajectory = false;
  };
  std::vector<std::optional<Lanes>> start;
  std::vector<std::vector<Lanes>> listed;
};

// A stream written symbol by symbol over waving_flag(frames, 3) (16
// vertices: clusters 0, vertices 0 … 7, and 1, the others), its segments
// of `segment_frames` frames; each unit a list of refinements (a group
// when it holds several) of the segment starting at its frame; the
// starts' and continued components' first differences from the values
// carried over from the segment before.
class SegmentedStream {
 public:
  SegmentedStream(uint32_t frames, uint32_t segment_frames) : sequence_(waving_flag(static_cast<int>(frames), 3, false)) {
    cluster_of_.assign(sequence_.vertex_count, 1);
    for (uint32_t v = 0; v < 8; ++v) cluster_of_[v] = 0;
    const ContainerParts parts = cpca_one_cluster_parts(sequence_);
    writer_.emplace(cpca_written_start(parts, cluster_of_, 2, std::nullopt, segment_frames));
    members_ = cpca_members(cluster_of_, 2);
    segment_frames_ = segment_frames;
    frames_ = frames;
    const BaseMesh base = base_mesh_of(parts);
    faces_ = base.faces;
    mesh_.emplace(faces_, plan_base_mesh(sequence_.faces, sequence_.vertex_count, false).input_of, cluster_of_, 2,
                  base.positions);
    carry_ = next_ = empty_carry();
  }

  uint32_t frames_of(uint32_t first) const { return std::min(segment_frames_, frames_ - first); }
  size_t members(uint32_t cluster) const { return members_[cluster].size(); }

  // A unit of the segment at frame `first`.
  void unit(uint32_t first, std::vector<Written> refinements) {
    enter(first);
    syntax::EntropyWriteIO<false> symbols(syntax::SectionPlace{});
    std::vector<CpcaRefinementHeader> list;
    for (const Written& w : refinements) list.push_back(w.h);
    if (list.size() > 1) {
      std::vector<uint8_t> started(2, 0);
      for (const auto& [c, lanes] : started_in_segment_) started[c] = 1;
      syntax::CpcaGroupContexts contexts;
      syntax::describe_group_list(
          symbols, contexts, std::span(list), 2, [&](uint32_t c) { return started[c] != 0; },
          [&](uint32_t c) { return static_cast<uint32_t>(carry_.listed[c].size()); },
          [&](const CpcaRefinementHeader& h, bool) {
            if (h.kind == kCpcaStart) started[h.cluster] = 1;
          });
    }
    syntax::CpcaCoders coders;
    for (Written& w : refinements) {
      std::array<int64_t, 3> before{};
      if (w.h.kind == kCpcaStart && carry_.start[w.h.cluster]) before = at(*carry_.start[w.h.cluster], w.h.shift, kCpcaMaxTranslation);
      if (w.h.kind == kCpcaContinued && w.h.reference < carry_.listed[w.h.cluster].size())
        before = at(carry_.listed[w.h.cluster][w.h.reference], w.h.shift, kCpcaMaxCoefficient);
      describe_refinement(symbols, coders, *mesh_, w.h, w.trajectory, before, w.translation, w.basis, w.coefficients);
      keep(w);
    }
    CpcaRefinement r;
    if (list.size() > 1) {
      r.kind = kCpcaGroup;
      r.cluster = 0;
      r.shift = 0;
      r.group = list;
    } else {
      r.cluster = list[0].cluster;
      r.kind = list[0].kind;
      r.shift = list[0].shift;
      r.reference = list[0].reference;
    }
    writer_->unit(refinement_unit_bytes(r, symbols, first));
  }

  // A unit of the segment at frame `first` whose data is `r` with the
  // symbols written by hand (values the shared descriptions refuse to write).
  void crafted(uint32_t first, const CpcaRefinement& r, syntax::EntropyWriteIO<false>& symbols) {
    enter(first);
    writer_->unit(refinement_unit_bytes(r, symbols, first));
  }

  // A frame hash unit, or a group hash unit, of the frames as decoded so far.
  void frame_hash(uint32_t frame) {
    FrameHash hash;
    const Digest digest = digest_of(frame);
    hash.md5 = digest;
    hash_unit(UnitType::kFrameHash, frame, [&](syntax::WriteIO& io) { syntax::describe(io, hash); });
  }
  void group_hash(uint32_t first, uint32_t count) {
    std::vector<Digest> digests;
    for (uint32_t f = first; f < first + count; ++f) digests.push_back(digest_of(f));
    const Digest group = group_digest(digests);
    GroupHash hash{count, group};
    hash_unit(UnitType::kGroupHash, first, [&](syntax::WriteIO& io) { syntax::describe(io, hash); });
  }

  std::vector<uint8_t> finish() { return writer_->finish(); }

 private:
  static Carry empty_carry() { return {std::vector<std::optional<Carry::Lanes>>(2), std::vector<std::vector<Carry::Lanes>>(2)}; }

  // A segment's first unit makes the previous one's carried values those
  // to continue (none when it had no unit).
  void enter(uint32_t first) {
    if (first == segment_) return;
    carry_ = first == segment_ + segment_frames_ ? next_ : empty_carry();
    next_ = empty_carry();
    started_in_segment_.clear();
    segment_ = first;
  }

  static std::array<int64_t, 3> at(const Carry::Lanes& lanes, uint32_t shift, int64_t limit) {
    std::array<int64_t, 3> before{};
    for (size_t l = 0; l < 3; ++l) before[l] = syntax::cpca_carried(lanes.last[l], lanes.shift, shift, limit);
    return before;
  }

  void keep(const Written& w) {
    if (w.h.kind == kCpcaStart) {
      started_in_segment_[w.h.cluster] = 1;
      Carry::Lanes lanes{{}, w.h.shift, false};
      for (size_t a = 0; a < 3; ++a) lanes.last[a] = w.translation[w.translation.size() - 3 + a];
      next_.start[w.h.cluster] = lanes;
      return;
    }
    const size_t count = w.trajectory ? 3 : 1;
    Carry::Lanes lanes{{}, w.h.shift, w.trajectory};
    for (size_t l = 0; l < count; ++l) lanes.last[l] = w.coefficients[w.coefficients.size() - count + l];
    next_.listed[w.h.cluster].push_back(lanes);
  }

  template <class Describe>
  void hash_unit(UnitType type, uint32_t frame, Describe&& describe) {
    BitWriter writer;
    syntax::WriteIO io(writer);
    UnitHeader header{static_cast<uint32_t>(type), frame};
    syntax::describe(io, header);
    describe(io);
    writer_->unit(writer.take_bytes());
  }

  // A frame as the decoder holds it now: the stream so far, decoded.
  Digest digest_of(uint32_t frame) {
    ContainerWriter copy = *writer_;
    const std::vector<uint8_t> so_far = copy.finish(false);
    Mesh3dDecoder decoder(so_far);
    while (decoder.next_unit()) {
    }
    std::vector<Float3> positions(sequence_.vertex_count);
    decoder.frame(frame, positions);
    return frame_digest(positions);
  }

  MeshSequence sequence_;
  std::vector<uint32_t> cluster_of_;
  std::vector<std::vector<NodeIndex>> members_;
  std::optional<ContainerWriter> writer_;
  std::vector<Triangle> faces_;  // the base mesh's, which the prediction over the mesh holds
  std::optional<CpcaMeshPrediction> mesh_;
  uint32_t segment_frames_ = 1, frames_ = 1, segment_ = 0;
  Carry carry_, next_;
  std::map<uint32_t, int> started_in_segment_;
};

// Values a, a + step, a + 2 step, … (count of them).
std::vector<int32_t> ramp(size_t count, int32_t first, int32_t step) {
  std::vector<int32_t> values(count);
  for (size_t i = 0; i < count; ++i) values[i] = first + static_cast<int32_t>(i) * step;
  return values;
}

Written start(uint32_t cluster, uint32_t shift, std::vector<int32_t> translation) {
  return {{cluster, kCpcaStart, shift, 0}, std::move(translation), {}, {}, false};
}
Written component(uint32_t cluster, uint32_t kind, uint32_t shift, std::vector<int32_t> basis, std::vector<int32_t> coefficients) {
  return {{cluster, kind, shift, 0}, {}, std::move(basis), std::move(coefficients), kind == kCpcaTrajectory};
}
Written continued(uint32_t cluster, uint32_t reference, bool trajectory, uint32_t shift, std::vector<int32_t> coefficients) {
  return {{cluster, kCpcaContinued, shift, reference}, {}, {}, std::move(coefficients), trajectory};
}

// Segments 0 … 3, 4 … 7 and 8, 9 of 10 frames; frame 0's segment ends
// with its clusters' last translations odd (x −3, y 3, z 5 at shift 17),
// the next continues them at shift 16 (halves rounded up), then in one
// group a shape component's last coefficient 7 at shift 0 continued at
// shift 63 (the base saturates at 2^23) and a trajectory component's
// lanes at shift 63 continued at 32 (the coder's channels 0 and 1 … 3
// side by side); cluster 1 a group of a start, a continued component
// (its reference in no raw bit) and a new one; the last segment of 2
// frames refines cluster 1 alone, continuing the second of its two
// components (a reference in 1 raw bit).
SegmentedStream written_segments(const std::function<void(SegmentedStream&, uint32_t)>& after_segment = nullptr) {
  SegmentedStream s(10, 4);
  const size_t m0 = s.members(0), m1 = s.members(1);
  s.unit(0, {start(0, 17, {5, 1, 0, 3, 2, 1, 0, 3, 3, -3, 3, 5})});
  s.unit(0, {component(0, kCpcaComponent, 0, ramp(3 * m0, -4, 1), {1, 3, 5, 7})});
  s.unit(0, {component(0, kCpcaTrajectory, 63, ramp(m0, 100, 7), {0, 0, 0, 1, 1, 1, 2, -2, 0, 1, -1, 2})});
  s.unit(0, {start(1, 16, ramp(12, 2, 1))});
  s.unit(0, {component(1, kCpcaComponent, 20, ramp(3 * m1, 3, -1), {2, 4, 6, 8})});
  if (after_segment) after_segment(s, 0);
  s.unit(4, {start(0, 16, {-1, 2, 3, 0, 2, 4, 1, 1, 1, 2, 0, -2})});
  s.unit(4, {continued(0, 0, false, 63, {(1 << 23) - 5, (1 << 23) - 3, 100, -100}),
             continued(0, 1, true, 32, {0, 0, 0, 1, -1, 0, 2, 2, 2, 0, 0, 0})});
  s.unit(4, {start(1, 18, ramp(12, 40, -3)), continued(1, 0, false, 21, {9, 7, 5, 3}),
             component(1, kCpcaComponent, 19, ramp(3 * m1, -5, 2), {1, -1, 1, -1})});
  if (after_segment) after_segment(s, 4);
  s.unit(8, {start(1, 16, {1, 2, 3, 4, 5, 6})});
  s.unit(8, {continued(1, 1, false, 17, {-2, 6})});
  if (after_segment) after_segment(s, 8);
  return s;
}

}  // namespace

std::vector<SuiteCase> cpca_segment_cases(bool traced) {
  std::vector<SuiteCase> suite;
  const MeshSequence flag = waving_flag(22, 8, false);
  suite.push_back(valid("cpca-36-segments", "segments of 8, 8 and 6 frames: trajectory components continued in groups, starts carried over",
                        {"cpca", "cpca-segments"}, flag,
                        cpca({{"clusters", "3"}, {"model", "trajectory"}, {"segment-frames", "8"}, {"group-bytes", "128"}, {"noise", "-2"}}),
                        traced));
  suite.push_back(valid("cpca-37-segments-shape", "segments of 10, 10 and 2 frames: shape components continued each in a unit of its own",
                        {"cpca", "cpca-segments"}, flag, cpca({{"clusters", "2"}, {"segment-frames", "10"}, {"noise", "-2"}}), traced));
  {
    // Hash units: a frame of a later segment (the mean shape) covered after
    // a unit of segment 0; each segment's frames after its last unit.
    SegmentedStream s = written_segments([](SegmentedStream& w, uint32_t first) {
      if (first == 0) w.frame_hash(9);
      w.group_hash(first, w.frames_of(first));
    });
    suite.push_back(written_case("cpca-38-segments-written",
                                 "segments written symbol by symbol: carried values rounded (halves up), saturated and shifted far, "
                                 "continued components alone and in a group, references in 0 and 1 raw bits, a last segment of 2 frames "
                                 "refining one cluster, hashes of a later segment's frame and of each segment",
                                 {"cpca", "cpca-segments"}, s.finish()));
  }
  {
    // Segment 1 of 3 … 5 has no unit: its frames keep the mean shape.
    SegmentedStream s(9, 3);
    s.unit(0, {start(0, 16, ramp(9, 1, 1)), start(1, 16, ramp(9, -1, 1))});
    s.unit(0, {component(0, kCpcaComponent, 16, ramp(3 * s.members(0), 1, 1), {1, 2, 3})});
    s.group_hash(0, 6);  // frames 3 … 5: a later segment's, held as the mean shape
    s.unit(6, {start(0, 16, ramp(9, 2, -1))});
    s.unit(6, {component(0, kCpcaComponent, 16, ramp(3 * s.members(0), -1, 1), {3, 2, 1})});
    s.group_hash(6, 3);
    suite.push_back(written_case("cpca-39-segment-skipped", "a segment without units between two with units: its frames the mean shape",
                                 {"cpca", "cpca-segments"}, s.finish()));
  }
  {
    // Continued components whose coefficients step through prefix_schedule() and 3 on every channel: a shape
    // component's lane (channel 0) and a trajectory component's three (1 … 3), in a segment as long as the schedule.
    std::vector<int32_t> schedule = prefix_schedule();
    schedule.insert(schedule.end(), 100, 0);  // the order back to 0, then a suffix whose top bit is 1 (powers of two have none)
    schedule.push_back(3);
    const uint32_t length = static_cast<uint32_t>(schedule.size());
    SegmentedStream s(2 * length, length);
    std::vector<int32_t> lane(length), lanes(3 * size_t{length});
    int32_t value = 0;
    for (uint32_t n = 0; n < length; ++n) {
      lane[n] = value += schedule[n];
      for (size_t l = 0; l < 3; ++l) lanes[3 * n + l] = value;
    }
    s.unit(0, {start(0, 16, std::vector<int32_t>(3 * size_t{length}))});
    s.unit(0, {component(0, kCpcaComponent, 16, ramp(3 * s.members(0), 1, 1), std::vector<int32_t>(length))});
    s.unit(0, {component(0, kCpcaTrajectory, 16, ramp(s.members(0), 1, 1), std::vector<int32_t>(3 * size_t{length}))});
    s.unit(length, {start(0, 16, std::vector<int32_t>(3 * size_t{length}))});
    s.unit(length, {continued(0, 0, false, 16, lane)});
    s.unit(length, {continued(0, 1, true, 16, lanes)});
    suite.push_back(written_case("cpca-42-continued-prefixes", "continued components' coefficients of every prefix length 0 … 13 after "
                                 "each class and a suffix's top bit 1, on the shape lane and the three trajectory lanes", {"cpca", "cpca-segments"}, s.finish()));
  }
  {
    // Carried values that pass ±R within the shifts' reach (d ≤ 30), saturated there: cluster 0's last translation
    // (5, 3, −3) at shift 0 carried to shift 28 (±2^29), its component's last coefficient 7 at shift 0 continued at
    // shift 30 (2^23); cluster 1's (10, 11, 12) at shift 0 carried to shift 22 (10 · 2^22 …: beyond ±2^23, within ±2^29).
    SegmentedStream s(8, 4);
    const size_t m0 = s.members(0);
    constexpr int32_t kT = int32_t{1} << 29, kC = int32_t{1} << 23;
    s.unit(0, {start(0, 0, {0, 0, 0, 1, 1, -1, 2, 2, -2, 5, 3, -3})});
    s.unit(0, {component(0, kCpcaComponent, 0, ramp(3 * m0, 1, 1), {1, 3, 5, 7})});
    s.unit(0, {start(1, 0, ramp(12, 1, 1))});
    s.group_hash(0, 4);
    s.unit(4, {start(0, 28, {kT - 1, kT - 2, -kT + 1, kT - 3, kT - 4, -kT + 2, kT - 5, kT - 6, -kT + 3, kT - 7, kT - 8, -kT + 4})});
    s.unit(4, {continued(0, 0, false, 30, {kC - 1, kC - 2, kC - 4, kC - 8})});
    s.unit(4, {start(1, 22, {(10 << 22) + 1, (11 << 22) - 1, 12 << 22, (10 << 22) + 2, (11 << 22) - 2, 12 << 22, (10 << 22) + 3, (11 << 22) - 3,
                            12 << 22, (10 << 22) + 4, (11 << 22) - 4, 12 << 22})});
    s.group_hash(4, 4);
    suite.push_back(written_case("cpca-47-carried-saturated", "carried values saturated within the shifts' reach: translations at ±2^29 "
                                 "(shift 0 → 28), a coefficient at 2^23 (0 → 30); a translation carried beyond 2^23 within 2^29 (0 → 22)",
                                 {"cpca", "cpca-segments"}, s.finish()));
  }
  {
    // The segment limit's edge: 1,024 vertices × 4,096 frames, exactly 2^22 vertex-frames, every frame the mean shape.
    const std::vector<uint8_t> short_one = encode_mesh3d(waving_strip(2, 31, 31), cpca({{"clusters", "1"}})).stream;
    suite.push_back(written_case("cpca-48-segment-at-limit", "a segment of exactly 2^22 vertex-frames (1,024 vertices, 4,096 frames), "
                                 "no refinement unit: every frame the mean shape", {"cpca", "cpca-segments"},
                                 edited(short_one, [&](ContainerParts& p) {
                                   put_field(p.object_payload, object_field<CpcaHeader>(short_one, "frame_count"), 4096);
                                   put_field(p.object_payload, object_field<CpcaHeader>(short_one, "segment_frames"), 4096);
                                   p.units.resize(1);
                                 })));
  }
  suite.push_back(valid("cpca-40-segments-of-one", "segments of one frame", {"cpca", "cpca-segments"}, waving_flag(4, 3, false),
                        cpca({{"clusters", "2"}, {"model", "trajectory"}, {"segment-frames", "1"}, {"noise", "-2"}}), traced));
  {
    // One segment however long: segment_frames 2^32 − 1 over cpca-12's frames.
    const std::vector<uint8_t> one = encode_mesh3d(waving_flag(9, 8, false), cpca({{"clusters", "4"}, {"model", "trajectory"}})).stream;
    suite.push_back(written_case("cpca-41-segment-frames-max", "segment_frames 2^32 − 1: every frame in one segment", {"cpca", "cpca-segments"},
                                 edited(one, [&](ContainerParts& p) {
                                   put_field(p.object_payload, object_field<CpcaHeader>(one, "segment_frames"), UINT32_MAX);
                                 })));
  }
  return suite;
}

std::vector<SuiteCase> cpca_segment_rejected(const std::vector<SuiteCase>& valid) {
  std::vector<SuiteCase> suite;
  const std::vector<uint8_t> groups = stream_of(valid, "cpca-36-segments"), lone = stream_of(valid, "cpca-37-segments-shape");
  auto header_field = [&](const char* name) { return object_field<CpcaHeader>(groups, name); };
  suite.push_back(invalid("x-157-cpca-segment-frames-zero", "segment_frames 0", {"cpca-segments"},
                          edited(groups, [&](ContainerParts& p) { put_field(p.object_payload, header_field("segment_frames"), 0); }),
                          ErrorKind::kOutOfRange, "segment_frames", kNoPlane));
  suite.push_back(invalid("x-158-cpca-segment-limit", "segments of 2^22 frames of 81 vertices in a stream of as many frames", {"cpca-segments"},
                          edited(groups,
                                 [&](ContainerParts& p) {
                                   put_field(p.object_payload, object_field<CpcaHeader>(groups, "frame_count"), 1u << 22);
                                   put_field(p.object_payload, header_field("segment_frames"), 1u << 22);
                                 }),
                          ErrorKind::kLimit, "segment_frames", kNoPlane));
  // Two rules broken at once: the header's fields and lengths come before the segment limit.
  suite.push_back(invalid("x-186-cpca-segment-limit-and-map-length", "x-158's segments, cluster_map_bins_bytes past the payload: the length first",
                          {"cpca-segments"},
                          edited(groups,
                                 [&](ContainerParts& p) {
                                   put_field(p.object_payload, object_field<CpcaHeader>(groups, "frame_count"), 1u << 22);
                                   put_field(p.object_payload, header_field("segment_frames"), 1u << 22);
                                   put_field(p.object_payload, header_field("cluster_map_bins_bytes"), 0xFFFFFF);
                                 }),
                          ErrorKind::kOutOfRange, "cluster_map_bins_bytes", kNoPlane));
  // The first refinement unit of the stream's second segment (frame 8).
  auto second_segment = [](const ContainerParts& p) {
    for (size_t n = 0;; ++n) {
      const size_t k = refinement_unit(p, n);
      if (unit_header_of(p.units[k].payload).frame_index != 0) return k;
    }
  };
  suite.push_back(invalid("x-159-cpca-segment-frame-index", "a refinement unit naming frame 9, inside the segment at 8", {"cpca-segments"},
                          edited(groups,
                                 [&](ContainerParts& p) { put_field(p.units[second_segment(p)].payload, unit_header_field("frame_index"), 9); }),
                          ErrorKind::kStructure, "frame_index", kNoPlane));
  suite.push_back(invalid("x-160-cpca-segment-backwards", "a refinement unit of segment 0 after one of segment 1", {"cpca-segments"},
                          edited(groups,
                                 [&](ContainerParts& p) {
                                   const size_t k = second_segment(p);
                                   p.units.insert(p.units.begin() + static_cast<std::ptrdiff_t>(k) + 1, p.units[refinement_unit(p, 1)]);
                                 }),
                          ErrorKind::kStructure, "frame_index", kNoPlane));
  suite.push_back(invalid("x-161-cpca-continued-first-segment", "a continued component (unit_kind 5) in the first segment", {"cpca-segments"},
                          edited(lone, [&](ContainerParts& p) { put_field(p.units[refinement_unit(p, 1)].payload, refinement_field("unit_kind"), 5); }),
                          ErrorKind::kStructure, "unit_kind", kNoPlane));
  {
    // cpca-37's first continued component.
    const ContainerParts parts = split_container(lone);
    size_t k = 0;
    for (size_t n = 0;; ++n) {
      k = refinement_unit(parts, n);
      if (field_value(parts.units[k].payload, refinement_field("unit_kind")) == kCpcaContinued) break;
    }
    suite.push_back(invalid("x-169-cpca-continued-left-over", "a byte after a continued component's raw bits", {"cpca-segments"},
                            edited(lone, [&](ContainerParts& p) { p.units[k].payload.push_back(0x00); }), ErrorKind::kStructure,
                            "continued_coefficient", kNoPlane));
  }
  {
    // Cluster 0 sends three components in segment 0; segment 1 continues the fourth.
    SegmentedStream s(8, 4);
    const size_t m0 = s.members(0);
    s.unit(0, {start(0, 16, ramp(12, 1, 1))});
    for (int32_t c = 1; c <= 3; ++c) s.unit(0, {component(0, kCpcaComponent, 16, ramp(3 * m0, c, 1), {c, c, c, c})});
    s.unit(4, {start(0, 16, ramp(12, 1, 1))});
    s.unit(4, {continued(0, 3, false, 16, {1, 1, 1, 1})});
    suite.push_back(invalid("x-162-cpca-continued-reference-beyond", "a continued component's reference 3 of a list of 3", {"cpca-segments"},
                            s.finish(), ErrorKind::kOutOfRange, "reference", kNoPlane));
  }
  {
    // Cluster 1 sends three components in segment 0; segment 1's group
    // starts it, then names the fourth of its list (2 raw bits: 3).
    SegmentedStream s(8, 4);
    const size_t m1 = s.members(1);
    s.unit(0, {start(1, 16, ramp(12, 1, 1))});
    for (int32_t c = 1; c <= 3; ++c) s.unit(0, {component(1, kCpcaComponent, 16, ramp(3 * m1, c, 1), {c, c, c, c})});
    syntax::EntropyWriteIO<false> symbols(syntax::SectionPlace{});
    syntax::CpcaGroupContexts contexts;
    uint32_t cluster = 1, reference = 3;
    int32_t same_shift = 0;
    bool continued_bin = true;
    symbols.raw("group_cluster", 1, cluster);
    contexts.shift.describe(symbols, 0, same_shift, syntax::kCpcaGroupShift);
    symbols.raw("group_cluster", 1, cluster);
    symbols.bin("group_continued", contexts.continued, 0, continued_bin);
    symbols.raw("group_reference", 2, reference);
    CpcaRefinement group{0, kCpcaGroup, 0, {CpcaRefinementHeader{1, kCpcaStart, 16, 0}, CpcaRefinementHeader{1, kCpcaContinued, 16, 3}}, 0, {}, {}};
    s.crafted(4, group, symbols);
    suite.push_back(invalid("x-163-cpca-group-reference-beyond", "a group's group_reference 3 of a list of 3", {"cpca-segments"}, s.finish(),
                            ErrorKind::kOutOfRange, "group_reference", kNoPlane));
  }
  {
    SegmentedStream s(8, 4);
    const size_t m0 = s.members(0);
    s.unit(0, {start(0, 16, ramp(12, 1, 1))});
    s.unit(0, {component(0, kCpcaComponent, 16, ramp(3 * m0, 1, 1), {1, 2, 3, 4})});
    s.unit(4, {continued(0, 0, false, 16, {1, 1, 1, 1})});
    suite.push_back(invalid("x-164-cpca-continued-not-started", "a continued component before its cluster's start in the segment",
                            {"cpca-segments"}, s.finish(), ErrorKind::kStructure, "unit_kind", kNoPlane));
  }
  {
    // Cluster 0 (8 members) over segments of 4 frames: at most min(24, 4) = 4 shape components a segment.
    SegmentedStream s(8, 4);
    const size_t m0 = s.members(0);
    s.unit(0, {start(0, 16, ramp(12, 1, 1))});
    s.unit(0, {component(0, kCpcaComponent, 16, ramp(3 * m0, 1, 1), {1, 2, 3, 4})});
    s.unit(4, {start(0, 16, ramp(12, 1, 1))});
    for (int i = 0; i < 5; ++i) s.unit(4, {continued(0, 0, false, 16, {1, 1, 1, 1})});
    suite.push_back(invalid("x-165-cpca-continued-beyond-components", "a fifth shape component (continued) where a segment of 4 frames "
                            "takes 4", {"cpca-segments"}, s.finish(), ErrorKind::kStructure, "cluster", kNoPlane));
  }
  {
    // Two rules broken at once: cluster 0's segment 1 holds its 4 shape and 8 trajectory components, then continues entry 1
    // of a list of 1: `reference` before the count.
    SegmentedStream s(8, 4);
    const size_t m0 = s.members(0);
    s.unit(0, {start(0, 16, ramp(12, 1, 1))});
    s.unit(0, {component(0, kCpcaComponent, 16, ramp(3 * m0, 1, 1), {1, 2, 3, 4})});
    s.unit(4, {start(0, 16, ramp(12, 1, 1))});
    for (int32_t c = 1; c <= 4; ++c) s.unit(4, {component(0, kCpcaComponent, 16, ramp(3 * m0, c, 1), {c, c, c, c})});
    for (int32_t c = 1; c <= 8; ++c) s.unit(4, {component(0, kCpcaTrajectory, 16, ramp(m0, c, 1), std::vector<int32_t>(12, c))});
    s.unit(4, {continued(0, 1, false, 16, {1, 1, 1, 1})});
    suite.push_back(invalid("x-187-cpca-continued-reference-and-count", "a continued component's reference 1 of a list of 1 where the "
                            "segment's shape and trajectory counts are full: the reference first", {"cpca-segments"}, s.finish(),
                            ErrorKind::kOutOfRange, "reference", kNoPlane));
  }
  {
    // After segment 1's first unit, frames 0 … 7 are final: their hashes come too late.
    auto after_second_start = [&](const std::function<std::vector<uint8_t>(uint32_t)>& hash) {
      return edited(groups, [&](ContainerParts& p) {
        const size_t k = second_segment(p);
        p.units.insert(p.units.begin() + static_cast<std::ptrdiff_t>(k) + 1, ContainerUnit{0, 0, hash(8)});
      });
    };
    const ContainerParts parts = split_container(groups);
    auto copy_of_hash = [&](UnitType type, uint32_t frame) {
      for (const ContainerUnit& u : parts.units)
        if (unit_header_of(u.payload).type() == type && unit_header_of(u.payload).frame_index == frame) return u.payload;
      throw Error(ErrorKind::kStructure, "", kNoPlane, kNoOffset, "suite: no such hash unit");
    };
    suite.push_back(invalid("x-166-cpca-frame-hash-released", "a frame hash of frame 0 after a unit of the segment at frame 8",
                            {"cpca-segments"}, after_second_start([&](uint32_t) { return copy_of_hash(UnitType::kFrameHash, 0); }),
                            ErrorKind::kStructure, "frame_index", 0));
    suite.push_back(invalid("x-167-cpca-group-hash-released", "a group hash of frames 7 … 8 after a unit of the segment at frame 8",
                            {"cpca-segments"}, after_second_start([&](uint32_t) {
                              std::vector<uint8_t> unit = copy_of_hash(UnitType::kFrameHash, 7);
                              BitWriter writer;
                              syntax::WriteIO io(writer);
                              UnitHeader header{static_cast<uint32_t>(UnitType::kGroupHash), 7};
                              syntax::describe(io, header);
                              GroupHash hash{2, std::span<const uint8_t>(unit).last(kFrameMd5Bytes)};
                              syntax::describe(io, hash);
                              return writer.take_bytes();
                            }),
                            ErrorKind::kStructure, "group_frames", 7));
  }
  {
    SegmentedStream s(8, 4);
    const size_t m0 = s.members(0);
    s.unit(0, {start(0, 16, ramp(12, 1, 1))});
    s.unit(0, {component(0, kCpcaComponent, 0, ramp(3 * m0, 1, 1), {1, 2, 3, 4})});
    s.unit(4, {start(0, 16, ramp(12, 1, 1))});
    // The base of the first difference saturates at 2^23 (shift 0 → 63): 2^23, 2^23, then 2^23 + 1.
    syntax::EntropyWriteIO<false> symbols(syntax::SectionPlace{});
    syntax::ResidualCoder<4> coder;
    for (int32_t difference : {0, 0, 1}) coder.describe(symbols, 0, difference, syntax::kCpcaContinuedCoefficient);
    CpcaRefinement unit{0, kCpcaContinued, 63, {}, 0, {}, {}};
    s.crafted(4, unit, symbols);
    suite.push_back(invalid("x-168-cpca-continued-coefficient-range", "a continued coefficient 2^23 + 1 (its base saturated at 2^23)",
                            {"cpca-segments"}, s.finish(), ErrorKind::kOutOfRange, "continued_coefficient", kNoPlane));
  }
  {
    // unit_kind 5 is the last.
    Encode3dOptions o = cpca({{"clusters", "2"}});
    o.hashes = false;
    const std::vector<uint8_t> stream = encode_mesh3d(waving_flag(4, 3, false), o).stream;
    suite.push_back(invalid("x-170-cpca-unit-kind-6", "unit_kind 6, one past the last", {"cpca-segments"},
                            edited(stream,
                                   [&](ContainerParts& p) { put_field(p.units[refinement_unit(p, 1)].payload, refinement_field("unit_kind"), 6); }),
                            ErrorKind::kOutOfRange, "unit_kind", kNoPlane));
  }
  {
    // Segment 1 (frames 3 … 5) has no unit: segment 2's components have none to continue.
    SegmentedStream s(9, 3);
    const size_t m0 = s.members(0);
    s.unit(0, {start(0, 16, ramp(9, 1, 1))});
    s.unit(0, {component(0, kCpcaComponent, 16, ramp(3 * m0, 1, 1), {1, 2, 3})});
    s.unit(6, {start(0, 16, ramp(9, 1, 1))});
    s.unit(6, {continued(0, 0, false, 16, {1, 1, 1})});
    suite.push_back(invalid("x-171-cpca-continued-after-skip", "a continued component in the segment after one without units",
                            {"cpca-segments"}, s.finish(), ErrorKind::kStructure, "unit_kind", kNoPlane));
  }
  return suite;
}

}  // namespace m4mesh::suite3d
