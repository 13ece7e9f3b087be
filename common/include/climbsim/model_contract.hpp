#pragma once
/// @file
/// The model contract (docs/design.md#the-model-contract) as a compile-time check. A model M
/// of a service is a pure class (no DDS, no clock) with
///  - the types M::Params (what it is built from), M::State (everything that evolves, held by
///    the caller), M::Inputs (one step's inputs) and M::Outputs (one step's outputs), and
///  - `Outputs step(State&, const Inputs&, std::int64_t t_ns, std::int64_t dt_ns) const`: one
///    step [t_ns, t_ns + dt_ns) [ns]; const, so that the model keeps nothing between steps.
/// Next to each model: `static_assert(climbsim::is_model_v<M>)`. A model whose step is not
/// const, returns another type or takes other arguments does not pass.

#include <cstdint>
#include <type_traits>
#include <utility>

namespace climbsim {

namespace model_contract_detail {
/// The type `m.step(state, inputs, t_ns, dt_ns)` has on a const M.
template <class M>
using StepResult = decltype(std::declval<const M&>().step(std::declval<typename M::State&>(),
                                                          std::declval<const typename M::Inputs&>(),
                                                          std::declval<std::int64_t>(), std::declval<std::int64_t>()));
}  // namespace model_contract_detail

/// true_type when M keeps the model contract (see the file comment), else false_type.
template <class M, class = void>
struct is_model : std::false_type {};

template <class M>
struct is_model<M, std::void_t<typename M::Params, typename M::State, typename M::Inputs, typename M::Outputs,
                               model_contract_detail::StepResult<M>>>
    : std::is_same<model_contract_detail::StepResult<M>, typename M::Outputs> {};

/// is_model<M>::value.
template <class M>
inline constexpr bool is_model_v = is_model<M>::value;

}  // namespace climbsim
