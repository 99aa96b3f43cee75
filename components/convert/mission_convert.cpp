#include "convert/mission_convert.h"

#include "convert/header.h"

namespace stickrep::convert {

static_assert(static_cast<int>(msgs::MISSION_LINK_LOST) ==
              static_cast<int>(message::MissionState::kLinkLost));

Checked<message::MissionGoal> FromIdl(const msgs::MissionGoal& m) {
  return Checked<message::MissionGoal>::Ok({FromIdl(m.header()), m.goal_id(), m.target()});
}

msgs::MissionGoal ToIdl(const message::MissionGoal& s) {
  msgs::MissionGoal m;
  m.header(ToIdl(s.header));
  m.goal_id(s.goal_id);
  m.target(s.target);
  return m;
}

Checked<message::MissionStatus> FromIdl(const msgs::MissionStatus& m) {
  const auto state = EnumFrom(m.state(), message::MissionState::kLinkLost);
  if (!state) return Checked<message::MissionStatus>::Refused("a mission state out of range");
  return Checked<message::MissionStatus>::Ok({FromIdl(m.header()), *state, m.goal_id(), m.message()});
}

msgs::MissionStatus ToIdl(const message::MissionStatus& s) {
  msgs::MissionStatus m;
  m.header(ToIdl(s.header));
  m.state(static_cast<msgs::MissionState>(s.state));
  m.goal_id(s.goal_id);
  m.message(s.message);
  return m;
}

Checked<message::MissionGoalResult> FromIdl(const msgs::MissionGoalResult& m) {
  return Checked<message::MissionGoalResult>::Ok(
      {FromIdl(m.header()), m.goal_id(), m.target(), m.accepted(), m.reason()});
}

msgs::MissionGoalResult ToIdl(const message::MissionGoalResult& s) {
  msgs::MissionGoalResult m;
  m.header(ToIdl(s.header));
  m.goal_id(s.goal_id);
  m.target(s.target);
  m.accepted(s.accepted);
  m.reason(s.reason);
  return m;
}

}  // namespace stickrep::convert
