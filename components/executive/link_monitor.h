#pragma once

#include <map>
#include <string>
#include <vector>

namespace stickrep::executive {

// Tells a dead process from a lost link to another host. Every process's heartbeat names the
// host it runs on. A process silent for `silence_s` (or whose liveliness DDS reports lost) is
// suspected; `settle_s` later it is judged: if every process heard from on its host has been
// silent for `settle_s` too, and that host is not the executive's own, the host is
// unreachable (the link or the host is down, which may end); otherwise the process is dead.
// A lost host is back when each of its processes is heard again; one that stays silent
// `settle_s` after the others returned is dead. A process on the executive's own host is
// dead as soon as it is suspected (no link can hide it). A dead process heard again (a
// restarted one) is alive again. Times are seconds on one clock. No DDS.
class LinkMonitor {
 public:
  struct Event {
    enum class Kind { kProcessGone, kHostLost, kHostBack };
    Kind kind;
    std::string host;
    std::vector<std::string> processes;  // the process gone, or the host's processes
    std::string why;
    double outage_s = 0.0;               // kHostBack: how long the host was unreachable
  };

  LinkMonitor(std::string own_host, double silence_s, double settle_s);

  std::vector<Event> OnHeartbeat(const std::string& name, const std::string& host, double now_s);
  // The process said it stopped: gone at once.
  std::vector<Event> OnStopped(const std::string& name);
  // DDS says the process's heartbeat writer lost its liveliness.
  void OnSilent(const std::string& name, const std::string& why, double now_s);
  std::vector<Event> Tick(double now_s);

  bool HostLost(const std::string& host) const { return lost_hosts_.count(host) > 0; }

 private:
  struct Process {
    std::string host;
    double last_heard_s = 0.0;
    double suspect_since_s = -1.0;
    std::string why;
    bool gone = false;
  };
  struct LostHost {
    double since_s = 0.0;         // the last time any of its processes was heard
    double first_return_s = -1.0;
  };

  std::vector<std::string> ProcessesOn(const std::string& host) const;
  void JudgeSuspects(double now_s, std::vector<Event>& events);
  void CheckLostHosts(double now_s, std::vector<Event>& events);
  Event HostBack(const std::string& host, double now_s);

  std::string own_host_;
  double silence_s_;
  double settle_s_;
  std::map<std::string, Process> processes_;
  std::map<std::string, LostHost> lost_hosts_;
};

}  // namespace stickrep::executive
