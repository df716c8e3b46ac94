// The command line's progress line: what it counts, and that what follows
// it starts on a clean line.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <string>

#include "cli/console.h"

namespace m4mesh {
namespace {

std::string text_of(std::FILE* file) {
  std::rewind(file);
  std::string text;
  for (int c; (c = std::fgetc(file)) != EOF;) text += static_cast<char>(c);
  return text;
}

TEST(Progress, CountsTheJobsOwnStepsAndClearsItsLineBeforeWhatFollows) {
  std::FILE* out = std::tmpfile();
  ASSERT_NE(out, nullptr);
  {
    // Frames announced, then the codec's own count of units.
    console::Progress progress("encoding", 204, out, true, std::chrono::milliseconds(0));
    progress.update(410, 1204);
    progress.finish();
    std::fputs("summary\n", out);
  }
  const std::string text = text_of(out);
  EXPECT_NE(text.find("encoding 410/1204"), std::string::npos) << text;
  EXPECT_EQ(text.find("/204"), std::string::npos) << text;
  // The summary follows a carriage return that ends a line of blanks.
  const size_t summary = text.find("summary");
  ASSERT_NE(summary, std::string::npos);
  EXPECT_EQ(text[summary - 1], '\r') << text;
  EXPECT_EQ(text[summary - 2], ' ') << text;
  std::fclose(out);
}

TEST(Progress, NothingBeforeItsTime) {
  std::FILE* out = std::tmpfile();
  ASSERT_NE(out, nullptr);
  {
    console::Progress off_terminal("decoding frame", 10, out, false, std::chrono::milliseconds(0), std::chrono::hours(1));
    off_terminal.update(5);
    console::Progress early("decoding frame", 10, out, true, std::chrono::hours(1));
    early.update(5);
  }
  EXPECT_EQ(text_of(out), "");
  std::fclose(out);
}

// A log (no terminal) gets lines of their own, never carriage returns.
TEST(Progress, OffATerminalOnlyWithVerbose) {
  std::FILE* out = std::tmpfile();
  ASSERT_NE(out, nullptr);
  {
    console::Progress log("tracking frame", 795, out, false, std::chrono::milliseconds(0), std::chrono::milliseconds(0));
    log.update(100);
  }
  EXPECT_EQ(text_of(out), "");  // a file or a pipe: nothing at the normal level
  console::set_level(console::Level::kVerbose);
  {
    console::Progress log("tracking frame", 795, out, false, std::chrono::milliseconds(0), std::chrono::milliseconds(0));
    log.update(100);
    log.update(200);
  }
  console::set_level(console::Level::kNormal);
  EXPECT_EQ(text_of(out), "tracking frame 100/795\ntracking frame 200/795\n");
  std::fclose(out);
}

}  // namespace
}  // namespace m4mesh
