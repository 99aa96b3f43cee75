#include "convert/base_convert.h"

#include <cmath>

#include "convert/header.h"

namespace stickrep::convert {

static_assert(static_cast<int>(msgs::MOTION_FOLLOW_HALLWAY) ==
              static_cast<int>(message::MotionMode::kFollowHallway));
static_assert(static_cast<int>(msgs::LOCOMOTION_OBSTACLE) ==
              static_cast<int>(message::LocomotionState::kObstacle));

Checked<message::WheelCommand> FromIdl(const msgs::WheelCommand& m) {
  if (!std::isfinite(m.left_speed_ftps()) || !std::isfinite(m.right_speed_ftps())) {
    return Checked<message::WheelCommand>::Refused("non-finite wheel speed");
  }
  return Checked<message::WheelCommand>::Ok(
      {FromIdl(m.header()), m.left_speed_ftps(), m.right_speed_ftps()});
}

msgs::WheelCommand ToIdl(const message::WheelCommand& s) {
  msgs::WheelCommand m;
  m.header(ToIdl(s.header));
  m.left_speed_ftps(s.left_speed_ftps);
  m.right_speed_ftps(s.right_speed_ftps);
  return m;
}

Checked<message::EncoderReading> FromIdl(const msgs::EncoderReading& m) {
  if (!std::isfinite(m.left_travel_in()) || !std::isfinite(m.right_travel_in())) {
    return Checked<message::EncoderReading>::Refused("non-finite wheel travel");
  }
  return Checked<message::EncoderReading>::Ok(
      {FromIdl(m.header()), m.left_travel_in(), m.right_travel_in()});
}

msgs::EncoderReading ToIdl(const message::EncoderReading& s) {
  msgs::EncoderReading m;
  m.header(ToIdl(s.header));
  m.left_travel_in(s.left_travel_in);
  m.right_travel_in(s.right_travel_in);
  return m;
}

Checked<message::MotionCommand> FromIdl(const msgs::MotionCommand& m) {
  const auto mode = EnumFrom(m.mode(), message::MotionMode::kFollowHallway);
  if (!mode) return Checked<message::MotionCommand>::Refused("a motion mode out of range");
  return Checked<message::MotionCommand>::Ok(
      {FromIdl(m.header()), *mode, m.linear_speed_ftps(), m.angular_rate_radps()});
}

msgs::MotionCommand ToIdl(const message::MotionCommand& s) {
  msgs::MotionCommand m;
  m.header(ToIdl(s.header));
  m.mode(static_cast<msgs::MotionMode>(s.mode));
  m.linear_speed_ftps(s.linear_speed_ftps);
  m.angular_rate_radps(s.angular_rate_radps);
  return m;
}

Checked<message::MotionState> FromIdl(const msgs::MotionState& m) {
  const auto mode = EnumFrom(m.mode(), message::MotionMode::kFollowHallway);
  const auto state = EnumFrom(m.state(), message::LocomotionState::kObstacle);
  if (!mode || !state) {
    return Checked<message::MotionState>::Refused("a motion mode or state out of range");
  }
  message::MotionState s;
  s.header = FromIdl(m.header());
  s.mode = *mode;
  s.state = *state;
  s.travel_sign = m.travel_sign();
  s.offset_valid = m.offset_valid();
  s.lateral_offset_in = m.lateral_offset_in();
  s.heading_valid = m.heading_valid();
  s.heading_error_deg = m.heading_error_deg();
  s.in_envelope = m.in_envelope();
  s.commanded_speed_ftps = m.commanded_speed_ftps();
  s.linear_speed_ftps = m.linear_speed_ftps();
  s.angular_rate_radps = m.angular_rate_radps();
  s.message = m.message();
  return Checked<message::MotionState>::Ok(std::move(s));
}

msgs::MotionState ToIdl(const message::MotionState& s) {
  msgs::MotionState m;
  m.header(ToIdl(s.header));
  m.mode(static_cast<msgs::MotionMode>(s.mode));
  m.state(static_cast<msgs::LocomotionState>(s.state));
  m.travel_sign(s.travel_sign);
  m.offset_valid(s.offset_valid);
  m.lateral_offset_in(s.lateral_offset_in);
  m.heading_valid(s.heading_valid);
  m.heading_error_deg(s.heading_error_deg);
  m.in_envelope(s.in_envelope);
  m.commanded_speed_ftps(s.commanded_speed_ftps);
  m.linear_speed_ftps(s.linear_speed_ftps);
  m.angular_rate_radps(s.angular_rate_radps);
  m.message(s.message);
  return m;
}

Checked<message::Odometry> FromIdl(const msgs::Odometry& m) {
  if (!std::isfinite(m.distance_in())) {
    return Checked<message::Odometry>::Refused("non-finite distance");
  }
  if (!std::isfinite(m.pose().heading_rad())) {
    return Checked<message::Odometry>::Refused("non-finite heading");
  }
  if (!std::isfinite(m.linear_speed_ftps())) {
    return Checked<message::Odometry>::Refused("non-finite speed");
  }
  message::Odometry s;
  s.header = FromIdl(m.header());
  s.x_in = m.pose().x_in();
  s.y_in = m.pose().y_in();
  s.heading_rad = m.pose().heading_rad();
  s.distance_in = m.distance_in();
  s.linear_speed_ftps = m.linear_speed_ftps();
  s.angular_rate_radps = m.angular_rate_radps();
  return Checked<message::Odometry>::Ok(s);
}

msgs::Odometry ToIdl(const message::Odometry& s) {
  msgs::Odometry m;
  m.header(ToIdl(s.header));
  m.pose().x_in(s.x_in);
  m.pose().y_in(s.y_in);
  m.pose().heading_rad(s.heading_rad);
  m.distance_in(s.distance_in);
  m.linear_speed_ftps(s.linear_speed_ftps);
  m.angular_rate_radps(s.angular_rate_radps);
  return m;
}

}  // namespace stickrep::convert
