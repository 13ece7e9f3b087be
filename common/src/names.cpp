#include "climbsim/names.hpp"

#include <algorithm>
#include <cctype>

#include "climbsim/errors.hpp"

namespace climbsim {

void validateName(const std::string& what, const std::string& name) {
  if (name.empty()) {
    throw ConfigError(what + ": empty name");
  }
  if (name.size() > kMaxNameLength) {
    throw ConfigError(what + ": name '" + name + "' is longer than " +
                      std::to_string(kMaxNameLength) + " characters");
  }
  for (const char c : name) {
    const bool ok = std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.';
    if (!ok) {
      throw ConfigError(what + ": name '" + name + "' has the character '" + std::string(1, c) +
                        "'; use letters, digits, '_', '-' and '.'");
    }
  }
}

std::vector<std::string> parseNameList(const std::string& what, const std::string& list) {
  std::vector<std::string> names;
  if (list.empty()) {
    return names;
  }
  std::size_t begin = 0;
  while (true) {
    const std::size_t comma = list.find(',', begin);
    const std::string item = list.substr(begin, comma == std::string::npos ? std::string::npos : comma - begin);
    validateName(what, item);
    names.push_back(item);
    if (comma == std::string::npos) {
      break;
    }
    begin = comma + 1;
  }
  return names;
}

std::string joinNames(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) {
    if (!out.empty()) {
      out += ", ";
    }
    out += n;
  }
  return out;
}

std::set<std::string> parseChoiceList(const std::string& option, const std::string& list,
                                      const std::vector<std::string>& choices) {
  std::set<std::string> chosen;
  if (list == "none") return chosen;
  for (const auto& name : parseNameList(option, list)) {
    if (std::find(choices.begin(), choices.end(), name) == choices.end()) {
      throw ConfigError(option + " = '" + list + "': unknown input '" + name + "' (choose from " + joinNames(choices) +
                        ", or none)");
    }
    chosen.insert(name);
  }
  return chosen;
}

}  // namespace climbsim
