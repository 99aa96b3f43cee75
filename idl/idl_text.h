#pragma once

#include <map>
#include <string>

namespace stickrep::msgs {

// The text of every StickRep .idl file by file name ("sensors.idl"), as built.
const std::map<std::string, std::string>& IdlFiles();

}  // namespace stickrep::msgs
