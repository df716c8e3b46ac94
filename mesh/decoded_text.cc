#include "mesh/decoded_text.h"

#include <charconv>
#include <limits>

#include "common/error.h"

namespace m4mesh {

namespace {

constexpr size_t kFlushBytes = 1 << 16;

void append_int(std::string& out, int64_t value) {
  char digits[24];
  auto result = std::to_chars(digits, digits + sizeof digits, value);
  out.append(digits, result.ptr);
}

}  // namespace

DecodedTextWriter::DecodedTextWriter(Sink sink) : sink_(std::move(sink)) { buffer_ = "m4mesh-decoded 1\n"; }

void DecodedTextWriter::flush() {
  md5_.update(buffer_);
  if (sink_) sink_(buffer_);
  buffer_.clear();
}

void DecodedTextWriter::flush_if_full() {
  if (buffer_.size() >= kFlushBytes) flush();
}

void DecodedTextWriter::plane(const PlaneInfo& info, std::span<const Point> nodes,
                              std::span<const Triangle> triangles) {
  std::string& b = buffer_;
  b += "plane ";
  append_int(b, plane_index_++);
  if (!info.intra) {
    b += " P range=";
    append_int(b, info.range);
  } else if (info.kind == MeshKind::kUniform) {
    const UniformParams& u = info.uniform;
    b += " I uniform cols=";
    append_int(b, u.cols);
    b += " rows=";
    append_int(b, u.rows);
    b += " dx=";
    append_int(b, u.dx);
    b += " dy=";
    append_int(b, u.dy);
    b += " split=";
    append_int(b, u.split);
  } else {
    b += " I delaunay boundary=";
    append_int(b, info.boundary);
  }
  b += "\nnodes ";
  append_int(b, static_cast<int64_t>(nodes.size()));
  b += '\n';
  for (const Point& p : nodes) {
    append_int(b, p.x);
    b += ' ';
    append_int(b, p.y);
    b += '\n';
    flush_if_full();
  }
  if (!info.intra) return;
  b += "triangles ";
  append_int(b, static_cast<int64_t>(triangles.size()));
  b += '\n';
  for (const Triangle& t : triangles) {
    append_int(b, t.v[0]);
    b += ' ';
    append_int(b, t.v[1]);
    b += ' ';
    append_int(b, t.v[2]);
    b += '\n';
    flush_if_full();
  }
}

void DecodedTextWriter::finish_incomplete() { flush(); }

std::string DecodedTextWriter::finish() {
  buffer_ += "end\n";
  flush();
  return md5_.hex_digest();
}

namespace {

// A line-by-line reader of §9 text with strict tokens.
class TextCursor {
 public:
  TextCursor(std::string_view text, const std::string& source) : text_(text), source_(source) {}

  bool at_end() const { return pos_ >= text_.size(); }
  int64_t line_number() const { return line_; }

  std::string_view next_line() {
    ++line_;
    if (at_end()) fail("unexpected end of text");
    size_t end = text_.find('\n', pos_);
    if (end == std::string_view::npos) fail("line without a final LF");
    std::string_view line = text_.substr(pos_, end - pos_);
    pos_ = end + 1;
    return line;
  }

  [[noreturn]] void fail(const std::string& message) const { throw input_error(source_, line_, message); }

  // Parses an integer filling the whole token.
  int64_t integer(std::string_view token, int64_t lo, int64_t hi, const char* what) const {
    int64_t value = 0;
    auto result = std::from_chars(token.data(), token.data() + token.size(), value);
    if (token.empty() || result.ec != std::errc() || result.ptr != token.data() + token.size())
      fail(std::string("expected an integer for ") + what + ", found '" + std::string(token) + "'");
    if (value < lo || value > hi)
      fail(std::string(what) + " " + std::to_string(value) + " outside " + std::to_string(lo) + "…" +
           std::to_string(hi));
    return value;
  }

