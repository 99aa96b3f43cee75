#include "console/doctor.h"

#include <fmt/format.h>

#include <algorithm>
#include <map>

namespace stickrep::console {

namespace {

int DurabilityRank(const std::string& d) {
  if (d == "transient_local") return 1;
  if (d == "transient") return 2;
  if (d == "persistent") return 3;
  return 0;  // volatile
}

// 0 stands for infinite in DiscoveredEndpoint.
double Period(double s) { return s <= 0.0 ? 1e300 : s; }

std::string Who(const runtime::DiscoveredEndpoint& e) {
  return e.participant.empty() ? e.guid : e.participant;
}

void CheckPair(const runtime::DiscoveredEndpoint& w, const runtime::DiscoveredEndpoint& r,
               std::vector<Finding>& out) {
  auto add = [&](const std::string& policy, const std::string& offered,
                 const std::string& requested) {
    out.push_back({w.topic, "incompatible QoS", policy, Who(w) + " offers " + offered,
                   Who(r) + " requests " + requested,
                   fmt::format("{}: the reader requests {} {} but the writer offers {}; they do "
                               "not match",
                               w.topic, policy, requested, offered)});
  };
  if (w.type != r.type) {
    out.push_back({w.topic, "type mismatch", "", Who(w) + " writes " + w.type,
                   Who(r) + " reads " + r.type,
                   fmt::format("{}: writer type {} and reader type {} differ", w.topic, w.type,
                               r.type)});
    return;
  }
  if (r.reliability == "reliable" && w.reliability != "reliable") {
    add("reliability", w.reliability, r.reliability);
  }
  if (DurabilityRank(r.durability) > DurabilityRank(w.durability)) {
    add("durability", w.durability, r.durability);
  }
  if (Period(r.deadline_s) < Period(w.deadline_s)) {
    add("deadline", fmt::format("{:g} s", w.deadline_s), fmt::format("{:g} s", r.deadline_s));
  }
  if (Period(r.liveliness_lease_s) < Period(w.liveliness_lease_s)) {
    add("liveliness lease", w.liveliness_lease_s > 0 ? fmt::format("{:g} s", w.liveliness_lease_s) : "infinite",
        fmt::format("{:g} s", r.liveliness_lease_s));
  }
}

}  // namespace

std::vector<Finding> Diagnose(const std::vector<runtime::DiscoveredEndpoint>& endpoints) {
  std::map<std::string, std::pair<std::vector<const runtime::DiscoveredEndpoint*>,
                                  std::vector<const runtime::DiscoveredEndpoint*>>>
      by_topic;
  for (const auto& e : endpoints) {
    (e.is_writer ? by_topic[e.topic].first : by_topic[e.topic].second).push_back(&e);
  }
  std::vector<Finding> out;
  for (const auto& [topic, sides] : by_topic) {
    const auto& [writers, readers] = sides;
    if (writers.empty()) {
      for (const auto* r : readers) {
        out.push_back({topic, "no writer", "", "", Who(*r),
                       fmt::format("{}: {} reads it but nothing writes it", topic, Who(*r))});
      }
    }
    if (readers.empty()) {
      for (const auto* w : writers) {
        out.push_back({topic, "no reader", "", Who(*w), "",
                       fmt::format("{}: {} writes it but nothing reads it", topic, Who(*w))});
      }
    }
    for (const auto* w : writers) {
      for (const auto* r : readers) CheckPair(*w, *r, out);
    }
  }
  return out;
}

std::vector<Finding> DiagnoseTimeliness(const std::vector<TimelinessWatch>& watches) {
  std::vector<Finding> out;
  for (const TimelinessWatch& w : watches) {
    std::string writers;
    for (const std::string& name : w.writers) writers += (writers.empty() ? "" : ", ") + name;
    if (w.deadline_s > 0.0 && w.deadlines_missed > 0) {
      out.push_back({w.topic, "missed deadline", "deadline",
                     fmt::format("{} offers {:g} s", writers.empty() ? "?" : writers, w.deadline_s),
                     fmt::format("stickrep-console requests {:g} s", w.deadline_s),
                     fmt::format("{}: {} deadlines of {:g} s passed with no sample in the {:g} s "
                                 "watched",
                                 w.topic, w.deadlines_missed, w.deadline_s, w.watched_s)});
    }
    std::vector<std::string> lost = w.writers_lost;
    std::sort(lost.begin(), lost.end());
    for (auto it = lost.begin(); it != lost.end();) {
      const auto next = std::upper_bound(it, lost.end(), *it);
      out.push_back({w.topic, "lost liveliness", "liveliness lease",
                     fmt::format("{} (lease {:g} s)", *it, w.lease_s),
                     fmt::format("stickrep-console requests {:g} s", w.lease_s),
                     fmt::format("{}: {} lost its liveliness {} time(s) in the {:g} s watched "
                                 "(no sample or assertion for {:g} s); {} writer(s) alive at "
                                 "the end",
                                 w.topic, *it, next - it, w.watched_s, w.lease_s,
                                 w.alive_writers_at_end)});
      it = next;
    }
  }
  return out;
}

bool IsFault(const Finding& f) { return f.problem != "no writer" && f.problem != "no reader"; }

}  // namespace stickrep::console
