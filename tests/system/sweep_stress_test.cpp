// A sweep of distributed runs with more jobs than cores loses no run to load: alone on the
// machine (SERIAL), as its 4 jobs on 2 cores are the load it is about.

#include <gtest/gtest.h>

#include <string>

#include "launcher_run.hpp"

namespace {

using namespace climbsim::system_test;

TEST(Sweep, DistributedVariantsFourAtATimeOnTwoCoresLoseNoRun) {
  // 20 distributed runs, 4 at a time (every service a process: about 30 processes on 2 cores),
  // each loading its scene while the others step: a loaded machine, and not one run lost.
  std::string values;
  for (int f = 1000; f < 2000; f += 50) values += (values.empty() ? "" : ",") + std::to_string(f);
  const auto r = runTool("climbsim-sweep", "sweep-stress",
                         "crack-descent --set duration_s=2 --set controller.downforce_n=" + values + " --distributed -j 4");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("20 of 20 variants finished (0 fell, 0 slid beyond their slide limit, 0 failed)"),
            std::string::npos) << r.output;
  const std::string csv = readFile(r.dir / "sweep.csv");
  EXPECT_EQ(lineCount(csv), 21u) << csv;
  EXPECT_EQ(csv.find(",failed,"), std::string::npos) << csv;
}

}  // namespace
