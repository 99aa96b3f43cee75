#pragma once

// How `stickrep-console echo` shows a sample. The JSON form itself is derived from the IDL at
// build time (msgs_json.h: to_json/from_json for every type, EnumName for every enum); this is
// only what echo shows differently.

#include <nlohmann/json.hpp>

#include <string>

#include "msgs_json.h"

namespace stickrep::console {

// The echo form of `sample`, the JSON form of a `type_name` ("stickrep::msgs::Image"): the same,
// except that each sequence<octet> (an image's pixels) is shown as its length and its 64-bit
// FNV-1a hash rather than its bytes: a struct member `data` as "data_bytes" and "data_fnv1a",
// an element of a sequence or an array as {"bytes": ..., "fnv1a": ...}.
nlohmann::json EchoForm(const std::string& type_name, nlohmann::json sample);

// The echo form of a sample of any IDL struct.
template <typename T>
nlohmann::json ToJson(const T& sample) {
  return EchoForm(idl::TypeName<T>::value, nlohmann::json(sample));
}

}  // namespace stickrep::console
