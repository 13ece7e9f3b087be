// What a sweep runs: the value lists of --set, their product, and bad input named in one line.

#include <gtest/gtest.h>

#include "climbsim/errors.hpp"
#include "sweep/sweep_results.hpp"
#include "sweep/sweep_spec.hpp"

namespace {

using namespace climbsim::sweep;

std::string errorOf(const std::string& option) {
  try {
    parseAxis(option);
  } catch (const climbsim::ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(SweepSpec, ValuesSplitAtTopLevelCommasOnly) {
  const auto a = parseAxis("controller.downforce_n=1800, 2000 ,2200");
  EXPECT_EQ(a.key, "controller.downforce_n");
  EXPECT_EQ(a.values, (std::vector<std::string>{"1800", "2000", "2200"}));
  const auto b = parseAxis("controller={type: none},{type: reference, downforce_n: 1500},'a,b'");
  EXPECT_EQ(b.values, (std::vector<std::string>{"{type: none}", "{type: reference, downforce_n: 1500}", "'a,b'"}));
  EXPECT_EQ(parseAxis("seed=7").values.size(), 1u) << "one value: a fixed override";
}

TEST(SweepSpec, AListThatDoesNotParseIsOneLineNamingIt) {
  EXPECT_NE(errorOf("seed").find("--set seed: expected KEY=V1,V2"), std::string::npos);
  EXPECT_NE(errorOf("=1,2").find("the key is empty"), std::string::npos);
  EXPECT_NE(errorOf("seed=").find("no values for seed"), std::string::npos) << "an empty product";
  EXPECT_NE(errorOf("seed=1,,3").find("value 2 of seed is empty"), std::string::npos);
  EXPECT_NE(errorOf("seed=1,2,").find("value 3 of seed is empty"), std::string::npos);
  EXPECT_NE(errorOf("controller={type: none").find("'}' missing"), std::string::npos);
  EXPECT_NE(errorOf("x=[1,2]],3").find("unbalanced ']'"), std::string::npos);
  EXPECT_NE(errorOf("x='a,b").find("not closed"), std::string::npos);
  for (const auto& bad : {"seed", "seed=", "seed=1,,3"}) {
    EXPECT_EQ(errorOf(bad).find('\n'), std::string::npos) << "one line: " << errorOf(bad);
  }
}

TEST(SweepSpec, TheProductVariesTheLastKeyFastestAndNamesEachVariant) {
  const auto variants = variantsOf({parseAxis("a=1,2"), parseAxis("b.c=x,y,z")});
  ASSERT_EQ(variants.size(), 6u);
  EXPECT_EQ(variants[0].overrides, (std::vector<std::string>{"a=1", "b.c=x"}));
  EXPECT_EQ(variants[1].overrides, (std::vector<std::string>{"a=1", "b.c=y"}));
  EXPECT_EQ(variants[5].overrides, (std::vector<std::string>{"a=2", "b.c=z"}));
  EXPECT_EQ(variants[4].name, "004_a=2__b.c=y");
  const auto odd = variantsOf({parseAxis("controller={type: none},{type: fixed}")});
  EXPECT_EQ(odd[0].name.find_first_of(" {}:/"), std::string::npos) << odd[0].name;
  EXPECT_NE(odd[0].name, odd[1].name);
}

TEST(SweepSpec, NoKeyOrAKeySweptTwiceIsRefused) {
  EXPECT_THROW(variantsOf({}), climbsim::ConfigError);
  EXPECT_THROW(variantsOf({parseAxis("a=1,2"), parseAxis("a=3")}), climbsim::ConfigError);
  EXPECT_THROW(variantsOf({parseAxis("a=1,2,3"), parseAxis("b=1,2,3")}, 8), climbsim::ConfigError);
}

TEST(SweepResults, SweepCsvHasARowPerVariantWithItsValuesAndFigures) {
  const auto axes = std::vector<SweepAxis>{parseAxis("k=1,{a: 1, b: 2}")};
  const auto variants = variantsOf(axes);
  VariantResult r;
  r.variant = variants[1];
  r.outcome = "fell";
  r.fell = true;
  r.min_downforce_n = 12.5;
  r.mean_downforce_n = 100.0;
  r.max_pf_shift_m = 0.25;
  r.max_slip_mps = 0.5;
  r.wall_s = 2.0;
  r.slid = true;
  r.slide_m = 0.125;
  r.slide_limit_m = 0.005;
  r.adhesion_failed = true;
  r.fell_at_s = 2.5;
  r.exit_code = 5;
  r.culprit = "drive";
  r.reason = "FELL at t = 2.5 s, \"off\"";
  const std::string csv = sweepCsv(axes, {r});
  EXPECT_EQ(csv,
            "variant,k,outcome,fell,min_downforce_n,mean_downforce_n,max_pf_shift_m,max_slip_mps,wall_s,dir,"
            "slid,slide_m,slide_limit_m,adhesion_failed,fell_at_s,seal_over_nothing_at_s,wheels_over_nothing_at_s,"
            "dropped_samples,exit_code,culprit,reason\n"
            "1,\"{a: 1, b: 2}\",fell,true,12.5,100,0.25,0.5,2," + variants[1].name +
            ",true,0.125,0.0050000000000000001,true,2.5,,,0,5,drive,\"FELL at t = 2.5 s, \"\"off\"\"\"\n");
}

}  // namespace
