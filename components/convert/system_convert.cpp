#include "convert/system_convert.h"

#include "convert/header.h"

namespace stickrep::convert {

static_assert(static_cast<int>(msgs::COMPONENT_FINALIZED) ==
              static_cast<int>(message::ComponentState::kFinalized));

Checked<message::ComponentStatus> FromIdl(const msgs::ComponentStatus& m) {
  const auto state = EnumFrom(m.state(), message::ComponentState::kFinalized);
  if (!state) return Checked<message::ComponentStatus>::Refused("a component state out of range");
  message::ComponentStatus s;
  s.header = FromIdl(m.header());
  s.component_name = m.component_name();
  s.state = *state;
  s.samples_in = m.samples_in();
  s.samples_out = m.samples_out();
  s.samples_dropped = m.samples_dropped();
  s.message = m.message();
  s.host = m.host();
  return Checked<message::ComponentStatus>::Ok(std::move(s));
}

msgs::ComponentStatus ToIdl(const message::ComponentStatus& s) {
  msgs::ComponentStatus m;
  m.header(ToIdl(s.header));
  m.component_name(s.component_name);
  m.state(static_cast<msgs::ComponentState>(s.state));
  m.samples_in(s.samples_in);
  m.samples_out(s.samples_out);
  m.samples_dropped(s.samples_dropped);
  m.message(s.message);
  m.host(s.host);
  return m;
}

}  // namespace stickrep::convert
