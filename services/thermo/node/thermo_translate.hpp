#pragma once
/// @file
/// Translators between the thermo topics (idl/thermo.idl, idl/sealing.idl) and the model's
/// inputs and outputs. Pure functions: no DDS entity, tested without a network. The stamp
/// fields (source, step, t_ns) are left to StampedOutput::write.

#include <string>
#include <vector>

#include "climbsim/topic_names.hpp"
#include "sealing.h"
#include "thermo.h"
#include "thermo_types.hpp"

namespace climbsim::thermo {

/// Topic names: the one list of common/include/climbsim/topic_names.hpp (topic::kLeakage, ...).
namespace topic = climbsim::topic;

/// Valve openings per chamber 1..N (0..1) as sent, any count; size and range checks are the
/// model's (validateInputs).
std::vector<double> valveCommandFromIdl(const climbsim::ValveCommand& sample);
/// At most kMaxChambers openings fit the topic (more: std::invalid_argument).
climbsim::ValveCommand valveCommandToIdl(const std::vector<double>& opening);

/// Engine commands in engine order; at most kMaxEngines fit the topic (more: std::invalid_argument).
std::vector<EngineCommand> engineCommandsFromIdl(const climbsim::EngineCommand& sample);
climbsim::EngineCommand engineCommandToIdl(const std::vector<EngineCommand>& engines);

/// A Leakage part covering the segments `indices` of `names` with the areas [m^2] and mean
/// gaps [m] at those indices (all vectors in geometry order).
climbsim::Leakage leakageToIdl(const std::vector<std::string>& names, const std::vector<double>& leak_area_m2,
                               const std::vector<double>& mean_gap_m, const std::vector<std::size_t>& indices);

/// Pressures [Pa] (chambers, then the reservoir if any), valve openings (none without a
/// reservoir), engine speeds and segment mass flows [kg/s] of `outputs`.
/// std::invalid_argument if more pressures, valves, engines or segments than the topic holds.
climbsim::ChamberState chamberStateToIdl(const ThermoOutputs& outputs);
/// Downforce F [N] and its point of action P_F (robot frame) [m].
climbsim::AdhesionForce adhesionForceToIdl(const ThermoOutputs& outputs);

/// The fields of ThermoOutputs that ChamberState and AdhesionForce carry (the rest stay
/// default): for consumers and round-trip tests.
ThermoOutputs outputsFromIdl(const climbsim::ChamberState& state, const climbsim::AdhesionForce& force);

}  // namespace climbsim::thermo
