#include "console/message_json.h"

#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

namespace stickrep::console {

using nlohmann::json;

namespace {

bool IsOctetSequence(const idl::Type& t) {
  return t.kind == idl::Kind::kSequence && t.element->kind == idl::Kind::kOctet;
}

// The length and FNV-1a hash of the bytes a base64 string holds; nullopt for anything else.
std::optional<std::pair<std::size_t, std::uint64_t>> Digest(const json& base64) {
  if (!base64.is_string()) return std::nullopt;
  std::vector<std::uint8_t> bytes;
  try {
    bytes = idl::Base64Decode(base64.get_ref<const std::string&>());
  } catch (const idl::JsonFormError&) {
    return std::nullopt;
  }
  std::uint64_t hash = 1469598103934665603ull;
  for (std::uint8_t b : bytes) hash = (hash ^ b) * 1099511628211ull;
  return std::make_pair(bytes.size(), hash);
}

void Abbreviate(const idl::Type& type, json& value);

void AbbreviateStruct(const idl::Struct& s, json& object) {
  if (!object.is_object()) return;
  for (const idl::Member& m : s.members) {
    const auto it = object.find(m.name);
    if (it == object.end()) continue;
    if (!IsOctetSequence(m.type)) {
      Abbreviate(m.type, *it);
    } else if (const auto digest = Digest(*it)) {
      object.erase(it);
      object[m.name + "_bytes"] = digest->first;
      object[m.name + "_fnv1a"] = digest->second;
    }
  }
}

void Abbreviate(const idl::Type& type, json& value) {
  if (type.kind == idl::Kind::kStruct) {
    if (const idl::Struct* s = idl::FindStruct(type.name)) AbbreviateStruct(*s, value);
  } else if ((type.kind == idl::Kind::kSequence || type.kind == idl::Kind::kArray) &&
             value.is_array()) {
    const idl::Type& element = *type.element;
    if (element.kind != idl::Kind::kStruct && element.kind != idl::Kind::kSequence &&
        element.kind != idl::Kind::kArray) {
      return;
    }
    for (json& e : value) {
      if (!IsOctetSequence(element)) {
        Abbreviate(element, e);
      } else if (const auto digest = Digest(e)) {
        e = {{"bytes", digest->first}, {"fnv1a", digest->second}};
      }
    }
  }
}

}  // namespace

json EchoForm(const std::string& type_name, json sample) {
  if (const idl::Struct* s = idl::FindStruct(type_name)) AbbreviateStruct(*s, sample);
  return sample;
}

}  // namespace stickrep::console
