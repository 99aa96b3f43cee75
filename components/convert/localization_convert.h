#pragma once

// localization.idl: the pose and its hypotheses (the map message is map_msg.h's).

#include "convert/checked.h"
#include "localization.h"
#include "messages/messages.h"

namespace stickrep::convert {

// Refused: a status beyond the enum.
Checked<message::LocalizationPose> FromIdl(const msgs::LocalizationPose& m);
msgs::LocalizationPose ToIdl(const message::LocalizationPose& s);

Checked<message::PoseHypotheses> FromIdl(const msgs::PoseHypotheses& m);
msgs::PoseHypotheses ToIdl(const message::PoseHypotheses& s);

}  // namespace stickrep::convert
