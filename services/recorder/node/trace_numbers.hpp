#pragma once
/// @file
/// The numbers of trace.csv as text: the characters printf's "%.17g" and "%.9f" give (C locale),
/// by std::to_chars, which the standard defines as that printf and which takes a sixth of its
/// time (a row holds some forty numbers, written every step).

#include <charconv>
#include <string>

namespace climbsim::recorder {

/// Appends `value` as printf("%.17g") writes it: 17 significant digits, enough to read the same
/// double back; "nan", "-nan", "inf", "-inf" for the non-finite.
inline void appendG17(std::string& line, double value) {
  char buffer[32];
  const auto end = std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::general, 17).ptr;
  line.append(buffer, end);
}

/// Appends `value` as printf("%.9f") writes it: nine decimals (the trace's t_s, whole
/// nanoseconds); `value` below 1e15 in magnitude.
inline void appendFixed9(std::string& line, double value) {
  char buffer[48];
  const auto end = std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::fixed, 9).ptr;
  line.append(buffer, end);
}

}  // namespace climbsim::recorder
