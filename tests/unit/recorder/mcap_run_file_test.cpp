// The MCAP file of a run and its check (climbsim/recording/mcap_run_file.hpp, mcap_check.hpp):
// closed files, files cut short at any byte, corrupt files.

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "climbsim/recording/mcap_check.hpp"
#include "climbsim/recording/mcap_run_file.hpp"

namespace climbsim::recording {
namespace {
namespace fs = std::filesystem;

fs::path tempFile(const std::string& name) {
  return fs::path(testing::TempDir()) / ("climbsim_mcap_" + name + "_" + std::to_string(::getpid()) + ".mcap");
}

std::vector<char> bytesOf(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void writeBytes(const fs::path& path, const std::vector<char>& bytes, std::size_t n) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(n));
}

/// Three seconds of two channels at 100 Hz, a chunk per second, `close`d or not.
void writeRun(const fs::path& path, bool close) {
  McapRunFile file(path.string());
  const auto a = file.addCdrChannel("thermo/AdhesionForce", "climbsim::AdhesionForce");
  const auto b = file.addChannel("test/Text", "text", "", "", "");
  file.metadata("scenario", {{"file", "x.yaml"}, {"text", "duration_s: 3\n"}});
  for (int k = 0; k < 300; ++k) {
    const std::int64_t t_ns = k * 10'000'000LL;
    if (k > 0 && k % 100 == 0) file.closeChunk();
    const std::string payload = "sample " + std::to_string(k);
    file.write(a, t_ns, payload.data(), payload.size());
    if (k % 10 == 0) file.write(b, t_ns, payload.data(), payload.size());
  }
  if (close) file.close();
}

TEST(McapRunFile, AClosedFileHoldsEveryMessage) {
  const fs::path path = tempFile("closed");
  writeRun(path, true);
  const McapCheck check = checkMcap(path.string());
  EXPECT_TRUE(check.closed) << check.problem;
  EXPECT_EQ(check.problem, "");
  EXPECT_EQ(check.chunks, 3u);
  EXPECT_EQ(check.metadata, 1u);
  ASSERT_EQ(check.channels.size(), 2u);
  EXPECT_EQ(check.channels.at("thermo/AdhesionForce").messages, 300u);
  EXPECT_EQ(check.channels.at("thermo/AdhesionForce").schema, "climbsim::AdhesionForce");
  EXPECT_EQ(check.channels.at("thermo/AdhesionForce").encoding, "cdr");
  EXPECT_EQ(check.channels.at("test/Text").messages, 30u);
  EXPECT_EQ(check.lastLogTimeNs(), 2'990'000'000LL);
  EXPECT_EQ(check.good_bytes, check.file_bytes);
  fs::remove(path);
}

TEST(McapRunFile, AFileCutShortReadsUpToItsLastWholeChunk) {
  const fs::path path = tempFile("whole");
  writeRun(path, true);
  const std::vector<char> bytes = bytesOf(path);
  const McapCheck whole = checkMcap(path.string());
  const fs::path cut = tempFile("cut");
  // Every length: never a crash, never "closed", never more than the whole file's messages,
  // and the counts only grow with the length.
  std::uint64_t previous = 0;
  for (std::size_t n = 0; n < bytes.size(); n += 97) {
    writeBytes(cut, bytes, n);
    const McapCheck check = checkMcap(cut.string());
    EXPECT_FALSE(check.closed) << n;
    EXPECT_NE(check.problem, "") << n;
    EXPECT_LE(check.messages(), whole.messages()) << n;
    EXPECT_GE(check.messages(), previous) << n;
    EXPECT_LE(check.good_bytes, n) << n;
    previous = check.messages();
  }
  EXPECT_EQ(previous, whole.messages()) << "the summary section holds no messages";
  fs::remove(cut);
  fs::remove(path);
}

TEST(McapRunFile, AnUnclosedFileReadsUpToItsLastClosedChunk) {
  const fs::path path = tempFile("open");
  {
    // The writer's state when its process is killed: the chunks closed so far are in the file.
    McapRunFile file(path.string());
    const auto a = file.addCdrChannel("thermo/AdhesionForce", "climbsim::AdhesionForce");
    for (int k = 0; k < 250; ++k) {
      if (k > 0 && k % 100 == 0) file.closeChunk();
      file.write(a, k * 10'000'000LL, "x", 1);
    }
    const McapCheck check = checkMcap(path.string());
    EXPECT_FALSE(check.closed);
    EXPECT_EQ(check.channels.at("thermo/AdhesionForce").messages, 200u);
    EXPECT_EQ(check.chunks, 2u);
  }
  fs::remove(path);
}

TEST(McapRunFile, CorruptFilesAndOtherFilesSaySo) {
  const fs::path path = tempFile("corrupt");
  writeRun(path, true);
  std::vector<char> bytes = bytesOf(path);
  for (std::size_t i = 9; i < 17; ++i) bytes[i] = static_cast<char>(0xA5);  // the header record's length
  writeBytes(path, bytes, bytes.size());
  const McapCheck corrupt = checkMcap(path.string());
  EXPECT_NE(corrupt.problem, "");
  EXPECT_EQ(corrupt.messages(), 0u);

  writeBytes(path, std::vector<char>{'t', 'r', 'a', 'c', 'e', '\n'}, 6);
  EXPECT_NE(checkMcap(path.string()).problem.find("not an MCAP file"), std::string::npos);
  fs::remove(path);
  EXPECT_NE(checkMcap(path.string()).problem.find("cannot read"), std::string::npos);
}

TEST(McapRunFile, AnUnwritablePathIsAConfigError) {
  EXPECT_ANY_THROW(McapRunFile("/nonexistent-dir/run.mcap"));
}

}  // namespace
}  // namespace climbsim::recording
