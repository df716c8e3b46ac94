#include "conformance/coverage3d.h"

#include <optional>
#include <sstream>

#include "codecs3d/registry.h"
#include "decoder/mesh3d/container_decoder.h"
#include "syntax/mesh3d/base_mesh.h"
#include "syntax/mesh3d/residual.h"

namespace m4mesh {

namespace {

using Residual = syntax::ResidualCoder<1>;

std::string item(const std::string& area, const std::string& text) { return area + ": " + text; }
std::string bin_item(const std::string& area, const std::string& name, int context, int value) {
  return item(area, name + " ctx " + std::to_string(context) + " = " + std::to_string(value));
}

// A residual symbol's bin (syntax/mesh3d/residual.h) from its trace context
// number: a zero flag or prefix bin by channel, class of the previous
// residual and prefix slot; a sign bin by channel and previous sign; a top
// bin by channel.
std::string residual_bin_item(const std::string& area, const std::string& name, int context, int value) {
  std::string text = name + " channel ";
  if (name.ends_with("_sign")) {
    text += std::to_string(context / 3) + " after " + (context % 3 == 0 ? "none" : context % 3 == 1 ? "+" : "-");
  } else if (name.ends_with("_top")) {
    text += std::to_string(context);
  } else {
    const int group = context / (Residual::kPrefixContexts + 1), slot = context % (Residual::kPrefixContexts + 1) - 1;
    text += std::to_string(group / Residual::kClasses) + " class " + std::to_string(group % Residual::kClasses);
    if (slot >= 0) text += " bin " + std::to_string(slot) + (slot == Residual::kPrefixContexts - 1 ? "+" : "");
  }
  return item(area, text + " = " + std::to_string(value));
}

bool is_residual_bin(const std::string& name) {
  return name.ends_with("_nonzero") || name.ends_with("_prefix") || name.ends_with("_sign") || name.ends_with("_top");
}

// A residual family (syntax/mesh3d/residual.h) on `channels`, whose prefix
// length e cannot exceed max_e: its zero flag and prefix bins by class, its
// sign bins by previous sign and its top bins.
void residual_family(std::set<std::string>& out, const std::string& area, const std::string& name, std::initializer_list<int> channels,
                     int max_e = Residual::kMaxPrefix) {
  for (int channel : channels)
    for (int cls = 0; cls < Residual::kClasses; ++cls) {
      const int base = (channel * Residual::kClasses + cls) * (Residual::kPrefixContexts + 1);
      for (int v = 0; v < 2; ++v) out.insert(residual_bin_item(area, name + "_nonzero", base, v));
      for (int slot = 0; slot < Residual::kPrefixContexts; ++slot) {
        const bool last = slot == Residual::kPrefixContexts - 1;  // bins i ≥ 11 share it
        if (slot <= max_e) out.insert(residual_bin_item(area, name + "_prefix", base + 1 + slot, 0));
        if (slot < max_e || (last && max_e > slot)) out.insert(residual_bin_item(area, name + "_prefix", base + 1 + slot, 1));
      }
    }
  for (int channel : channels)
    for (int v = 0; v < 2; ++v) {
      for (int previous_sign = 0; previous_sign < 3; ++previous_sign) out.insert(residual_bin_item(area, name + "_sign", channel * 3 + previous_sign, v));
      out.insert(residual_bin_item(area, name + "_top", channel, v));
    }
}

// The area of a codec's own symbols and fields.
std::string codec_area(uint32_t codec_id) {
  const Codec3d* row = find_codec3d(codec_id);
  return row ? row->name : "unknown";
}

bool is_base_mesh_symbol(const std::string& name) {
  for (const char* prefix : {"gate_", "candidate_index", "seed_", "position_", "order_", "far_", "front_index", "loose_vertex"})
    if (name.starts_with(prefix)) return true;
  return false;
}

}  // namespace

std::set<std::string> coverage_items3d(std::span<const uint8_t> stream) {
  std::ostringstream text;
  const std::string area = codec_area(trace_mesh3d(stream, text));
  std::set<std::string> items;
  std::istringstream lines(text.str());
  uint32_t kind = 0;  // cpca-wpt's unit_kind of the unit in hand
  for (std::string l; std::getline(lines, l);) {
    const std::optional<TraceLine> line = parse_trace_line(l);
    if (!line || !line->numeric()) continue;
    const std::string& n = line->name;
    const int64_t value = std::stoll(line->value);
    const std::string where = is_base_mesh_symbol(n) ? "base-mesh" : area;
    if (line->bin()) {
      items.insert((is_residual_bin(n) ? residual_bin_item : bin_item)(where, n, line->context, static_cast<int>(value)));
      continue;
    }
    if (n == "unit_type" && value == 0 && line->frame > 0) items.insert(item(area, "intra refresh (a base mesh unit at a later frame)"));
    if (n == "unit_type" && value == 3) items.insert(item("container", "frame hash unit"));
    if (n == "unit_type" && value == 4) items.insert(item("container", "group hash unit"));
    if (n == "frame_count" && value == 0) items.insert(item("container", "frame_count = 0 (streaming)"));
    if (n == "vertex_order") items.insert(item("base-mesh", "vertex_order = " + std::to_string(value)));
    if (n == "loose_face_count" && value > 0) items.insert(item("base-mesh", "loose faces"));
    if (n == "quantization_bits" && (value == 4 || value == 24)) items.insert(item(area, "quantization_bits = " + std::to_string(value)));
    if (n == "prediction_mode" || n == "reference_mode" || n == "coding_mode") items.insert(item(area, n + " = " + std::to_string(value)));
    if (n == "temporal_gop") items.insert(item(area, value == 0 ? "temporal_gop = 0" : "temporal_gop > 0"));
    if ((n == "theta_bits" && (value == 2 || value == 15)) || (n == "rh_bits" && (value == 1 || value == 20)) ||
        (n == "max_depth" && (value == 1 || value == 20)) || (n == "fraction_bits" && (value == 0 || value == 16)))
      items.insert(item(area, n + " = " + std::to_string(value)));
    if (n == "direct_shift") items.insert(item(area, value == 0 ? "direct_shift = 0" : "direct_shift > 0"));
    if (n == "cluster_count") items.insert(item(area, value == 1 ? "cluster_count = 1" : "cluster_count > 1"));
    if (n == "unit_kind") {
      kind = static_cast<uint32_t>(value);
      items.insert(item(area, "unit_kind = " + line->value));
    }
    if (n == "shift") {
      const char* relation = value < 16 ? "< 16" : value == 16 ? "= 16" : "> 16";
      items.insert(item(area, std::string(kind == 0 ? "start" : "component") + " shift " + relation));
    }
  }
  return items;
}

std::map<std::string, std::set<std::string>> coverage_catalog3d() {
  std::map<std::string, std::set<std::string>> c;
  // The base mesh. deg(a), deg(b) ≥ 1 at every gate a → b (a gate lies on
  // a decoded face), so no context with a degree 0 is reachable;
  // gate_candidate is read only with candidates ≥ 1, candidate_index's
  // first bin only with 2 or more. Gates are visited first in, first out,
  // and a visited gate is closed (a border, or the face attached closes
  // it), so a gate's candidates come from half-edges added after it: the
  // next new half-edge of its own face, and one per face decoded since (a
  // face holding both a half-edge out of b and one into a would repeat
  // a → b). The face attached behind gate u → t is (t, u, c), whose new
  // gates are u → c, then c → t, and u and t had a face before. So, with D
  // the larger degree, gate u → c (deg(u) ≥ 2) sees at most
  // 1 + (D − 2) + (D − 1) candidates, c → t at most (D − 2) + (D − 1), a
  // seed's gates at most 2: at most 2D − 2 for D ≥ 2, and 1 for D = 1.
  // With deg(a) = 1, a is the new vertex c of gate c → t (u → c was a
  // border), whose candidates are the later faces' at t: at most
  // deg(b) − 2. With deg(b) = 1, b is the new vertex c of gate u → c (or a
  // seed's corner), whose first candidate t gives the face (c, u, t), which
  // repeats the half-edge u → t: candidate index 0 is never valid.
  std::set<std::string>& base = c["base-mesh"];
  for (int v = 0; v < 2; ++v) {
    for (int candidates = 0; candidates <= 3; ++candidates)
      for (int degree = 1; degree <= 7; ++degree) {
        if (candidates > (degree == 1 ? 1 : 2 * degree - 2)) continue;
        base.insert(bin_item("base-mesh", "gate_new_vertex", candidates * 8 + degree, v));
        if (candidates > 0) base.insert(bin_item("base-mesh", "gate_candidate", candidates * 8 + degree, v));
      }
    for (int b = 1; b <= 7; ++b)
      for (int a = 1; a <= 7; ++a) {
        if ((a == 1 && b < 4) || (b == 1 && (a == 1 || v == 0))) continue;
        base.insert(bin_item("base-mesh", "candidate_index", b * 8 + a, v));
      }
    for (int later = 64; later <= 67; ++later) base.insert(bin_item("base-mesh", "candidate_index", later, v));
    for (int border = 0; border < 2; ++border) base.insert(bin_item("base-mesh", "gate_border", border, v));
    base.insert(bin_item("base-mesh", "seed_new_vertex", 0, v));
    // Whether a far vertex is on the gate's front, and its index there (contexts by bin, the last for bins 3 on).
    base.insert(bin_item("base-mesh", "far_on_front", 0, v));
    for (int slot = 0; slot < syntax::BaseMeshContexts::kFrontSlots; ++slot) base.insert(bin_item("base-mesh", "front_index", slot, v));
  }
  residual_family(base, "base-mesh", "position", {0, 1, 2, 3, 4, 5});
  residual_family(base, "base-mesh", "order", {0});
  residual_family(base, "base-mesh", "far", {0});
  // A far residual of 0 names the gate's own vertex a: the face (b, a, a) is a `structure` error.
  for (int cls = 0; cls < Residual::kClasses; ++cls) base.erase(residual_bin_item("base-mesh", "far_nonzero", cls * (Residual::kPrefixContexts + 1), 0));
  for (int order = 0; order <= 2; ++order) base.insert(item("base-mesh", "vertex_order = " + std::to_string(order)));
  base.insert(item("base-mesh", "loose faces"));

  std::set<std::string>& container = c["container"];
  for (const char* s : {"frame hash unit", "group hash unit", "frame_count = 0 (streaming)"}) container.insert(item("container", s));

  std::set<std::string>& bfs = c["bfs3d"];
  residual_family(bfs, "bfs3d", "motion", {0});
  for (const char* s : {"prediction_mode = 0", "prediction_mode = 1", "intra refresh (a base mesh unit at a later frame)", "quantization_bits = 4",
                        "quantization_bits = 24"})
    bfs.insert(item("bfs3d", s));

  std::set<std::string>& ao = c["affine-octree"];
  for (int v = 0; v < 2; ++v)
    for (int depth = 0; depth < 16; ++depth) {
      ao.insert(bin_item("affine-octree", "split_flag", depth, v));
      ao.insert(bin_item("affine-octree", "direct_flag", depth, v));
    }
  residual_family(ao, "affine-octree", "matrix", {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11});
  residual_family(ao, "affine-octree", "direct", {12, 13, 14});
  for (const char* s : {"intra refresh (a base mesh unit at a later frame)", "direct_shift = 0", "direct_shift > 0", "max_depth = 1", "max_depth = 20",
                        "quantization_bits = 4", "quantization_bits = 24"})
    ao.insert(item("affine-octree", s));

  std::set<std::string>& lcc = c["lcc"];
  residual_family(lcc, "lcc", "direct", {0, 1, 2, 6, 7, 8});
  residual_family(lcc, "lcc", "theta", {3, 9});
  residual_family(lcc, "lcc", "rho", {4, 10});
  residual_family(lcc, "lcc", "zeta", {5, 11});
  for (const char* s : {"reference_mode = 0", "reference_mode = 1", "coding_mode = 0", "coding_mode = 1", "temporal_gop = 0", "temporal_gop > 0",
                        "theta_bits = 2", "theta_bits = 15", "rh_bits = 1", "rh_bits = 20", "quantization_bits = 4", "quantization_bits = 24"})
    lcc.insert(item("lcc", s));

  // cpca-wpt: cluster differences lie within ±254, so e ≤ 7.
  std::set<std::string>& cpca = c["cpca-wpt"];
  residual_family(cpca, "cpca-wpt", "cluster", {0}, 7);
  // Clusters start at 0 and stay at or above it: the first nonzero difference is positive.
  cpca.erase(residual_bin_item("cpca-wpt", "cluster_sign", 0, 1));
  residual_family(cpca, "cpca-wpt", "translation", {0, 1, 2});
  residual_family(cpca, "cpca-wpt", "basis", {0, 1, 2});
  residual_family(cpca, "cpca-wpt", "coefficient", {3, 6});
  residual_family(cpca, "cpca-wpt", "mesh_basis", {0, 1, 2, 3, 4, 5});
  residual_family(cpca, "cpca-wpt", "trajectory_basis", {0, 1});
  residual_family(cpca, "cpca-wpt", "trajectory_coefficient", {2, 3, 4});
  // Group lists: shift differences lie within ±63, so e ≤ 5.
  residual_family(cpca, "cpca-wpt", "group_shift", {0, 1}, 5);
  for (int v = 0; v < 2; ++v)
    for (const char* bin : {"group_trajectory", "group_mesh", "group_continued"}) cpca.insert(bin_item("cpca-wpt", bin, 0, v));
  // Continued components: a shape component's lane on channel 0, a trajectory component's on 1 … 3.
  residual_family(cpca, "cpca-wpt", "continued_coefficient", {0, 1, 2, 3});
  for (const char* s : {"start shift < 16", "start shift = 16", "start shift > 16", "component shift < 16", "component shift = 16",
                        "component shift > 16", "cluster_count = 1", "cluster_count > 1", "fraction_bits = 0", "fraction_bits = 16",
                        "quantization_bits = 4", "quantization_bits = 24", "unit_kind = 0", "unit_kind = 1", "unit_kind = 2", "unit_kind = 3",
                        "unit_kind = 5"})
    cpca.insert(item("cpca-wpt", s));
  return c;
}

}  // namespace m4mesh
