#pragma once
/// @file
/// Leak areas per sealing segment from the Leakage parts of one step (idl/sealing.idl; one
/// part per sealing shard), shared by thermo (its input) and the recorder (trace columns).

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "sealing.h"

namespace climbsim {

/// Merges the Leakage parts of one step (one sample per producer, e.g. several sealing
/// shards) into leak areas per segment, by segment name.
///  - A segment covered by no part keeps its last valid area (initially `initial_leak_area_m2`).
///  - A part is dropped as a whole (spdlog::warn with the reason, counted, its segments keep
///    their last valid areas) if it names an unknown segment, names a segment twice, carries a
///    non-finite or negative leak area or a non-finite mean gap, or names a segment that an
///    earlier part of the same step (in the order given) already covered.
class LeakageMerger {
 public:
  /// `segment_names` and `initial_leak_area_m2` [m^2] in model order (geometry order).
  LeakageMerger(std::vector<std::string> segment_names, std::vector<double> initial_leak_area_m2);

  /// Applies the parts of one step; returns the leak areas now in force [m^2], model order.
  const std::vector<double>& merge(const std::vector<climbsim::Leakage>& parts);

  /// "" if `part` alone is acceptable, else a one-line reason naming segment and value.
  std::string check(const climbsim::Leakage& part) const;

  const std::vector<double>& leakAreas() const { return leak_area_m2_; }
  /// Parts dropped so far.
  std::uint64_t dropped() const { return dropped_; }

 private:
  /// The index of segment `name` in model order, or names_.size() if it is none of the robot's.
  std::size_t indexOf(std::string_view name) const;
  /// check() that also gives each segment's index in `indices` when it passes (`seen`: scratch).
  std::string checkIndexed(const climbsim::Leakage& part, std::vector<std::size_t>& indices,
                           std::vector<char>& seen) const;

  std::vector<std::string> names_;
  std::map<std::string, std::size_t, std::less<>> index_;
  std::vector<double> leak_area_m2_;
  /// Scratch of merge (every step in thermo and the recorder: no allocation once sized).
  std::vector<char> seen_;
  std::vector<char> covered_;
  std::vector<std::size_t> indices_;
  std::uint64_t dropped_ = 0;
};

}  // namespace climbsim
