#pragma once

// base.idl: wheel commands, encoders, motion commands and state, odometry.

#include "base.h"
#include "convert/checked.h"
#include "messages/messages.h"

namespace stickrep::convert {

// Refused: a non-finite wheel speed.
Checked<message::WheelCommand> FromIdl(const msgs::WheelCommand& m);
msgs::WheelCommand ToIdl(const message::WheelCommand& s);

// Refused: a non-finite wheel travel.
Checked<message::EncoderReading> FromIdl(const msgs::EncoderReading& m);
msgs::EncoderReading ToIdl(const message::EncoderReading& s);

// Refused: a mode beyond the enum. A non-finite speed is passed on: locomotion answers it by
// stopping the base, which is more than a drop.
Checked<message::MotionCommand> FromIdl(const msgs::MotionCommand& m);
msgs::MotionCommand ToIdl(const message::MotionCommand& s);

// Refused: a mode or state beyond the enum.
Checked<message::MotionState> FromIdl(const msgs::MotionState& m);
msgs::MotionState ToIdl(const message::MotionState& s);

// Refused: a non-finite distance or heading.
Checked<message::Odometry> FromIdl(const msgs::Odometry& m);
msgs::Odometry ToIdl(const message::Odometry& s);

}  // namespace stickrep::convert
