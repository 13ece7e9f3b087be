#include "sweep_spec.hpp"

#include <cstdio>
#include <set>

#include "climbsim/errors.hpp"

namespace climbsim::sweep {
namespace {

std::string where(const std::string& option) { return "--set " + option; }

/// Characters kept in a directory name; every other becomes '_'.
std::string safeName(const std::string& text) {
  std::string out;
  for (const char c : text) {
    const bool keep = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '.' ||
                      c == '-' || c == '=' || c == '_' || c == '+';
    out += keep ? c : '_';
  }
  return out.size() > 100 ? out.substr(0, 100) : out;
}

std::string trimmed(const std::string& s) {
  const auto first = s.find_first_not_of(" \t");
  if (first == std::string::npos) return {};
  return s.substr(first, s.find_last_not_of(" \t") - first + 1);
}

}  // namespace

SweepAxis parseAxis(const std::string& option) {
  const auto eq = option.find('=');
  if (eq == std::string::npos) throw ConfigError(where(option) + ": expected KEY=V1,V2,...");
  SweepAxis axis;
  axis.key = trimmed(option.substr(0, eq));
  if (axis.key.empty()) throw ConfigError(where(option) + ": the key is empty");
  const std::string list = option.substr(eq + 1);
  if (trimmed(list).empty()) {
    throw ConfigError(where(option) + ": no values for " + axis.key + " (the product of the sweep would be empty)");
  }
  std::string current;
  std::vector<char> open;  // brackets not closed yet
  char quote = 0;
  const auto push = [&](std::size_t at) {
    const std::string value = trimmed(current);
    if (value.empty()) {
      throw ConfigError(where(option) + ": value " + std::to_string(axis.values.size() + 1) + " of " + axis.key +
                        " is empty (at character " + std::to_string(eq + 1 + at) + ")");
    }
    axis.values.push_back(value);
    current.clear();
  };
  for (std::size_t i = 0; i < list.size(); ++i) {
    const char c = list[i];
    if (quote != 0) {
      if (c == quote) quote = 0;
    } else if (c == '"' || c == '\'') {
      quote = c;
    } else if (c == '[' || c == '{') {
      open.push_back(c == '[' ? ']' : '}');
    } else if (c == ']' || c == '}') {
      if (open.empty() || open.back() != c) {
        throw ConfigError(where(option) + ": unbalanced '" + std::string(1, c) + "' at character " +
                          std::to_string(eq + 2 + i));
      }
      open.pop_back();
    } else if (c == ',' && open.empty()) {
      push(i);
      continue;
    }
    current += c;
  }
  if (quote != 0) throw ConfigError(where(option) + ": a quote (" + std::string(1, quote) + ") is not closed");
  if (!open.empty()) throw ConfigError(where(option) + ": '" + std::string(1, open.back()) + "' missing");
  push(list.size());
  return axis;
}

std::vector<Variant> variantsOf(const std::vector<SweepAxis>& axes, std::size_t max_variants) {
  if (axes.empty()) throw ConfigError("--set KEY=V1,V2,...: give at least one key to sweep");
  std::set<std::string> keys;
  std::size_t count = 1;
  for (const auto& axis : axes) {
    if (!keys.insert(axis.key).second) throw ConfigError("--set " + axis.key + "=...: the key is swept twice");
    if (axis.values.empty()) throw ConfigError("--set " + axis.key + "=: no values (the product would be empty)");
    count *= axis.values.size();
    if (count > max_variants) {
      throw ConfigError("--set: the product of the values has more than " + std::to_string(max_variants) +
                        " variants");
    }
  }
  std::vector<Variant> out;
  for (std::size_t n = 0; n < count; ++n) {
    Variant v;
    v.index = n;
    std::size_t rest = n;
    std::vector<std::size_t> pick(axes.size());
    for (std::size_t a = axes.size(); a-- > 0;) {
      pick[a] = rest % axes[a].values.size();
      rest /= axes[a].values.size();
    }
    char prefix[24];
    std::snprintf(prefix, sizeof(prefix), "%03zu", n);
    v.name = prefix;
    for (std::size_t a = 0; a < axes.size(); ++a) {
      const std::string& value = axes[a].values[pick[a]];
      v.values.push_back(value);
      v.overrides.push_back(axes[a].key + "=" + value);
      v.name += (a == 0 ? "_" : "__") + safeName(axes[a].key + "=" + value);
    }
    out.push_back(std::move(v));
  }
  return out;
}

}  // namespace climbsim::sweep
