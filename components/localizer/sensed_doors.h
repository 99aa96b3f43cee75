#pragma once

// Door classes as the robot's detector reports them, in map terms: the class a measured
// door width falls in under the detector's decision regions (sensing::DefaultBoundaries,
// Table 4.1), so that a map door of measured width (map format 2) is matched as the class
// the robot will see it as, or as wall when the detector rejects that width.

#include <optional>

#include "sensing/door_classifier.h"
#include "stickrep/map.h"

namespace stickrep::localizer {

// The class the detector reports for a door opening of `width_in`; nullopt when it rejects
// the width (no decision region holds it: 44-56 in, over 76 in, under 28.5 in).
std::optional<map::DoorClass> SensedDoorClass(double width_in);

}  // namespace stickrep::localizer
