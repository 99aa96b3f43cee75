#include "common/input_error.h"

namespace stickrep {

std::string FormatInputError(const std::string& file, int line, const std::string& key,
                             const std::string& reason) {
  std::string out = file.empty() ? std::string("<input>") : file;
  if (line > 0) out += ":" + std::to_string(line);
  out += ": ";
  if (!key.empty()) out += "key '" + key + "': ";
  out += reason;
  return out;
}

InputError::InputError(std::string file, int line, std::string key, std::string reason)
    : std::runtime_error(FormatInputError(file, line, key, reason)),
      file_(std::move(file)),
      line_(line),
      key_(std::move(key)),
      reason_(std::move(reason)) {}

}  // namespace stickrep
