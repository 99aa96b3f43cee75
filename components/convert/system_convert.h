#pragma once

// system.idl: the processes' status (heartbeats) and the virtual robot's ground truth.

#include "convert/checked.h"
#include "messages/messages.h"
#include "system.h"

namespace stickrep::convert {

// Refused: a state beyond the enum.
Checked<message::ComponentStatus> FromIdl(const msgs::ComponentStatus& m);
msgs::ComponentStatus ToIdl(const message::ComponentStatus& s);

// Refused: a non-finite position or heading.
Checked<message::GroundTruth> FromIdl(const msgs::GroundTruth& m);
msgs::GroundTruth ToIdl(const message::GroundTruth& s);

}  // namespace stickrep::convert
