#include "domain_choice.hpp"

#include <gtest/gtest.h>

#include <stdlib.h>

#include <filesystem>
#include <optional>
#include <set>
#include <stdexcept>
#include <vector>

namespace climbsim::launcher {
namespace {

class DomainChoiceTest : public ::testing::Test {
 protected:
  void SetUp() override {
    char pattern[] = "/tmp/climbsim-domain-test-XXXXXX";
    ASSERT_NE(::mkdtemp(pattern), nullptr);
    dir_ = pattern;
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string dir_;
};

TEST_F(DomainChoiceTest, ConcurrentRunsGetDifferentIdsBelowTheTestRange) {
  std::set<int> ids;
  std::vector<DomainLease> leases;
  for (int i = 0; i < 5; ++i) {
    leases.push_back(leaseRunDomain(std::nullopt, dir_));
    EXPECT_GE(leases.back().id(), kAutoDomainFirst);
    EXPECT_LE(leases.back().id(), kAutoDomainLast);
    ids.insert(leases.back().id());
  }
  EXPECT_EQ(ids.size(), 5u);
  EXPECT_LT(kAutoDomainLast, 100);  // the tests lease ids from 100 on
}

TEST_F(DomainChoiceTest, AFixedIdIsHeldOnce) {
  std::optional<DomainLease> lease = leaseRunDomain(42, dir_);
  EXPECT_EQ(lease->id(), 42);
  try {
    leaseRunDomain(42, dir_);
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("DDS domain 42 is used"), std::string::npos) << e.what();
  }
  EXPECT_NE(leaseRunDomain(std::nullopt, dir_).id(), 42);
  lease.reset();
  EXPECT_EQ(leaseRunDomain(42, dir_).id(), 42);
}

}  // namespace
}  // namespace climbsim::launcher
