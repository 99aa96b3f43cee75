#pragma once

// What the generated msgs_json.cpp is written with: writing and reading one value of an IDL
// type in its JSON form. Included only by the generated source and by idl_json.cpp.
//
// The JSON form: booleans, integers and strings as themselves; float and double as numbers,
// or "nan", "inf", "-inf" when not finite (JSON has no such numbers); char as a one-character
// string (values above 127 as U+0080..U+00FF); enums by their IDL names; structs as objects
// with every member; sequences and arrays as arrays, except sequence<octet>, a base64 string.

#include <fastrtps/utils/fixed_size_string.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "idl_json.h"

namespace stickrep::idl::codec {

using nlohmann::json;

// A JSON value for an error message: its kind and the start of its text.
std::string Describe(const json& j);
// "expected WHAT, got DESCRIBE(j)".
JsonFormError Expected(const std::string& what, const json& j);
// A string that is no enumerator of the enum.
JsonFormError NotAnEnumerator(const json& j, const char* enum_name, const char* enumerators);

json CharToJson(char c);
char CharFromJson(const json& j);
json DoubleToJson(double d);
// A number, or "nan", "inf", "-inf"; `idl` names the type in errors.
double DoubleFromJson(const json& j, const char* idl);

json WriteBytes(const std::vector<std::uint8_t>& bytes);
void ReadBytes(const json& j, std::vector<std::uint8_t>& bytes, std::uint32_t bound,
               const char* idl);

// Throws unless `j` is an object with exactly these members.
void CheckObject(const json& j, const char* struct_name,
                 std::initializer_list<const char*> members);

template <typename T>
struct IsFixedString : std::false_type {};
template <std::size_t N>
struct IsFixedString<eprosima::fastrtps::fixed_string<N>> : std::true_type {};

template <typename T>
constexpr const char* IntegerIdl() {
  if constexpr (std::is_same_v<T, std::uint8_t>) return "octet";
  if constexpr (std::is_same_v<T, std::int16_t>) return "short";
  if constexpr (std::is_same_v<T, std::uint16_t>) return "unsigned short";
  if constexpr (std::is_same_v<T, std::int32_t>) return "long";
  if constexpr (std::is_same_v<T, std::uint32_t>) return "unsigned long";
  if constexpr (std::is_same_v<T, std::int64_t>) return "long long";
  if constexpr (std::is_same_v<T, std::uint64_t>) return "unsigned long long";
  return "integer";
}

template <typename T>
void ReadInteger(const json& j, T& v) {
  using Limits = std::numeric_limits<T>;
  const auto out_of_range = [&j] {
    return JsonFormError("", Describe(j) + " is out of the range of " + IntegerIdl<T>());
  };
  if (j.is_number_unsigned()) {
    const auto u = j.get<std::uint64_t>();
    if (u > static_cast<std::uint64_t>(Limits::max())) throw out_of_range();
    v = static_cast<T>(u);
  } else if (j.is_number_integer()) {
    const auto s = j.get<std::int64_t>();
    if constexpr (std::is_unsigned_v<T>) {
      if (s < 0 || static_cast<std::uint64_t>(s) > static_cast<std::uint64_t>(Limits::max())) {
        throw out_of_range();
      }
    } else {
      if (s < static_cast<std::int64_t>(Limits::min()) ||
          s > static_cast<std::int64_t>(Limits::max())) {
        throw out_of_range();
      }
    }
    v = static_cast<T>(s);
  } else {
    throw Expected(std::string("an integer (") + IntegerIdl<T>() + ")", j);
  }
}

// One value that is not a sequence or an array. Enums and structs go through their generated
// to_json and from_json, found by argument-dependent lookup.
template <typename T>
json Write(const T& v) {
  if constexpr (std::is_same_v<T, bool>) {
    return json(v);
  } else if constexpr (std::is_same_v<T, char>) {
    return CharToJson(v);
  } else if constexpr (std::is_integral_v<T>) {
    return json(v);
  } else if constexpr (std::is_floating_point_v<T>) {
    return DoubleToJson(static_cast<double>(v));
  } else if constexpr (std::is_same_v<T, std::string>) {
    return json(v);
  } else if constexpr (IsFixedString<T>::value) {
    return json(std::string(v.c_str(), v.size()));
  } else {
    json j;
    to_json(j, v);
    return j;
  }
}

template <typename T>
void Read(const json& j, T& v) {
  if constexpr (std::is_same_v<T, bool>) {
    if (!j.is_boolean()) throw Expected("a boolean", j);
    v = j.get<bool>();
  } else if constexpr (std::is_same_v<T, char>) {
    v = CharFromJson(j);
  } else if constexpr (std::is_integral_v<T>) {
    ReadInteger(j, v);
  } else if constexpr (std::is_same_v<T, float>) {
    const double d = DoubleFromJson(j, "float");
    if (std::isfinite(d) && std::fabs(d) > std::numeric_limits<float>::max()) {
      throw JsonFormError("", Describe(j) + " is out of the range of float");
    }
    v = static_cast<float>(d);
  } else if constexpr (std::is_same_v<T, double>) {
    v = DoubleFromJson(j, "double");
  } else if constexpr (std::is_same_v<T, std::string>) {
    if (!j.is_string()) throw Expected("a string", j);
    v = j.get_ref<const std::string&>();
  } else if constexpr (IsFixedString<T>::value) {
    if (!j.is_string()) throw Expected("a string", j);
    const auto& s = j.get_ref<const std::string&>();
    if (s.size() > v.max_size) {
      throw JsonFormError("", "a string of " + std::to_string(s.size()) +
                                  " bytes, longer than its bound of " + std::to_string(v.max_size));
    }
    v = s;
  } else {
    from_json(j, v);
  }
}

// A sequence or an array, element by element.
template <typename Container, typename WriteElement>
json WriteSequence(const Container& v, WriteElement write) {
  json out = json::array();
  for (std::size_t i = 0; i < v.size(); ++i) {
    const typename Container::value_type& e = v[i];  // a copy only for std::vector<bool>
    out.push_back(write(e));
  }
  return out;
}

template <typename Vector, typename ReadElement>
void ReadSequence(const json& j, Vector& v, std::uint32_t bound, const char* idl,
                  ReadElement read) {
  if (!j.is_array()) throw Expected(std::string("an array (") + idl + ")", j);
  if (bound != 0 && j.size() > bound) {
    throw JsonFormError("", std::to_string(j.size()) + " elements, more than the bound of " + idl);
  }
  v.clear();
  v.reserve(j.size());
  for (std::size_t i = 0; i < j.size(); ++i) {
    typename Vector::value_type e{};
    try {
      read(j[i], e);
    } catch (const JsonFormError& error) {
      throw error.Within("[" + std::to_string(i) + "]");
    }
    v.push_back(std::move(e));
  }
}

template <typename Array, typename ReadElement>
void ReadArray(const json& j, Array& a, const char* idl, ReadElement read) {
  if (!j.is_array()) throw Expected(std::string("an array (") + idl + ")", j);
  if (j.size() != a.size()) {
    throw JsonFormError(
        "", std::to_string(j.size()) + " elements; " + idl + " has " + std::to_string(a.size()));
  }
  for (std::size_t i = 0; i < a.size(); ++i) {
    try {
      read(j[i], a[i]);
    } catch (const JsonFormError& error) {
      throw error.Within("[" + std::to_string(i) + "]");
    }
  }
}

// One member of a struct, checked present by CheckObject; errors name the member.
template <typename ReadValue>
void ReadMember(const json& j, const char* name, ReadValue read) {
  try {
    read(j.at(name));
  } catch (const JsonFormError& error) {
    throw error.Within(name);
  }
}

}  // namespace stickrep::idl::codec
