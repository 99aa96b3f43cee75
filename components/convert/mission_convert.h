#pragma once

// mission.idl: goals, the mission's status, goal results.

#include "convert/checked.h"
#include "messages/messages.h"
#include "mission.h"

namespace stickrep::convert {

Checked<message::MissionGoal> FromIdl(const msgs::MissionGoal& m);
msgs::MissionGoal ToIdl(const message::MissionGoal& s);

// Refused: a state beyond the enum.
Checked<message::MissionStatus> FromIdl(const msgs::MissionStatus& m);
msgs::MissionStatus ToIdl(const message::MissionStatus& s);

Checked<message::MissionGoalResult> FromIdl(const msgs::MissionGoalResult& m);
msgs::MissionGoalResult ToIdl(const message::MissionGoalResult& s);

}  // namespace stickrep::convert
