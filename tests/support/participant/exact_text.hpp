#pragma once
/// @file
/// Test feeders record doubles as C99 hex floats ("%a"): exact text, so records compare bit
/// for bit.

#include <cstdio>
#include <string>

namespace climbsim::records {

inline std::string hexText(double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), "%a", value);
  return buffer;
}

}  // namespace climbsim::records
