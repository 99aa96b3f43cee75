#pragma once

#include <cstdint>
#include <iosfwd>
#include <map>
#include <string>
#include <vector>

#include "runtime/deployment_options.h"

namespace stickrep::recording {

struct RecordOptions {
  std::string output;               // the recording to create (never overwritten)
  std::string system_file;          // domain, QoS file, and the files stored in the metadata
  int domain_id = -1;               // -1: the system file's
  runtime::DeploymentOptions deployment;
  std::vector<std::string> topics;  // empty: every topic that has a writer of a known type
  double duration_s = 0.0;          // 0: until SIGINT/SIGTERM
  double batch_s = 0.1;             // longest stretch of data in one transaction
  std::int64_t max_bytes = 0;       // 0: unbounded; else the file's size cap (a full disk)
  double discovery_period_s = 0.2;  // how often new topics are looked for
};

// What one topic's recording came to.
struct TopicTally {
  std::string type;
  std::uint64_t received = 0;  // samples taken from DDS
  std::uint64_t stored = 0;    // committed to the file
  std::uint64_t lost = 0;      // gaps in the writers' sequence numbers
};

struct RecordReport {
  std::map<std::string, TopicTally> topics;
  double duration_s = 0.0;
  std::uint64_t bytes = 0;
  std::string failure;  // empty when the recording ended normally
};

// stickrep-record: subscribes to every (or each named) topic as its writers appear, with the
// reliability and durability they offer, and stores each sample's CDR payload unchanged with
// its source timestamp and reception time. Stops on SIGINT/SIGTERM or after duration_s and
// commits everything. A failed write (a full disk) ends it: what was committed stays.
// Throws InputError for bad settings or an existing output file.
RecordReport Record(const RecordOptions& options, std::ostream& log);

// The report as the tool prints it: one line per topic, then the totals.
void PrintRecordReport(const RecordReport& report, std::ostream& out);

}  // namespace stickrep::recording
