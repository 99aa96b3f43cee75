#include "executive/link_monitor.h"

#include <fmt/format.h>

#include <algorithm>
#include <set>

namespace stickrep::executive {

LinkMonitor::LinkMonitor(std::string own_host, double silence_s, double settle_s)
    : own_host_(std::move(own_host)), silence_s_(silence_s), settle_s_(settle_s) {}

std::vector<std::string> LinkMonitor::ProcessesOn(const std::string& host) const {
  std::vector<std::string> out;
  for (const auto& [name, p] : processes_) {
    if (p.host == host && !p.gone) out.push_back(name);
  }
  return out;
}

std::vector<LinkMonitor::Event> LinkMonitor::OnHeartbeat(const std::string& name,
                                                         const std::string& host, double now_s) {
  Process& p = processes_[name];
  p.host = host;
  p.last_heard_s = now_s;
  p.suspect_since_s = -1.0;
  p.gone = false;
  std::vector<Event> events;
  const auto lost = lost_hosts_.find(host);
  if (lost == lost_hosts_.end()) return events;
  if (lost->second.first_return_s < 0.0) lost->second.first_return_s = now_s;
  const auto on_host = ProcessesOn(host);
  const bool all_back = std::all_of(on_host.begin(), on_host.end(), [&](const std::string& n) {
    return processes_.at(n).last_heard_s > lost->second.since_s;
  });
  if (all_back) events.push_back(HostBack(host, now_s));
  return events;
}

std::vector<LinkMonitor::Event> LinkMonitor::OnStopped(const std::string& name) {
  auto it = processes_.find(name);
  if (it != processes_.end() && it->second.gone) return {};
  const std::string host = it == processes_.end() ? "" : it->second.host;
  processes_[name].gone = true;
  return {Event{Event::Kind::kProcessGone, host, {name}, "it stopped"}};
}

void LinkMonitor::OnSilent(const std::string& name, const std::string& why, double now_s) {
  auto it = processes_.find(name);
  if (it == processes_.end() || it->second.gone || it->second.suspect_since_s >= 0.0) return;
  it->second.suspect_since_s = now_s;
  it->second.why = why;
}

std::vector<LinkMonitor::Event> LinkMonitor::Tick(double now_s) {
  for (auto& [name, p] : processes_) {
    if (!p.gone && p.suspect_since_s < 0.0 && now_s - p.last_heard_s > silence_s_) {
      p.suspect_since_s = now_s;
      p.why = fmt::format("no heartbeat for {:.1f} s", silence_s_);
    }
  }
  std::vector<Event> events;
  JudgeSuspects(now_s, events);
  CheckLostHosts(now_s, events);
  return events;
}

void LinkMonitor::JudgeSuspects(double now_s, std::vector<Event>& events) {
  // On the executive's own host a silent process cannot be a lost link: it is judged dead
  // at once, which stops the robot one settle time sooner.
  const auto settled = [&](const Process& p) {
    return p.suspect_since_s >= 0.0 &&
           now_s - p.suspect_since_s >= (p.host == own_host_ ? 0.0 : settle_s_);
  };
  std::set<std::string> hosts;
  for (const auto& [name, p] : processes_) {
    if (!p.gone && settled(p) && lost_hosts_.count(p.host) == 0) hosts.insert(p.host);
  }
  for (const std::string& host : hosts) {
    const auto on_host = ProcessesOn(host);
    double last_heard = 0.0;
    bool all_silent = true;
    for (const std::string& n : on_host) {
      last_heard = std::max(last_heard, processes_.at(n).last_heard_s);
      all_silent &= now_s - processes_.at(n).last_heard_s >= settle_s_;
    }
    if (all_silent && host != own_host_) {
      lost_hosts_[host] = LostHost{last_heard, -1.0};
      for (const std::string& n : on_host) processes_.at(n).suspect_since_s = -1.0;
      events.push_back(Event{Event::Kind::kHostLost, host, on_host,
                             fmt::format("no process on host '{}' heard for {:.1f} s", host,
                                         now_s - last_heard)});
      continue;
    }
    for (const std::string& n : on_host) {
      Process& p = processes_.at(n);
      if (settled(p)) {
        p.gone = true;
        events.push_back(Event{Event::Kind::kProcessGone, host, {n}, p.why});
      }
    }
  }
}

void LinkMonitor::CheckLostHosts(double now_s, std::vector<Event>& events) {
  std::vector<std::string> back;
  for (const auto& [host, lost] : lost_hosts_) {
    if (lost.first_return_s >= 0.0 && now_s - lost.first_return_s >= settle_s_) {
      back.push_back(host);
    }
  }
  for (const std::string& host : back) {
    const double since = lost_hosts_.at(host).since_s;
    for (const std::string& n : ProcessesOn(host)) {
      Process& p = processes_.at(n);
      if (p.last_heard_s <= since) {
        p.gone = true;
        events.push_back(Event{Event::Kind::kProcessGone, host, {n},
                               "it did not come back with its host"});
      }
    }
    events.push_back(HostBack(host, now_s));
  }
}

LinkMonitor::Event LinkMonitor::HostBack(const std::string& host, double now_s) {
  const double outage = now_s - lost_hosts_.at(host).since_s;
  lost_hosts_.erase(host);
  return Event{Event::Kind::kHostBack, host, ProcessesOn(host),
               fmt::format("host '{}' heard again after {:.1f} s", host, outage), outage};
}

}  // namespace stickrep::executive
