#pragma once

// `stickrep-console doctor`: what keeps endpoints of the domain from talking, judged from
// what discovery shows of every writer and reader (no DDS here: the console feeds it).
// Requested-versus-offered QoS follows the DDS rules: a reader may not ask for more
// reliability, durability, a shorter deadline or a shorter liveliness lease than a writer
// offers; a writer and a reader of one topic must name the same type.

#include <string>
#include <vector>

#include "runtime/discovery.h"

namespace stickrep::console {

struct Finding {
  std::string topic;
  std::string problem;  // "incompatible QoS", "type mismatch", "no writer", "no reader"
  std::string policy;   // the QoS policy at fault ("reliability", ...), or ""
  std::string writer;   // the process and what it offers, or ""
  std::string reader;   // the process and what it requests, or ""
  std::string detail;   // one sentence
};

std::vector<Finding> Diagnose(const std::vector<runtime::DiscoveredEndpoint>& endpoints);

}  // namespace stickrep::console
