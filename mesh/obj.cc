#include "mesh/obj.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "common/error.h"
#include "common/parse_number.h"

namespace m4mesh {

namespace {

double parse_number(std::string_view token, const std::string& path, int64_t line) {
  double value = 0;
  if (token.empty() || parse_double(token.data(), token.data() + token.size(), value) != token.data() + token.size())
    throw input_error(path, line, "expected a number, found '" + std::string(token) + "'");
  if (!std::isfinite(value)) throw input_error(path, line, "non-finite number '" + std::string(token) + "'");
  return value;
}

// The vertex index of an "i", "i/t" or "i/t/n" face token, 0-based.
NodeIndex parse_face_index(std::string_view token, size_t vertex_count, const std::string& path, int64_t line) {
  token = token.substr(0, token.find('/'));
  int64_t index = 0;
  auto result = std::from_chars(token.data(), token.data() + token.size(), index);
  if (token.empty() || result.ec != std::errc() || result.ptr != token.data() + token.size())
    throw input_error(path, line, "malformed face index '" + std::string(token) + "'");
  if (index < 0) index += static_cast<int64_t>(vertex_count) + 1;  // relative index
  if (index < 1 || index > static_cast<int64_t>(vertex_count))
    throw input_error(path, line, "face index " + std::string(token) + " outside 1…" + std::to_string(vertex_count));
  return static_cast<NodeIndex>(index - 1);
}

// The number in a file name, for numeric frame order.
int64_t frame_number(const std::filesystem::path& path) {
  const std::string stem = path.stem().string();
  int64_t number = -1;
  for (size_t i = 0; i < stem.size();) {
    if (std::isdigit(static_cast<unsigned char>(stem[i]))) {
      size_t j = i;
      while (j < stem.size() && std::isdigit(static_cast<unsigned char>(stem[j]))) ++j;
      std::from_chars(stem.data() + i, stem.data() + j, number);
      i = j;
    } else {
      ++i;
    }
  }
  return number;
}

}  // namespace

ObjFrame read_obj(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw Error(ErrorKind::kIo, "", kNoPlane, kNoOffset, path + ": cannot open");
  ObjFrame frame;
  std::string text;
  int64_t line = 0;
  std::vector<std::string_view> tokens;
  while (std::getline(in, text)) {
    ++line;
    tokens.clear();
    std::string_view rest(text);
    while (!rest.empty()) {
      const size_t start = rest.find_first_not_of(" \t\r");
      if (start == std::string_view::npos) break;
      rest.remove_prefix(start);
      const size_t end = rest.find_first_of(" \t\r");
      tokens.push_back(rest.substr(0, end));
      rest.remove_prefix(end == std::string_view::npos ? rest.size() : end);
    }
    if (tokens.empty() || tokens[0][0] == '#') continue;
    if (tokens[0] == "v") {
      if (tokens.size() < 4) throw input_error(path, line, "a vertex needs x y z");
      frame.vertices.push_back({parse_number(tokens[1], path, line), parse_number(tokens[2], path, line),
                                parse_number(tokens[3], path, line)});
      frame.vertex_lines.push_back(line);
    } else if (tokens[0] == "f") {
      if (tokens.size() < 4) throw input_error(path, line, "a face needs at least 3 vertices");
      std::vector<NodeIndex> polygon;
      for (size_t i = 1; i < tokens.size(); ++i)
        polygon.push_back(parse_face_index(tokens[i], frame.vertices.size(), path, line));
      for (size_t i = 1; i + 1 < polygon.size(); ++i) frame.faces.push_back(Triangle{{polygon[0], polygon[i], polygon[i + 1]}});
    } else if (std::find(frame.dropped.begin(), frame.dropped.end(), tokens[0]) == frame.dropped.end()) {
      frame.dropped.emplace_back(tokens[0]);
    }
  }
  if (in.bad()) throw Error(ErrorKind::kIo, "", kNoPlane, kNoOffset, path + ": cannot read");
  if (frame.vertices.empty()) throw input_error(path, 0, "no vertices");
  return frame;
}

std::string dropped_records_note(const std::string& file, const std::vector<std::string>& dropped, const std::string& coded) {
  if (dropped.empty()) return "";
  std::string kinds;
  for (const std::string& kind : dropped) kinds += (kinds.empty() ? "" : ", ") + kind;
  return file + ": only " + coded + " are coded; its " + kinds + " records are left out";
}

std::vector<std::string> frame_files(const std::string& folder_or_pattern, std::initializer_list<const char*> kinds, std::vector<std::string>* unused) {
  namespace fs = std::filesystem;
  auto lower = [](std::string text) {
    for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return text;
  };
  fs::path folder;
  std::string prefix, suffix;  // a pattern's parts around '*'; empty for a folder
  const fs::path given(folder_or_pattern);
  if (fs::is_directory(given)) {
    folder = given;
  } else if (const std::string name = given.filename().string(); name.find('*') != std::string::npos) {
    folder = given.parent_path().empty() ? fs::path(".") : given.parent_path();
    prefix = name.substr(0, name.find('*'));
    suffix = name.substr(name.find('*') + 1);
  } else if (fs::is_regular_file(given)) {
    return {folder_or_pattern};
  } else {
    throw Error(ErrorKind::kIo, "", kNoPlane, kNoOffset, folder_or_pattern + ": no such file, folder or pattern");
  }
  const bool pattern = !prefix.empty() || !suffix.empty();
  std::vector<fs::path> files;
  std::map<std::string, fs::path> kinds_found;  // extension → its first file, by name
  for (const fs::directory_entry& entry : fs::directory_iterator(folder)) {
    if (!entry.is_regular_file()) continue;
    const std::string name = entry.path().filename().string();
    const std::string extension = lower(entry.path().extension().string());
    const bool frame = pattern ? name.size() >= prefix.size() + suffix.size() && name.starts_with(prefix) && lower(name).ends_with(lower(suffix))
                               : std::any_of(kinds.begin(), kinds.end(), [&](const char* k) { return extension == k; });
    if (!frame) {
      if (unused && !pattern) unused->push_back(entry.path().string());
      continue;
    }
    files.push_back(entry.path());
    if (auto [it, added] = kinds_found.try_emplace(extension, entry.path()); !added && entry.path() < it->second) it->second = entry.path();
  }
  if (files.empty()) throw Error(ErrorKind::kIo, "", kNoPlane, kNoOffset, folder_or_pattern + ": no frame files");
  if (kinds_found.size() > 1) {
    std::string examples;
    for (const auto& [extension, file] : kinds_found) examples += (examples.empty() ? "" : ", ") + file.filename().string();
    throw Error(ErrorKind::kInput, "", kNoPlane, kNoOffset,
                folder_or_pattern + ": frames of " + std::to_string(kinds_found.size()) + " kinds (" + examples +
                    "): one kind per folder, or a pattern such as " + (folder / ("*" + kinds_found.begin()->first)).string());
  }
  std::sort(files.begin(), files.end(), [](const fs::path& a, const fs::path& b) {
    const int64_t na = frame_number(a), nb = frame_number(b);
    return na != nb ? na < nb : a < b;
  });
  if (files.size() > 1 && frame_number(files.front()) < 0)
    throw Error(ErrorKind::kInput, "", kNoPlane, kNoOffset,
                files.front().string() + ": a frame file without a number among " + std::to_string(files.size()) +
                    " frames (each frame file's name holds its frame number)");
  for (size_t k = 1; k < files.size(); ++k)
    if (frame_number(files[k]) == frame_number(files[k - 1]))
      throw Error(ErrorKind::kInput, "", kNoPlane, kNoOffset,
                  files[k - 1].string() + " and " + files[k].string() + " are both frame " + std::to_string(frame_number(files[k])));
  if (unused) std::sort(unused->begin(), unused->end());
  std::vector<std::string> paths;
  for (const fs::path& p : files) paths.push_back(p.string());
  return paths;
}

std::string numbering_gaps_warning(const std::string& folder_or_pattern, const std::vector<std::string>& files) {
  if (files.size() < 3) return "";
  std::vector<int64_t> numbers;
  for (const std::string& f : files) numbers.push_back(frame_number(f));
  std::map<int64_t, size_t> steps;  // step → how often it occurs
  for (size_t k = 1; k < numbers.size(); ++k) ++steps[numbers[k] - numbers[k - 1]];
  // The most common step; of steps as common, the smallest.
  const int64_t step = std::max_element(steps.begin(), steps.end(), [](const auto& a, const auto& b) { return a.second < b.second; })->first;
  std::vector<int64_t> missing;
  std::string first_gap;
  uint64_t missing_count = 0;
  for (size_t k = 1; k < numbers.size(); ++k) {
    if (numbers[k] - numbers[k - 1] <= step) continue;
    if (first_gap.empty())
      first_gap = std::filesystem::path(files[k - 1]).filename().string() + " and " + std::filesystem::path(files[k]).filename().string();
    for (int64_t n = numbers[k - 1] + step; n < numbers[k]; n += step, ++missing_count)
      if (missing.size() < 5) missing.push_back(n);
  }
  if (missing_count == 0) return "";
  std::string list;
  for (int64_t n : missing) list += (list.empty() ? "" : ", ") + std::to_string(n);
  if (missing_count > missing.size()) list += ", …";
  return folder_or_pattern + ": " + std::to_string(missing_count) + (missing_count == 1 ? " frame" : " frames") +
         " missing from the numbering (every " + std::to_string(step) + "): " + list + " (the first gap between " + first_gap + "); " +
         std::to_string(files.size()) + " frames read, the gaps closed";
}

}  // namespace m4mesh