 private:
  std::string_view text_;
  const std::string& source_;
  size_t pos_ = 0;
  int64_t line_ = 0;
};

std::vector<std::string_view> split_spaces(std::string_view line) {
  std::vector<std::string_view> tokens;
  size_t start = 0;
  while (start <= line.size()) {
    size_t end = line.find(' ', start);
    if (end == std::string_view::npos) end = line.size();
    tokens.push_back(line.substr(start, end - start));
    start = end + 1;
  }
  return tokens;
}

// "key=value" with the expected key.
int64_t keyed(const TextCursor& cursor, std::string_view token, std::string_view key, int64_t lo, int64_t hi) {
  if (token.size() <= key.size() || token.substr(0, key.size()) != key || token[key.size()] != '=')
    cursor.fail("expected " + std::string(key) + "=…, found '" + std::string(token) + "'");
  return cursor.integer(token.substr(key.size() + 1), lo, hi, std::string(key).c_str());
}

constexpr int64_t kCoordinateLimit = int64_t{1} << 30;
constexpr int64_t kMaxNodes = 1023 * 1023;

}  // namespace

std::vector<MeshPlane> parse_decoded_text(std::string_view text, const std::string& source) {
  TextCursor cursor(text, source);
  if (cursor.next_line() != "m4mesh-decoded 1") cursor.fail("expected the header 'm4mesh-decoded 1'");
  std::vector<MeshPlane> planes;
  while (true) {
    std::string_view line = cursor.next_line();
    if (line == "end") break;
    std::vector<std::string_view> t = split_spaces(line);
    if (t.size() < 3 || t[0] != "plane") cursor.fail("expected 'plane K …' or 'end'");
    if (cursor.integer(t[1], 0, std::numeric_limits<int64_t>::max(), "plane number") !=
        static_cast<int64_t>(planes.size()))
      cursor.fail("planes must be numbered 0, 1, 2, … in order");
    MeshPlane plane;
    PlaneInfo& info = plane.info;
    if (t[2] == "P" && t.size() == 4) {
      info.intra = false;
      info.range = static_cast<uint32_t>(keyed(cursor, t[3], "range", 1, 3));
      if (planes.empty()) cursor.fail("a P-plane before any I-plane");
    } else if (t[2] == "I" && t.size() == 9 && t[3] == "uniform") {
      info.kind = MeshKind::kUniform;
      info.uniform.cols = static_cast<uint32_t>(keyed(cursor, t[4], "cols", 2, 1023));
      info.uniform.rows = static_cast<uint32_t>(keyed(cursor, t[5], "rows", 2, 1023));
      info.uniform.dx = static_cast<uint32_t>(keyed(cursor, t[6], "dx", 1, 255));
      info.uniform.dy = static_cast<uint32_t>(keyed(cursor, t[7], "dy", 1, 255));
      info.uniform.split = static_cast<uint32_t>(keyed(cursor, t[8], "split", 0, 3));
    } else if (t[2] == "I" && t.size() == 5 && t[3] == "delaunay") {
      info.kind = MeshKind::kDelaunay;
      info.boundary = static_cast<uint32_t>(keyed(cursor, t[4], "boundary", 3, 1023));
    } else {
      cursor.fail("malformed plane line '" + std::string(line) + "'");
    }

    std::vector<std::string_view> n = split_spaces(cursor.next_line());
    if (n.size() != 2 || n[0] != "nodes") cursor.fail("expected 'nodes N'");
    const int64_t count = cursor.integer(n[1], 3, kMaxNodes, "node count");
    if (info.intra && info.kind == MeshKind::kDelaunay && info.boundary > count)
      cursor.fail("boundary=" + std::to_string(info.boundary) + " exceeds the " + std::to_string(count) + " nodes");
    if (!info.intra && count != static_cast<int64_t>(planes.back().nodes.size()))
      cursor.fail("a P-plane has " + std::to_string(count) + " nodes where the mesh has " +
                  std::to_string(planes.back().nodes.size()));
    plane.nodes.reserve(static_cast<size_t>(count));
    for (int64_t i = 0; i < count; ++i) {
      std::vector<std::string_view> xy = split_spaces(cursor.next_line());
      if (xy.size() != 2) cursor.fail("expected 'x y'");
      plane.nodes.push_back(Point{static_cast<int32_t>(cursor.integer(xy[0], -kCoordinateLimit, kCoordinateLimit, "x")),
                                  static_cast<int32_t>(cursor.integer(xy[1], -kCoordinateLimit, kCoordinateLimit, "y"))});
    }
    if (info.intra) {
      std::vector<std::string_view> tr = split_spaces(cursor.next_line());
      if (tr.size() != 2 || tr[0] != "triangles") cursor.fail("expected 'triangles M'");
      const int64_t triangles = cursor.integer(tr[1], 1, 2 * kMaxNodes, "triangle count");
      plane.triangles.reserve(static_cast<size_t>(triangles));
      for (int64_t i = 0; i < triangles; ++i) {
        std::vector<std::string_view> abc = split_spaces(cursor.next_line());
        if (abc.size() != 3) cursor.fail("expected 'a b c'");
        Triangle tri;
        for (int j = 0; j < 3; ++j)
          tri.v[j] = static_cast<NodeIndex>(cursor.integer(abc[j], 0, count - 1, "node index"));
        plane.triangles.push_back(tri);
      }
    }
    planes.push_back(std::move(plane));
  }
  if (!cursor.at_end()) {
    cursor.next_line();
    cursor.fail("text after 'end'");
  }
  if (planes.empty()) cursor.fail("no planes");
  return planes;
}

}  // namespace m4mesh
