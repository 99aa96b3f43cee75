#pragma once

#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <limits>
#include <memory>
#include <set>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include "common/input_error.h"

namespace stickrep {

// Largest YAML file any StickRep program reads (maps and configs are a few hundred kB).
inline constexpr std::uintmax_t kMaxYamlFileBytes = 16u * 1024u * 1024u;

// The text of a YAML file, refused before reading if it is missing, not a regular file, or
// over kMaxYamlFileBytes (a huge file of garbage is never loaded). Throws InputError.
std::string ReadYamlText(const std::string& path);

// `text` as a double-quoted YAML scalar that reads back as exactly `text`: quote and
// backslash escaped, every control byte written as \xNN, other bytes as they are. For
// writers that put free text (a source, a description) into a YAML file they will load.
std::string YamlQuoted(const std::string& text);

// A view of one YAML node that knows its file and its key path, reads values strictly and
// reports every problem as an InputError naming file, line and key. A mapping remembers
// which keys were read so that Finish() can reject the unknown ones ("every key used
// exactly once").
//
//   StrictYaml root = StrictYaml::LoadFile(path);
//   StrictYaml sonar = root.Child("sonar");
//   cfg.rate_hz = sonar.Get<double>("rate_hz", 0.1, 100.0);
//   sonar.Finish();
class StrictYaml {
 public:
  // Parses a file; throws InputError for a missing, oversized, binary or malformed file.
  static StrictYaml LoadFile(const std::string& path);
  // Parses text; `name` stands in for the file name in messages.
  static StrictYaml LoadString(const std::string& text, const std::string& name);

  const std::string& file() const { return file_; }
  // Dotted path of this node from the document root, e.g. "rings[2].edges[7]".
  const std::string& path() const { return path_; }
  // 1-based line of this node in its file (0 if unknown).
  int line() const;

  bool IsMap() const { return node_.IsMap(); }
  bool IsSequence() const { return node_.IsSequence(); }
  bool IsScalar() const { return node_.IsScalar(); }
  bool Has(const std::string& key) const;
  // Keys of this mapping in file order.
  std::vector<std::string> Keys() const;

  // A required child; throws if this is not a mapping or the key is missing.
  StrictYaml Child(const std::string& key) const;
  // The elements of a required sequence under `key`.
  std::vector<StrictYaml> Sequence(const std::string& key) const;
  // The elements of this node, which must be a sequence.
  std::vector<StrictYaml> Elements() const;

  // A required scalar converted to T (bool, integers, floating point, std::string).
  template <typename T>
  T Get(const std::string& key) const;
  // A required number in [lo, hi]; `unit` goes into the message.
  template <typename T>
  T Get(const std::string& key, T lo, T hi, const std::string& unit = "") const;
  // An optional scalar; `fallback` when the key is absent (but a present bad value throws).
  template <typename T>
  T GetOr(const std::string& key, const T& fallback) const;
  // This node itself as a scalar of type T.
  template <typename T>
  T As() const;

  // Throws InputError for every key of this mapping that was not read.
  void Finish() const;
  // Throws InputError about `key` (its line if present, else this node's line).
  [[noreturn]] void Fail(const std::string& key, const std::string& reason) const;

  const YAML::Node& raw() const { return node_; }

 private:
  StrictYaml(YAML::Node node, std::string file, std::string path);
  void RequireMap() const;
  // A mapping key's text; throws InputError for a key that is not a scalar.
  std::string KeyText(const YAML::Node& key) const;
  YAML::Node Lookup(const std::string& key) const;
  std::string ChildPath(const std::string& key) const;
  template <typename T>
  T Convert(const YAML::Node& node, const std::string& key) const;
  template <typename T>
  static std::string ToText(T v) {
    std::ostringstream out;
    out << v;
    return out.str();
  }
  static const char* TypeName(const bool*) { return "true or false"; }
  static const char* TypeName(const std::string*) { return "a string"; }
  template <typename T>
  static const char* TypeName(const T*) {
    return std::is_integral<T>::value ? "an integer" : "a number";
  }

  YAML::Node node_;
  std::string file_;
  std::string path_;
  std::shared_ptr<std::set<std::string>> used_;
};

template <typename T>
T StrictYaml::Convert(const YAML::Node& node, const std::string& key) const {
  const int line = node.Mark().line >= 0 ? node.Mark().line + 1 : this->line();
  if (!node.IsScalar()) {
    throw InputError(file_, line, key, std::string("expected ") + TypeName((T*)nullptr));
  }
  T value{};
  if (!YAML::convert<T>::decode(node, value)) {
    throw InputError(file_, line, key,
                     std::string("expected ") + TypeName((T*)nullptr) + ", got '" +
                         node.Scalar() + "'");
  }
  if constexpr (std::is_floating_point<T>::value) {
    if (!(value == value) || value == std::numeric_limits<T>::infinity() ||
        value == -std::numeric_limits<T>::infinity()) {
      throw InputError(file_, line, key, "expected a finite number, got '" + node.Scalar() + "'");
    }
  }
  return value;
}

template <typename T>
T StrictYaml::Get(const std::string& key) const {
  return Convert<T>(Lookup(key), ChildPath(key));
}

template <typename T>
T StrictYaml::Get(const std::string& key, T lo, T hi, const std::string& unit) const {
  const YAML::Node node = Lookup(key);
  const T value = Convert<T>(node, ChildPath(key));
  if (value < lo || value > hi) {
    const std::string u = unit.empty() ? "" : " " + unit;
    throw InputError(file_, node.Mark().line + 1, ChildPath(key),
                     "value " + ToText(value) + u + " is outside [" + ToText(lo) + ", " +
                         ToText(hi) + "]" + u);
  }
  return value;
}

template <typename T>
T StrictYaml::GetOr(const std::string& key, const T& fallback) const {
  if (!Has(key)) {
    RequireMap();
    used_->insert(key);
    return fallback;
  }
  return Get<T>(key);
}

template <typename T>
T StrictYaml::As() const {
  return Convert<T>(node_, path_);
}

}  // namespace stickrep
