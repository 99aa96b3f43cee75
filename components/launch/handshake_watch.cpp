#include "launch/handshake_watch.h"

#include <regex>

namespace stickrep::launch {

HandshakeWatch::HandshakeWatch(double timeout_s, int max_heals)
    : timeout_s_(timeout_s), max_heals_(max_heals) {}

void HandshakeWatch::Started(const std::string& process, double now_s) {
  Process& p = processes_[process];
  p.running = true;
  p.started_s = now_s;
  p.authenticated.clear();
}

void HandshakeWatch::Stopped(const std::string& process) { processes_[process].running = false; }

void HandshakeWatch::Line(const std::string& process, const std::string& line) {
  static const std::regex identity(R"(secured: identity '[^']*' of .* \(participant (\S+)\))");
  static const std::regex authenticated(R"(DDS Security: participant \S+ \((\S+)\) authenticated)");
  const auto it = processes_.find(process);
  if (it == processes_.end()) return;
  std::smatch m;
  if (std::regex_search(line, m, authenticated)) {
    it->second.authenticated.insert(m[1]);
  } else if (std::regex_search(line, m, identity)) {
    it->second.participant = m[1];
  }
}

bool HandshakeWatch::Authenticated(const Process& a, const Process& b) const {
  return a.authenticated.count(b.participant) > 0 || b.authenticated.count(a.participant) > 0;
}

std::vector<HandshakeWatch::Stuck> HandshakeWatch::Check(double now_s) {
  std::vector<Stuck> out;
  if (timeout_s_ <= 0.0) return out;
  for (auto a = processes_.begin(); a != processes_.end(); ++a) {
    for (auto b = std::next(a); b != processes_.end(); ++b) {
      const Process& pa = a->second;
      const Process& pb = b->second;
      if (!pa.running || !pb.running || pa.participant.empty() || pb.participant.empty()) continue;
      if (pa.participant == pb.participant) continue;
      const double together_s = now_s - std::max(pa.started_s, pb.started_s);
      if (together_s < timeout_s_ || Authenticated(pa, pb)) continue;
      int& heals = heals_[{a->first, b->first}];
      if (heals >= max_heals_) continue;
      heals++;
      const bool a_later = pa.started_s >= pb.started_s;
      out.push_back({a_later ? a->first : b->first, a_later ? b->first : a->first, together_s});
      // Restarted, the later process starts its clock again: not reported twice.
      (a_later ? a->second : b->second).running = false;
    }
  }
  return out;
}

}  // namespace stickrep::launch
