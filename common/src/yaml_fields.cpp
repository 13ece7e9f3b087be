#include "climbsim/yaml_fields.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>

#include "climbsim/errors.hpp"

namespace climbsim {

namespace {
constexpr std::size_t kMaxShownValue = 60;

std::string oneLine(const std::string& text) {
  std::string out;
  for (const char c : text) {
    if (c == '\n') {
      out += "\\n";
    } else if (c == '\r' || c == '\t') {
      out += ' ';
    } else {
      out += c;
    }
  }
  if (out.size() > kMaxShownValue) {
    out = out.substr(0, kMaxShownValue - 3) + "...";
  }
  return out;
}

std::string shortNumber(double v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) {
    out += out.empty() ? "" : ", ";
    out += n;
  }
  return out;
}
}  // namespace

YAML::Node YamlFields::load(const std::string& yaml_text, const std::string& source) {
  try {
    return YAML::Load(yaml_text);
  } catch (const YAML::Exception& e) {
    const std::string line = e.mark.is_null() ? "" : ":" + std::to_string(e.mark.line + 1);
    throw ConfigErrorAt(source + line + ": YAML syntax error: " + e.msg, e.mark.is_null() ? 0 : e.mark.line + 1);
  }
}

YAML::Node YamlFields::loadFile(const std::string& path, const std::string& what) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ConfigError(path + ": cannot read the " + what);
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw ConfigError(path + ": cannot read the " + what);
  return load(text.str(), path);
}

int YamlFields::lineOf(const YAML::Node& node) {
  if (!node.IsDefined()) {
    return 0;
  }
  const YAML::Mark mark = node.Mark();
  return mark.is_null() ? 0 : mark.line + 1;
}

std::string YamlFields::show(const YAML::Node& node) {
  if (!node.IsDefined() || node.IsNull()) {
    return "null";
  }
  if (node.IsScalar()) {
    return node.Scalar().empty() ? "''" : oneLine(node.Scalar());
  }
  YAML::Emitter emitter;
  emitter << YAML::Flow << node;
  return oneLine(emitter.good() ? emitter.c_str() : "?");
}

std::string YamlFields::where(const YAML::Node& node) const {
  const int line = lineOf(node);
  return line > 0 ? source_ + ":" + std::to_string(line) : source_;
}

std::string YamlFields::shortText(const std::string& text) { return oneLine(text); }

void YamlFields::fail(const YAML::Node& node, const std::string& key, const std::string& message) const {
  throw ConfigErrorAt(where(node) + ": " + oneLine(key) + " = " + show(node) + ": " + message, lineOf(node));
}

void YamlFields::failKey(const YAML::Node& node, const std::string& key, const std::string& message) const {
  throw ConfigErrorAt(where(node) + ": " + oneLine(key) + ": " + message, lineOf(node));
}

void YamlFields::failValue(int line, const std::string& key, const std::string& value,
                           const std::string& message) const {
  const std::string where = line > 0 ? source_ + ":" + std::to_string(line) : source_;
  throw ConfigErrorAt(where + ": " + oneLine(key) + " = " + oneLine(value) + ": " + message, line);
}

YAML::Node YamlFields::required(const YAML::Node& map, const std::string& key, const std::string& name) const {
  const YAML::Node child = map[name];  // const operator[]: never inserts
  if (!child.IsDefined()) failKey(map, key.empty() ? name : key + "." + name, "missing");
  return child;
}

void YamlFields::requireMapAnyKeys(const YAML::Node& node, const std::string& key) const {
  if (!node.IsMap()) {
    fail(node, key, "it must be a mapping (key: value, ...)");
  }
  std::set<std::string> seen;
  for (const auto& item : node) {
    if (!item.first.IsScalar()) {
      fail(item.first, key, "keys must be plain names");
    }
    if (!seen.insert(item.first.Scalar()).second) {
      check([&] { failKey(item.first, key.empty() ? item.first.Scalar() : key + "." + item.first.Scalar(), "duplicate key"); });
    }
  }
}

bool YamlFields::requireMap(const YAML::Node& node, const std::string& key,
                            std::initializer_list<const char*> allowed) const {
  return requireMap(node, key, std::vector<std::string>(allowed.begin(), allowed.end()));
}

bool YamlFields::requireMap(const YAML::Node& node, const std::string& key,
                            const std::vector<std::string>& allowed) const {
  requireMapAnyKeys(node, key);
  bool all_known = true;
  for (const auto& item : node) {
    const std::string& name = item.first.Scalar();
    if (std::find(allowed.begin(), allowed.end(), name) == allowed.end()) {
      all_known = false;
      check([&] {
        failKey(item.first, key.empty() ? name : key + "." + name, "unknown key (known keys: " + joined(allowed) + ")");
      });
    }
  }
  return all_known;
}

