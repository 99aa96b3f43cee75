#pragma once

// The contract every YAML loader is fuzzed against: on any text it returns a value or
// throws InputError naming the file it was given (possibly with a qualifier, e.g. "(as a
// map)") and a reason. Any other exception, a
// crash, a hang or a sanitizer report is a bug; so is an InputError without a reason.

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "common/input_error.h"
#include "common/strict_yaml.h"

namespace stickrep::fuzz {

// The name the fuzzed text is loaded under (stands for the file name in messages).
inline const std::string kFuzzFileName = "fuzz-input.yaml";

[[noreturn]] inline void FuzzFail(const std::string& what) {
  std::fprintf(stderr, "fuzz target contract broken: %s\n", what.c_str());
  std::abort();
}

// Runs `load(text)` and checks the contract. `load` returns true when the input loaded.
template <typename Load>
bool RunLoader(const std::uint8_t* data, std::size_t size, Load load) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    return load(text);
  } catch (const InputError& e) {
    if (e.reason().empty()) FuzzFail(std::string("InputError without a reason: ") + e.what());
    if (e.file().rfind(kFuzzFileName, 0) != 0) {
      FuzzFail("InputError names '" + e.file() + "', not the file loaded: " + e.what());
    }
    return false;
  } catch (const std::exception& e) {
    FuzzFail(std::string("exception other than InputError: ") + e.what());
  }
}

// The document root, as every loader that takes a StrictYaml is handed it.
inline StrictYaml Root(const std::string& text) {
  return StrictYaml::LoadString(text, kFuzzFileName);
}

}  // namespace stickrep::fuzz
