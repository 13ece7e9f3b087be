// The step-data queue depth read from a QoS file, and the window it allows.

#include "qos_depth.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "climbsim/errors.hpp"

namespace climbsim::launcher {
namespace {

namespace fs = std::filesystem;

std::string qosFile(const std::string& name, int writer_depth, int reader_depth) {
  const fs::path path = fs::temp_directory_path() / ("climbsim-qos-depth-" + name + ".xml");
  std::ofstream(path) << "<dds><profiles>"
                      << "<data_writer profile_name=\"climbsim.step_data.writer\"><topic><historyQos><kind>KEEP_LAST"
                      << "</kind><depth>" << writer_depth << "</depth></historyQos></topic></data_writer>"
                      << "<data_reader profile_name=\"climbsim.step_data.reader\"><topic><historyQos><kind>KEEP_LAST"
                      << "</kind><depth>" << reader_depth << "</depth></historyQos></topic></data_reader>"
                      << "</profiles></dds>";
  return path.string();
}

TEST(QosDepth, TheShippedFileHoldsTheDefaultWindow) {
  const std::string shipped = std::string(CLIMBSIM_ROOT) + "/deploy/qos/climbsim.xml";
  EXPECT_EQ(stepDataQueueDepth(shipped), 34);
  EXPECT_NO_THROW(checkWindowFitsQueues(1, shipped));
  EXPECT_NO_THROW(checkWindowFitsQueues(16, shipped));
  EXPECT_NO_THROW(checkWindowFitsQueues(32, shipped));
  EXPECT_THROW(checkWindowFitsQueues(33, shipped), ConfigError);
}

TEST(QosDepth, TheShallowerOfWriterAndReaderCounts) {
  const auto file = qosFile("shallow-reader", 40, 10);
  EXPECT_EQ(stepDataQueueDepth(file), 10);
  EXPECT_NO_THROW(checkWindowFitsQueues(8, file));
  try {
    checkWindowFitsQueues(9, file);
    FAIL() << "a window of 9 does not fit queues of 10";
  } catch (const ConfigError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("= 9: above 8"), std::string::npos) << what;
    EXPECT_NE(what.find(file), std::string::npos) << what;
  }
}

TEST(QosDepth, ZeroWindowAndBrokenFilesAreOneLineErrors) {
  EXPECT_THROW(checkWindowFitsQueues(0, qosFile("zero", 34, 34)), ConfigError);
  EXPECT_THROW(stepDataQueueDepth("/nonexistent/qos.xml"), ConfigError);
  const fs::path empty = fs::temp_directory_path() / "climbsim-qos-depth-empty.xml";
  std::ofstream(empty) << "<dds><profiles/></dds>";
  EXPECT_THROW(stepDataQueueDepth(empty.string()), ConfigError);
}

}  // namespace
}  // namespace climbsim::launcher
