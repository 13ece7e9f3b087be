// The model contract as a compile-time check (climbsim/model_contract.hpp): a type with the
// contract's four types and a const step passes; each way of breaking it does not. The six
// models assert it next to their classes; this file proves the check can say no.

#include <gtest/gtest.h>

#include <cstdint>

#include "climbsim/model_contract.hpp"

namespace climbsim {
namespace {

struct P {};
struct S {};
struct I {};
struct O {};

struct Good {
  using Params = P;
  using State = S;
  using Inputs = I;
  using Outputs = O;
  Outputs step(State&, const Inputs&, std::int64_t, std::int64_t) const { return {}; }
};

/// step changes the model: not const.
struct NonConstStep {
  using Params = P;
  using State = S;
  using Inputs = I;
  using Outputs = O;
  Outputs step(State&, const Inputs&, std::int64_t, std::int64_t) { return {}; }
};

/// No State: everything that evolves would live in the model.
struct NoState {
  using Params = P;
  using Inputs = I;
  using Outputs = O;
  Outputs step(const Inputs&, std::int64_t, std::int64_t) const { return {}; }
};

/// step returns something else than Outputs.
struct OtherResult {
  using Params = P;
  using State = S;
  using Inputs = I;
  using Outputs = O;
  int step(State&, const Inputs&, std::int64_t, std::int64_t) const { return 0; }
};

/// step without the step's length.
struct NoDt {
  using Params = P;
  using State = S;
  using Inputs = I;
  using Outputs = O;
  Outputs step(State&, const Inputs&, std::int64_t) const { return {}; }
};

/// No Params type.
struct NoParams {
  using State = S;
  using Inputs = I;
  using Outputs = O;
  Outputs step(State&, const Inputs&, std::int64_t, std::int64_t) const { return {}; }
};

static_assert(is_model_v<Good>);
static_assert(!is_model_v<NonConstStep>);
static_assert(!is_model_v<NoState>);
static_assert(!is_model_v<OtherResult>);
static_assert(!is_model_v<NoDt>);
static_assert(!is_model_v<NoParams>);
static_assert(!is_model_v<int>);

TEST(ModelContract, TheTraitSaysYesOnlyToTheContract) {
  EXPECT_TRUE(is_model<Good>::value);
  EXPECT_FALSE(is_model<NonConstStep>::value);
  EXPECT_FALSE(is_model<NoState>::value);
  EXPECT_FALSE(is_model<OtherResult>::value);
  EXPECT_FALSE(is_model<NoDt>::value);
  EXPECT_FALSE(is_model<NoParams>::value);
}

}  // namespace
}  // namespace climbsim
