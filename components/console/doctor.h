#pragma once

// `stickrep-console doctor`: what keeps endpoints of the domain from talking, judged from
// what discovery shows of every writer and reader, and what the doctor's own readers of the
// timed topics saw (no DDS here: the console feeds it).
// Requested-versus-offered QoS follows the DDS rules: a reader may not ask for more
// reliability, durability, a shorter deadline or a shorter liveliness lease than a writer
// offers; a writer and a reader of one topic must name the same type.

#include <cstdint>
#include <string>
#include <vector>

#include "runtime/discovery.h"

namespace stickrep::console {

struct Finding {
  std::string topic;
  std::string problem;  // "incompatible QoS", "type mismatch", "no writer", "no reader",
                        // "missed deadline", "lost liveliness"
  std::string policy;   // the QoS policy at fault ("reliability", ...), or ""
  std::string writer;   // the process and what it offers, or ""
  std::string reader;   // the process and what it requests, or ""
  std::string detail;   // one sentence
};

std::vector<Finding> Diagnose(const std::vector<runtime::DiscoveredEndpoint>& endpoints);

// What a reader with a topic's catalogued QoS saw while it watched a topic whose QoS has a
// deadline or a liveliness lease: the deadlines DDS reported missed and the writers whose
// liveliness it reported lost.
struct TimelinessWatch {
  std::string topic;
  double deadline_s = 0.0;  // 0: none
  double lease_s = 0.0;     // 0: infinite
  double watched_s = 0.0;
  std::vector<std::string> writers;       // who writes the topic (process names)
  std::uint64_t deadlines_missed = 0;
  std::vector<std::string> writers_lost;  // whose liveliness lapsed, once per loss
  int alive_writers_at_end = 0;
};

// One "missed deadline" finding per topic whose deadline passed, one "lost liveliness" per
// writer that lapsed.
std::vector<Finding> DiagnoseTimeliness(const std::vector<TimelinessWatch>& watches);

// True for the findings that mean samples do not flow as their QoS promises (all but a
// reader or writer alone, which is normal while a graph starts or stops).
bool IsFault(const Finding& f);

}  // namespace stickrep::console
