#include "idl_json.h"

#include <array>
#include <cmath>
#include <limits>
#include <utility>

#include "idl_json_codec.h"

namespace stickrep::idl {

namespace {


constexpr char kBase64[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

// The 6-bit value of a base64 character; -1 for any other.
int Base64Value(char c) {
  if (c >= 'A' && c <= 'Z') return c - 'A';
  if (c >= 'a' && c <= 'z') return c - 'a' + 26;
  if (c >= '0' && c <= '9') return c - '0' + 52;
  if (c == '+') return 62;
  if (c == '/') return 63;
  return -1;
}

}  // namespace

Type BasicType(Kind kind) {
  Type t;
  t.kind = kind;
  t.idl = KindSpelling(kind);
  return t;
}

Type NamedType(Kind kind, std::string scoped_name) {
  Type t;
  t.kind = kind;
  t.idl = scoped_name;
  t.name = std::move(scoped_name);
  return t;
}

Type StringType(std::uint32_t bound) {
  Type t = BasicType(Kind::kString);
  t.bound = bound;
  if (bound != 0) t.idl += "<" + std::to_string(bound) + ">";
  return t;
}

Type SequenceType(Type element, std::uint32_t bound) {
  Type t;
  t.kind = Kind::kSequence;
  t.bound = bound;
  t.idl = "sequence<" + element.idl + (bound != 0 ? ", " + std::to_string(bound) : "") + ">";
  t.element = std::make_shared<const Type>(std::move(element));
  return t;
}

Type ArrayType(Type element, std::uint32_t length) {
  Type t;
  t.kind = Kind::kArray;
  t.bound = length;
  // float x[2][3] is an array of 2 arrays of 3: spelled float[2][3].
  const std::size_t dims =
      element.kind == Kind::kArray ? element.idl.find('[') : element.idl.size();
  t.idl = element.idl;
  t.idl.insert(dims, "[" + std::to_string(length) + "]");
  t.element = std::make_shared<const Type>(std::move(element));
  return t;
}

JsonFormError::JsonFormError(std::string path, std::string reason)
    : std::runtime_error(path.empty() ? reason : path + ": " + reason),
      path_(std::move(path)),
      reason_(std::move(reason)) {}

JsonFormError JsonFormError::Within(const std::string& step) const {
  if (path_.empty()) return JsonFormError(step, reason_);
  return JsonFormError(step + (path_.front() == '[' ? "" : ".") + path_, reason_);
}

std::string Base64Encode(const std::vector<std::uint8_t>& bytes) {
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const std::uint32_t v = (bytes[i] << 16) | (bytes[i + 1] << 8) | bytes[i + 2];
    out += kBase64[v >> 18];
    out += kBase64[(v >> 12) & 63];
    out += kBase64[(v >> 6) & 63];
    out += kBase64[v & 63];
  }
  if (i + 1 == bytes.size()) {
    const std::uint32_t v = bytes[i] << 16;
    out += kBase64[v >> 18];
    out += kBase64[(v >> 12) & 63];
    out += "==";
  } else if (i + 2 == bytes.size()) {
    const std::uint32_t v = (bytes[i] << 16) | (bytes[i + 1] << 8);
    out += kBase64[v >> 18];
    out += kBase64[(v >> 12) & 63];
    out += kBase64[(v >> 6) & 63];
    out += '=';
  }
  return out;
}

std::vector<std::uint8_t> Base64Decode(std::string_view text) {
  if (text.size() % 4 != 0) {
    throw JsonFormError(
        "", "base64 of " + std::to_string(text.size()) + " characters, not a multiple of 4");
  }
  std::vector<std::uint8_t> out;
  out.reserve(text.size() / 4 * 3);
  for (std::size_t i = 0; i < text.size(); i += 4) {
    const bool last = i + 4 == text.size();
    const int pad = last ? (text[i + 3] == '=') + (text[i + 2] == '=') : 0;
    std::array<int, 4> v{};
    for (int k = 0; k < 4 - pad; ++k) {
      v[k] = Base64Value(text[i + k]);
      if (v[k] < 0) {
        throw JsonFormError("", "not base64: character " + std::to_string(i + k) + " is '" +
                                    std::string(1, text[i + k]) + "'");
      }
    }
    if (pad == 1 && text[i + 2] == '=') {
      throw JsonFormError("", "not base64: '=' before the last character");
    }
    const std::uint32_t bits = (v[0] << 18) | (v[1] << 12) | (v[2] << 6) | v[3];
    out.push_back(static_cast<std::uint8_t>(bits >> 16));
    if (pad < 2) out.push_back(static_cast<std::uint8_t>((bits >> 8) & 0xff));
    if (pad < 1) out.push_back(static_cast<std::uint8_t>(bits & 0xff));
    // Canonical form only: the bits a padded group leaves over are zero.
    if ((pad == 1 && (v[2] & 3) != 0) || (pad == 2 && (v[1] & 15) != 0)) {
      throw JsonFormError("", "not canonical base64: nonzero bits before the padding");
    }
  }
  return out;
}

namespace codec {

std::string Describe(const json& j) {
  std::string text = j.dump(-1, ' ', false, json::error_handler_t::replace);
  if (text.size() > 40) text = text.substr(0, 37) + "...";
  switch (j.type()) {
    case json::value_t::null:
      return "null";
    case json::value_t::boolean:
      return "a boolean (" + text + ")";
    case json::value_t::number_integer:
    case json::value_t::number_unsigned:
    case json::value_t::number_float:
      return "a number (" + text + ")";
    case json::value_t::string:
      return "a string (" + text + ")";
    case json::value_t::array:
      return "an array of " + std::to_string(j.size()) + " elements";
    case json::value_t::object:
      return "an object";
    default:
      return text;
  }
}

JsonFormError Expected(const std::string& what, const json& j) {
  return JsonFormError("", "expected " + what + ", got " + Describe(j));
}

JsonFormError NotAnEnumerator(const json& j, const char* enum_name, const char* enumerators) {
  const std::string what =
      j.is_string() ? "unknown " + std::string(enum_name) + " name " +
                          j.dump(-1, ' ', false, json::error_handler_t::replace)
                    : "expected a " + std::string(enum_name) + " name, got " + Describe(j);
  return JsonFormError("", what + "; the names are " + enumerators);
}

json CharToJson(char c) {
  const auto u = static_cast<unsigned char>(c);
  if (u < 0x80) return json(std::string(1, c));
  // U+0080..U+00FF in UTF-8.
  return json(
      std::string{static_cast<char>(0xc0 | (u >> 6)), static_cast<char>(0x80 | (u & 0x3f))});
}

char CharFromJson(const json& j) {
  if (j.is_string()) {
    const auto& s = j.get_ref<const std::string&>();
    const auto b0 = s.empty() ? 0 : static_cast<unsigned char>(s[0]);
    if (s.size() == 1 && b0 < 0x80) return s[0];
    if (s.size() == 2 && (b0 == 0xc2 || b0 == 0xc3) &&
        (static_cast<unsigned char>(s[1]) & 0xc0) == 0x80) {
      return static_cast<char>(((b0 & 0x03) << 6) | (static_cast<unsigned char>(s[1]) & 0x3f));
    }
  }
  throw Expected("a char (a string of one character, U+0000 to U+00FF)", j);
}

json DoubleToJson(double d) {
  if (std::isnan(d)) return json("nan");
  if (std::isinf(d)) return json(d > 0 ? "inf" : "-inf");
  return json(d);
}

double DoubleFromJson(const json& j, const char* idl) {
  if (j.is_number()) return j.get<double>();
  if (j.is_string()) {
    const auto& s = j.get_ref<const std::string&>();
    if (s == "nan") return std::numeric_limits<double>::quiet_NaN();
    if (s == "inf") return std::numeric_limits<double>::infinity();
    if (s == "-inf") return -std::numeric_limits<double>::infinity();
  }
  throw Expected(std::string("a number (") + idl + "), \"nan\", \"inf\" or \"-inf\"", j);
}

json WriteBytes(const std::vector<std::uint8_t>& bytes) { return json(Base64Encode(bytes)); }

void ReadBytes(const json& j, std::vector<std::uint8_t>& bytes, std::uint32_t bound,
               const char* idl) {
  if (!j.is_string()) throw Expected(std::string("a base64 string (") + idl + ")", j);
  bytes = Base64Decode(j.get_ref<const std::string&>());
  if (bound != 0 && bytes.size() > bound) {
    throw JsonFormError("", std::to_string(bytes.size()) + " bytes, more than the bound of " + idl);
  }
}

void CheckObject(const json& j, const char* struct_name,
                 std::initializer_list<const char*> members) {
  if (!j.is_object()) throw Expected(std::string("an object (") + struct_name + ")", j);
  for (const char* m : members) {
    if (!j.contains(m)) {
      throw JsonFormError("", "missing member '" + std::string(m) + "' of " + struct_name);
    }
  }
  if (j.size() != members.size()) {
    for (const auto& [key, value] : j.items()) {
      bool known = false;
      for (const char* m : members) known = known || key == m;
      if (!known) throw JsonFormError("", "unknown member '" + key + "' of " + struct_name);
    }
  }
}

}  // namespace codec

}  // namespace stickrep::idl
