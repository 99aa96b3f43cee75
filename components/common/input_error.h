#pragma once

#include <stdexcept>
#include <string>

namespace stickrep {

// Exit code of every tool and process for bad input (malformed file, bad key or value).
inline constexpr int kExitBadInput = 2;

// Bad input found while setting up: which file, which line (1-based, 0 when unknown),
// which key, and why. Thrown at set-up only; tools catch it and exit with kExitBadInput.
class InputError : public std::runtime_error {
 public:
  InputError(std::string file, int line, std::string key, std::string reason);

  const std::string& file() const { return file_; }
  int line() const { return line_; }
  const std::string& key() const { return key_; }
  const std::string& reason() const { return reason_; }

 private:
  std::string file_;
  int line_;
  std::string key_;
  std::string reason_;
};

// "file:line: key 'k': reason", leaving out the parts that are empty.
std::string FormatInputError(const std::string& file, int line, const std::string& key,
                             const std::string& reason);

}  // namespace stickrep
