// trace.csv's numbers as text: std::to_chars must write exactly what printf("%.17g") and
// printf("%.9f") write, for every kind of double (the traces of earlier runs stay comparable
// byte for byte).

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <random>
#include <string>

#include "node/trace_numbers.hpp"

namespace climbsim::recorder {
namespace {

std::string printfText(const char* format, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, format, value);
  return buffer;
}

std::string g17(double value) {
  std::string line;
  appendG17(line, value);
  return line;
}

TEST(TraceNumbers, EveryDoubleIsWrittenAsPrintfsG17) {
  const double specials[] = {0.0,
                             -0.0,
                             std::nan(""),
                             -std::nan(""),
                             std::numeric_limits<double>::infinity(),
                             -std::numeric_limits<double>::infinity(),
                             std::numeric_limits<double>::denorm_min(),
                             std::numeric_limits<double>::min(),
                             std::numeric_limits<double>::max(),
                             -std::numeric_limits<double>::max(),
                             0.1,
                             1e-5,
                             1e-4,
                             1e16,
                             1e17,
                             123456789012345678.0,
                             2271.0000000000005,
                             -101325.0};
  for (double v : specials) EXPECT_EQ(g17(v), printfText("%.17g", v)) << "value bits of " << v;
  std::mt19937_64 random(20261207);
  int differing = 0;
  for (int i = 0; i < 200000; ++i) {
    const std::uint64_t bits = random();
    double any;  // every bit pattern: subnormals, NaN payloads, all exponents
    std::memcpy(&any, &bits, sizeof any);
    // values of a trace's magnitudes: pressures, forces, metres, leak areas
    const double typical = std::ldexp(static_cast<double>(random() >> 11), -53) *
                           std::pow(10.0, static_cast<int>(random() % 24) - 12) * ((random() & 1) ? -1.0 : 1.0);
    for (double v : {any, typical}) {
      if (g17(v) != printfText("%.17g", v) && ++differing <= 5) {
        ADD_FAILURE() << g17(v) << " against printf's " << printfText("%.17g", v);
      }
    }
  }
  EXPECT_EQ(differing, 0);
}

TEST(TraceNumbers, TimesAreWrittenAsPrintfsFixedNine) {
  std::mt19937_64 random(7);
  for (int i = 0; i < 100000; ++i) {
    const double t_s = static_cast<double>(random() % 100000000000000ULL) * 1e-9;  // up to 27 h in ns
    std::string line;
    appendFixed9(line, t_s);
    ASSERT_EQ(line, printfText("%.9f", t_s));
  }
  std::string zero;
  appendFixed9(zero, 0.0);
  EXPECT_EQ(zero, "0.000000000");
}

}  // namespace
}  // namespace climbsim::recorder