long long YamlFields::integer(const YAML::Node& node, const std::string& key, long long min, long long max) const {
  const std::string range = max == std::numeric_limits<long long>::max() ||
                                    max == std::numeric_limits<std::uint32_t>::max()
                                ? "an integer >= " + std::to_string(min)
                                : "an integer in " + std::to_string(min) + ".." + std::to_string(max);
  if (!node.IsScalar()) {
    fail(node, key, "it must be " + range);
  }
  const std::string& text = node.Scalar();
  long long value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || text.empty()) {
    fail(node, key, "it must be " + range);
  }
  if (value < min || value > max) {
    fail(node, key, "it must be " + range);
  }
  return value;
}

double YamlFields::number(const YAML::Node& node, const std::string& key, const std::string& expected) const {
  double value = 0.0;
  if (!node.IsScalar()) {
    fail(node, key, "it must be " + expected);
  }
  try {
    value = node.as<double>();
  } catch (const YAML::Exception&) {
    fail(node, key, "it must be " + expected);
  }
  if (!std::isfinite(value)) {
    fail(node, key, "it must be " + expected);
  }
  return value;
}

double YamlFields::number(const YAML::Node& node, const std::string& key) const {
  return number(node, key, "a finite number");
}

double YamlFields::numberIn(const YAML::Node& node, const std::string& key, double min, double max) const {
  const std::string expected = "a number in [" + shortNumber(min) + ", " + shortNumber(max) + "]";
  const double value = number(node, key, expected);
  if (value < min || value > max) {
    fail(node, key, "it must be " + expected);
  }
  return value;
}

double YamlFields::positive(const YAML::Node& node, const std::string& key, bool allow_zero) const {
  const std::string expected = allow_zero ? "a finite number >= 0" : "a finite number > 0";
  const double value = number(node, key, expected);
  if (value < 0.0 || (value == 0.0 && !allow_zero)) {
    fail(node, key, "it must be " + expected);
  }
  return value;
}

std::string YamlFields::text(const YAML::Node& node, const std::string& key) const {
  if (!node.IsScalar() || node.Scalar().empty()) {
    fail(node, key, "it must be a non-empty string");
  }
  return node.Scalar();
}

bool YamlFields::boolean(const YAML::Node& node, const std::string& key) const {
  try {
    if (node.IsScalar()) {
      return node.as<bool>();
    }
  } catch (const YAML::Exception&) {
  }
  fail(node, key, "it must be true or false");
}

// ---- YamlMap ----

YamlMap::YamlMap(const YamlFields& fields, const YAML::Node& node, std::string path)
    : fields_(fields), path_(std::move(path)) {
  node_.reset(node);  // reset, not operator=: the latter would overwrite the caller's node
  fields_.requireMapAnyKeys(node_, path_.empty() ? "(document)" : path_);
}

YAML::Node YamlMap::take(const char* key) {
  if (std::find(known_.begin(), known_.end(), key) == known_.end()) known_.emplace_back(key);
  const YAML::Node& map = node_;  // the const operator[] never inserts the key
  return map[key];
}

std::string YamlMap::full(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }

template <typename Read>
bool YamlMap::read(const char* key, Read&& read) {
  const YAML::Node item = take(key);
  if (!item) return true;
  return fields_.check([&] { read(item, full(key)); });
}

bool YamlMap::number(const char* key, double& value) {
  return read(key, [&](const YAML::Node& item, const std::string& name) { value = fields_.number(item, name); });
}

bool YamlMap::integer(const char* key, int& value, long long min, long long max) {
  return read(key, [&](const YAML::Node& item, const std::string& name) {
    value = static_cast<int>(fields_.integer(item, name, min, max));
  });
}

bool YamlMap::text(const char* key, std::string& value) {
  return read(key, [&](const YAML::Node& item, const std::string& name) { value = fields_.text(item, name); });
}

bool YamlMap::boolean(const char* key, bool& value) {
  return read(key, [&](const YAML::Node& item, const std::string& name) { value = fields_.boolean(item, name); });
}

void YamlMap::rejectUnknown() const {
  for (const auto& entry : node_) {
    const std::string key = entry.first.Scalar();
    if (std::find(known_.begin(), known_.end(), key) == known_.end()) {
      fields_.check([&] { fields_.failKey(entry.first, full(key), "unknown key (known keys: " + joined(known_) + ")"); });
    }
  }
}

}  // namespace climbsim
