#include "convert/system_convert.h"

#include <cmath>

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

Checked<message::GroundTruth> FromIdl(const msgs::GroundTruth& m) {
  const msgs::Pose2D& p = m.pose();
  if (!std::isfinite(p.x_in()) || !std::isfinite(p.y_in()) || !std::isfinite(p.heading_rad())) {
    return Checked<message::GroundTruth>::Refused("a non-finite true pose");
  }
  message::GroundTruth s;
  s.header = FromIdl(m.header());
  s.x_in = p.x_in();
  s.y_in = p.y_in();
  s.heading_rad = p.heading_rad();
  s.ring_id = m.ring_id();
  s.edge_index = static_cast<int>(m.edge_index());
  s.offset_in = m.offset_in();
  s.distance_in = m.distance_in();
  s.lateral_offset_in = m.lateral_offset_in();
  s.heading_error_deg = m.heading_error_deg();
  s.collisions = static_cast<int>(m.collisions());
  s.forward_in_ring = m.forward_in_ring();
  return Checked<message::GroundTruth>::Ok(std::move(s));
}

msgs::GroundTruth ToIdl(const message::GroundTruth& s) {
  msgs::GroundTruth m;
  m.header(ToIdl(s.header));
  m.pose().x_in(s.x_in);
  m.pose().y_in(s.y_in);
  m.pose().heading_rad(s.heading_rad);
  m.ring_id(s.ring_id);
  m.edge_index(static_cast<uint32_t>(s.edge_index));
  m.offset_in(s.offset_in);
  m.distance_in(s.distance_in);
  m.lateral_offset_in(s.lateral_offset_in);
  m.heading_error_deg(s.heading_error_deg);
  m.collisions(static_cast<uint32_t>(s.collisions));
  m.forward_in_ring(s.forward_in_ring);
  return m;
}

}  // namespace stickrep::convert
