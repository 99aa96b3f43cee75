#pragma once

#include <optional>
#include <string>
#include <utility>

namespace stickrep::convert {

// A sample read from the network: the value, or why it was refused.
template <typename T>
struct Checked {
  std::optional<T> value;
  std::string reason;
  static Checked Ok(T v) { return {std::move(v), {}}; }
  static Checked Refused(std::string why) { return {std::nullopt, std::move(why)}; }
};

// An IDL enum read as the C++ enum of the same order; nullopt beyond its last value.
template <typename To, typename From>
std::optional<To> EnumFrom(From v, To last) {
  const auto n = static_cast<long long>(v);
  if (n < 0 || n > static_cast<long long>(last)) return std::nullopt;
  return static_cast<To>(n);
}

}  // namespace stickrep::convert
