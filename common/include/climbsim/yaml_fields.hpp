#pragma once
/// @file
/// Typed, validated access to YAML fields with one-line errors that name the file, the
/// line, the key and the value ("compose.yaml:7: services.a.period = 0: it must be >= 1").

#include <yaml-cpp/yaml.h>

#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

#include "climbsim/errors.hpp"

namespace climbsim {

/// Reads fields of one YAML document; every failure is a ConfigError (ConfigErrorAt). A parser
/// runs each independent field inside check() and calls finish() at the end, so that all
/// problems of a file are reported at once, in line order.
class YamlFields {
 public:
  /// `source` is the file name used in messages.
  explicit YamlFields(std::string source) : source_(std::move(source)) {}

  const std::string& source() const { return source_; }

  /// Throws ConfigError "<source>:<line>: <key> = <value>: <message>".
  [[noreturn]] void fail(const YAML::Node& node, const std::string& key, const std::string& message) const;

  /// Throws ConfigError "<source>:<line>: <key>: <message>" (no value to show).
  [[noreturn]] void failKey(const YAML::Node& node, const std::string& key, const std::string& message) const;

  /// Throws ConfigError "<source>[:<line>]: <key> = <value>: <message>" for a value that has no
  /// node (e.g. one built in code); `line` 0 for none. `value` is shown cut to one short line.
  [[noreturn]] void failValue(int line, const std::string& key, const std::string& value,
                              const std::string& message) const;

  /// Runs `body`; a ConfigError it throws is recorded for finish(). True if it ran through.
  template <typename Body>
  bool check(Body&& body) const {
    return errors_.check(std::forward<Body>(body));
  }

  /// Throws one ConfigError listing every recorded problem (one per line, in line order).
  void finish() const { errors_.throwIfAny(); }

  /// True once a problem has been recorded.
  bool failed() const { return !errors_.empty(); }

  /// Requires `node` to be a mapping (else throws); unknown keys (not in `allowed`) and
  /// duplicate keys are recorded for finish(), each as its own problem. True if every key is
  /// known (a missing key of a map with an unknown one is most likely the one misspelt).
  bool requireMap(const YAML::Node& node, const std::string& key, std::initializer_list<const char*> allowed) const;
  bool requireMap(const YAML::Node& node, const std::string& key, const std::vector<std::string>& allowed) const;

  /// The value of `name` in the mapping `map` (whose own key is `key`, "" at the top level);
  /// throws "<source>:<line of map>: <key>.<name>: missing" if it is not there. Never inserts.
  YAML::Node required(const YAML::Node& map, const std::string& key, const std::string& name) const;

  /// Requires `node` to be a mapping (else throws); duplicate keys are recorded for finish().
  void requireMapAnyKeys(const YAML::Node& node, const std::string& key) const;

  /// An integer in [min, max] (decimal, optional sign).
  long long integer(const YAML::Node& node, const std::string& key, long long min, long long max) const;

  /// Any finite number.
  double number(const YAML::Node& node, const std::string& key) const;

  /// A finite number in [min, max].
  double numberIn(const YAML::Node& node, const std::string& key, double min, double max) const;

  /// A finite number > 0 (or >= 0 if `allow_zero`).
  double positive(const YAML::Node& node, const std::string& key, bool allow_zero = false) const;

  /// A non-empty scalar string.
  std::string text(const YAML::Node& node, const std::string& key) const;

  /// true or false.
  bool boolean(const YAML::Node& node, const std::string& key) const;

  /// Parses YAML text; a syntax error is a ConfigError "<source>:<line>: YAML syntax error: ...".
  static YAML::Node load(const std::string& yaml_text, const std::string& source);

  /// Reads and parses the file `path`; ConfigError "<path>: cannot read the <what>" if it
  /// cannot be read, else as load().
  static YAML::Node loadFile(const std::string& path, const std::string& what);

  /// The 1-based line of `node`, or 0 if unknown.
  static int lineOf(const YAML::Node& node);

  /// `node` as short one-line text for messages (flow style, at most about 60 characters).
  static std::string show(const YAML::Node& node);

  /// `text` on one line, cut to about 60 characters.
  static std::string shortText(const std::string& text);

 private:
  std::string where(const YAML::Node& node) const;
  double number(const YAML::Node& node, const std::string& key, const std::string& expected) const;

  std::string source_;
  mutable ErrorList errors_;
};

/// One YAML mapping read key by key through a YamlFields (whose problems it records, so that
/// every problem of a file is reported at once): each reader takes its key, an absent key
/// keeps the value the caller set, and rejectUnknown() records every key nobody took.
/// "<file>:<line>: <path>.<key> = <value>: <why>" as every other file of the project.
class YamlMap {
 public:
  /// `path`: the mapping's own key ("" at the top level, "cracks[2]" in a list). Throws
  /// (ConfigError) if `node` is not a mapping; duplicate keys are recorded.
  YamlMap(const YamlFields& fields, const YAML::Node& node, std::string path);

  /// The node of `key` (undefined if absent); marks it as known.
  YAML::Node take(const char* key);
  /// "<path>.<key>" (or "<key>" at the top level), for messages.
  std::string full(const std::string& key) const;

  /// Each reads `key` if present (errors recorded, `value` then unchanged); true if absent or read.
  bool number(const char* key, double& value);
  bool integer(const char* key, int& value, long long min = -1'000'000'000, long long max = 1'000'000'000);
  bool text(const char* key, std::string& value);
  bool boolean(const char* key, bool& value);

  /// Records every key of the mapping no reader took, naming the known ones.
  void rejectUnknown() const;

  const YamlFields& fields() const { return fields_; }
  const YAML::Node& node() const { return node_; }

 private:
  template <typename Read>
  bool read(const char* key, Read&& read);

  const YamlFields& fields_;
  YAML::Node node_;
  std::string path_;
  std::vector<std::string> known_;
};

}  // namespace climbsim
