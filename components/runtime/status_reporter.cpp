#include "runtime/status_reporter.h"

#include "runtime/endpoint.h"
#include "systemPubSubTypes.h"

namespace stickrep::runtime {

struct StatusReporter::Impl {
  Impl(Participant& p, std::string c, std::string h, const SampleCounters& k)
      : writer(p, "system/status"), component(std::move(c)), host(std::move(h)), counters(k) {}
  Writer<msgs::ComponentStatusPubSubType> writer;
  std::string component;
  std::string host;
  const SampleCounters& counters;
};

StatusReporter::StatusReporter(Participant& participant, std::string component,
                               std::string host, const SampleCounters& counters)
    : impl_(std::make_unique<Impl>(participant, std::move(component), std::move(host),
                                   counters)) {}

StatusReporter::~StatusReporter() = default;

void StatusReporter::Publish(State state, const std::string& message) {
  msgs::ComponentStatus s;
  s.component_name(impl_->component);
  switch (state) {
    case State::kUnconfigured: s.state(msgs::COMPONENT_UNCONFIGURED); break;
    case State::kInactive: s.state(msgs::COMPONENT_INACTIVE); break;
    case State::kActive: s.state(msgs::COMPONENT_ACTIVE); break;
    case State::kFinalized: s.state(msgs::COMPONENT_FINALIZED); break;
  }
  s.samples_in(impl_->counters.in());
  s.samples_out(impl_->counters.out());
  s.samples_dropped(impl_->counters.dropped());
  s.message(message);
  s.host(impl_->host);
  impl_->writer.Publish(s, WallClockNowNs());
}

}  // namespace stickrep::runtime
