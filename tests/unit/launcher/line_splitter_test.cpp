#include "line_splitter.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace climbsim::launcher {
namespace {

struct Collect {
  std::vector<std::string> lines;
  LineSplitter::Emit emit() {
    return [this](std::string_view line) { lines.emplace_back(line); };
  }
};

TEST(LineSplitter, JoinsChunksIntoLines) {
  LineSplitter splitter;
  Collect got;
  splitter.feed("one\ntw", got.emit());
  splitter.feed("o\r\nthr", got.emit());
  splitter.feed("ee\n\n", got.emit());
  EXPECT_EQ(got.lines, (std::vector<std::string>{"one", "two", "three", ""}));
  splitter.finish(got.emit());
  EXPECT_EQ(got.lines.size(), 4u);
}

TEST(LineSplitter, FinishEmitsAnUnterminatedTail) {
  LineSplitter splitter;
  Collect got;
  splitter.feed("tail without newline", got.emit());
  EXPECT_TRUE(got.lines.empty());
  splitter.finish(got.emit());
  EXPECT_EQ(got.lines, (std::vector<std::string>{"tail without newline"}));
}

TEST(LineSplitter, CutsOverlongLines) {
  LineSplitter splitter(4);
  Collect got;
  splitter.feed("abcdefghij", got.emit());
  EXPECT_EQ(got.lines, (std::vector<std::string>{"abcd", "efgh"}));
  splitter.feed("\n", got.emit());
  EXPECT_EQ(got.lines.back(), "ij");
}

}  // namespace
}  // namespace climbsim::launcher
