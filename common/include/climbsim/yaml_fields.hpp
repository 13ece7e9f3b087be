#pragma once
/// @file
/// Typed, validated access to YAML fields with one-line errors that name the file, the
/// line, the key and the value ("compose.yaml:7: services.a.period = 0: it must be >= 1").

#include <yaml-cpp/yaml.h>

#include <initializer_list>
#include <string>
#include <utility>

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
  /// duplicate keys are recorded for finish(), each as its own problem.
  void requireMap(const YAML::Node& node, const std::string& key, std::initializer_list<const char*> allowed) const;

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

}  // namespace climbsim
