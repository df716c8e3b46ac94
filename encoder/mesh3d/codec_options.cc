#include "encoder/mesh3d/codec_options.h"

#include <cmath>
#include <cstdlib>

#include "common/error.h"

namespace m4mesh {

namespace {

std::string range_text(const CodecOption& o) {
  auto number = [](double v) {
    std::string s = std::to_string(v);
    s.erase(s.find_last_not_of('0') + 1);
    if (s.back() == '.') s.pop_back();
    return s;
  };
  return number(o.min) + " … " + number(o.max);
}

void check(const std::string& codec, const CodecOption& o, const std::string& value) {
  const std::string what = "--" + o.name + " " + value + " (" + codec + ")";
  if (o.kind == OptionKind::kFlag) {
    if (value != "0" && value != "1") throw usage_error(what + ": a flag takes no value");
    return;
  }
  if (o.kind == OptionKind::kText) return;
  char* end = nullptr;
  const double v = std::strtod(value.c_str(), &end);
  if (value.empty() || *end != '\0' || !std::isfinite(v)) throw usage_error(what + ": not a number");
  if (o.kind == OptionKind::kInteger && v != std::floor(v)) throw usage_error(what + ": not an integer");
  if (v < o.min || v > o.max) throw usage_error(what + ": outside " + range_text(o));
}

}  // namespace

CodecSettings::CodecSettings(const std::string& codec, const std::vector<CodecOption>& options, const CodecOptionValues& values,
                             const BaseMeshCoding& base_mesh, unsigned threads)
    : base_mesh_(base_mesh), threads_(threads) {
  for (const CodecOption& o : options) values_[o.name] = o.kind == OptionKind::kFlag ? "0" : o.default_value;
  for (const auto& [name, value] : values) {
    auto it = values_.find(name);
    if (it == values_.end()) {
      std::string known;
      for (const CodecOption& o : options) known += (known.empty() ? "--" : ", --") + o.name;
      throw usage_error("--" + name + " is not an option of " + codec + (known.empty() ? " (it has none)" : " (its options: " + known + ")"));
    }
    for (const CodecOption& o : options)
      if (o.name == name) check(codec, o, value);
    it->second = value;
  }
}

const std::string& CodecSettings::value(const std::string& name) const {
  auto it = values_.find(name);
  if (it == values_.end()) throw usage_error("the codec declares no option " + name);
  return it->second;
}

int CodecSettings::integer(const std::string& name) const { return static_cast<int>(std::strtod(value(name).c_str(), nullptr)); }
double CodecSettings::number(const std::string& name) const { return std::strtod(value(name).c_str(), nullptr); }
bool CodecSettings::flag(const std::string& name) const { return value(name) == "1"; }
const std::string& CodecSettings::text(const std::string& name) const { return value(name); }

CodecOption bits_option(const std::string& help) { return {"bits", help, OptionKind::kInteger, "12", 4, 24}; }

CodecOption intra_period_option() {
  return {"intra-period", "re-send the base mesh every N frames (0: only frame 0)", OptionKind::kInteger, "0", 0, 1e9};
}

}  // namespace m4mesh
