// A policy that writes the syntax table of a description, in the style of
// the specification's §3: one row per element, in the order the
// description reads them, with its descriptor and allowed range. The docs
// hold these tables, and tests/docs_test.cc checks them against the code;
// tests/requirements_test.cc takes the ranges from here.
#pragma once

#include <cstdio>
#include <span>
#include <string>
#include <vector>

#include "syntax/io.h"
#include "syntax/vlc.h"

namespace m4mesh::syntax {

class TableIO : public IOBase {
 public:
  static constexpr bool kReading = false;
  static constexpr bool kTable = true;

  // A field with its allowed range, as the table prints it.
  struct Range {
    std::string name;
    int bits;
    uint32_t lo, hi;
  };

  template <class T>
  void field(const char* name, int bits, T&) {
    row(name, "u(" + std::to_string(bits) + ")", "");
  }
  template <class T>
  void field_in(const char* name, int bits, T&, uint32_t lo, uint32_t hi) {
    ranges_.push_back({name, bits, lo, hi});
    row(name, "u(" + std::to_string(bits) + ")", std::to_string(lo) + " … " + std::to_string(hi));
  }
  template <class T>
  void vlc(const char* name, const VlcTable&, T&) {
    row(name, "vlc", "");
  }
  // A repeated structure is printed once, where its count is read.
  template <class T>
  void resize(std::vector<T>&, uint32_t, const char*, int = 1) {}
  // A length the syntax fixes (the description's own structure holds zero
  // for lengths read from fields) is printed.
  void section(const char* name, uint64_t length, std::span<const uint8_t>&) {
    row(name, length ? "b(" + std::to_string(length) + ")" : "bytes", "");
  }
  void tail_section(const char* name, std::span<const uint8_t>&) { row(name, "bytes", "to the end of the unit"); }
  // Constraints between fields are the prose's, not the table's.
  void require(bool, ErrorKind, const char*, const char*) const {}
  void require_remaining_bytes(const char*, uint64_t, const char* = nullptr) const {}
  void require_length(const char*, uint64_t) const {}

  // A conditional or repeated part: "head {", its rows indented, "}".
  void open(const std::string& head) {
    rows_ += std::string(indent_, ' ') + "    " + head + " {\n";
    indent_ += 4;
  }
  void close() {
    indent_ -= 4;
    rows_ += std::string(indent_, ' ') + "    }\n";
  }

  // "title() {", the rows, "}".
  std::string table(const std::string& title) const { return title + "() {\n" + rows_ + "}\n"; }
  const std::vector<Range>& ranges() const { return ranges_; }

 private:
  void row(const char* name, const std::string& descriptor, const std::string& range) {
    char line[160];
    // Nested rows keep the descriptor column: the name's column narrows.
    std::snprintf(line, sizeof line, "    %*s%-*s %-8s %s", static_cast<int>(indent_), "", static_cast<int>(28 - indent_), name,
                  descriptor.c_str(), range.c_str());
    std::string text(line);
    text.erase(text.find_last_not_of(' ') + 1);
    rows_ += text + "\n";
  }
  std::string rows_;
  std::vector<Range> ranges_;
  size_t indent_ = 0;
};

}  // namespace m4mesh::syntax
