// The figure-9 comparison plot (plot/figure9_plot.hpp) on a synthetic trace.

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>

#include "plot/figure9_plot.hpp"

namespace climbsim::plot {
namespace {

/// A robot yawed -90 degrees (R's x down the wall) driving down from y = 1.2 to 0.2 at 5 cm/s.
TraceTable descent() {
  std::ostringstream csv;
  csv << "t_s,downforce_n,pf_x_m,pf_y_m,y_m,yaw_rad\n";
  for (int k = 0; k <= 200; ++k) {
    const double t = 0.1 * k;
    csv << t << ',' << 2200.0 - 400.0 * std::exp(-std::pow(t - 10.0, 2)) << ",0.03,0.04," << 1.2 - 0.05 * t << ','
        << -1.5707963267948966 << '\n';
  }
  return TraceTable::parse(csv.str(), "synthetic.csv");
}

TEST(Figure9Plot, TheCrackOffsetIsWhereTheHorizontalCrackCrossesTheRobotsXAxis) {
  const auto trace = descent();
  const auto x = crackOffsetAlongX(trace, 0.70);
  // At y = 1.2 the crack is 0.5 m below the centre: ahead along R's x (which points down).
  EXPECT_NEAR(x.front(), 0.5, 1e-9);
  EXPECT_NEAR(x[100], 0.0, 1e-9);    // t = 10 s, y = 0.70: under the centre
  EXPECT_NEAR(x.back(), -0.5, 1e-9);  // passed: 0.5 m behind
  // A robot whose x axis runs along the crack has no such offset.
  std::ostringstream csv;
  csv << "t_s,y_m,yaw_rad\n0,1.2,0\n";
  EXPECT_TRUE(std::isnan(crackOffsetAlongX(TraceTable::parse(csv.str(), "along.csv"), 0.70)[0]));
}

TEST(Figure9Plot, DrawsTwoChartsSideBySide) {
  const cv::Mat img = figure9Plot(descent(), 0.70, 2.0);
  ASSERT_FALSE(img.empty());
  EXPECT_EQ(img.type(), CV_8UC3);
  EXPECT_EQ(img.cols, 2 * 900);
}

}  // namespace
}  // namespace climbsim::plot
