// A 3D codec's own encoder options: declared by the codec (name, help,
// default, range), given as text by the user (`encode3d --NAME VALUE`).
// Integers, numbers and flags are checked and typed here; a text option
// (cpca-wpt's "auto or a number") is handed to its codec, which checks it.
// The command line is built from the declarations of every registered
// codec (encoder/mesh3d/codec_encoders.h).
#pragma once

#include <map>
#include <span>
#include <string>
#include <vector>

#include "codecs3d/codec_encoder.h"

namespace m4mesh {

enum class OptionKind { kInteger, kNumber, kFlag, kText };

struct CodecOption {
  std::string name;  // the flag without "--"
  std::string help;
  OptionKind kind = OptionKind::kInteger;
  std::string default_value;  // "" for a flag (off)
  double min = 0, max = 0;    // inclusive, for integers and numbers
};

// Option name → value as text ("1" for a flag that is set).
using CodecOptionValues = std::map<std::string, std::string>;

// The values of one codec's options: every given value checked against
// its declaration (a usage error names the option), defaults for the rest.
class CodecSettings {
 public:
  // base_mesh: how its base meshes are coded; threads: how many an
  // encoder's own search may run at once (0: every core).
  CodecSettings(const std::string& codec, const std::vector<CodecOption>& options, const CodecOptionValues& values,
                const BaseMeshCoding& base_mesh, unsigned threads = 0);

  int integer(const std::string& name) const;
  double number(const std::string& name) const;
  bool flag(const std::string& name) const;
  const std::string& text(const std::string& name) const;
  const BaseMeshCoding& base_mesh() const { return base_mesh_; }
  unsigned threads() const { return threads_; }
  // The frames' vertices in the base mesh's coding order, when the
  // container encoder has planned it (else empty).
  std::span<const uint32_t> coding_order() const { return coding_order_; }
  void set_coding_order(std::span<const uint32_t> order) { coding_order_ = order; }

 private:
  const std::string& value(const std::string& name) const;
  std::map<std::string, std::string> values_;
  BaseMeshCoding base_mesh_;
  unsigned threads_;
  std::span<const uint32_t> coding_order_;
};

// The options every frame-by-frame grid codec declares.
CodecOption bits_option(const std::string& help);
CodecOption intra_period_option();

}  // namespace m4mesh
