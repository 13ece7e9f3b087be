#pragma once
/// @file
/// Which sealing pictures the recorder writes (no DDS). The scenario asks for pictures at times
/// pictures.sealing_at_s; the sealing service publishes, for each of them, the pictures of its
/// first due step at or after that time (reliably, in time order). A picture of step time t_ns
/// is therefore the one of every requested time t with round(t * 1e9) <= t_ns that has none of
/// its kind yet: the files pictures/sealing_<kind>_<t>s.png (plot/picture_names.hpp).

#include <cstdint>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace climbsim::recorder {

/// round(t_s * 1e9) as the clock counts [ns].
std::int64_t secondsToNs(double t_s);

class SealingPictureFiles {
 public:
  /// `at_s`: the requested times [s] (any order, duplicates ignored); `kinds`: the picture kinds
  /// expected at each ("edges", "gaps").
  explicit SealingPictureFiles(std::vector<double> at_s, std::vector<std::string> kinds = {"edges", "gaps"});

  /// The file names the picture of `kind` at step time t_ns is written as (possibly none:
  /// nothing requested, or already written). A kind not given to the constructor gives none
  /// (so no file name is made of what the topic carries).
  std::vector<std::string> filesFor(const std::string& kind, std::int64_t t_ns);

  /// Number of (time, kind) pictures still missing among the requested times <= up_to_ns.
  std::size_t missingUpTo(std::int64_t up_to_ns) const;
  /// Number of (time, kind) pictures written so far.
  std::size_t written() const { return done_.size(); }
  const std::vector<double>& times() const { return at_s_; }

 private:
  std::vector<double> at_s_;  ///< sorted, unique
  std::vector<std::string> kinds_;
  std::set<std::pair<std::size_t, std::string>> done_;  ///< (index into at_s_, kind)
};

}  // namespace climbsim::recorder
