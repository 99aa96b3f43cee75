#pragma once

// sensors.idl: sonar echoes and scans, camera images.

#include "convert/checked.h"
#include "messages/messages.h"
#include "sensors.h"

namespace stickrep::convert {

Checked<message::SonarEcho> FromIdl(const msgs::SonarEcho& m);
msgs::SonarEcho ToIdl(const message::SonarEcho& s);

// Refused: a reading with an echo (valid or outside the footprint) that is not a positive,
// finite range, or a reading state beyond the enum.
Checked<message::SonarScan> FromIdl(const msgs::SonarScan& m);
msgs::SonarScan ToIdl(const message::SonarScan& s);

// Not checked here: the frame's shape is the camera component's check (camera/frame_check.h).
Checked<message::Image> FromIdl(const msgs::Image& m);
msgs::Image ToIdl(const message::Image& s);

}  // namespace stickrep::convert
