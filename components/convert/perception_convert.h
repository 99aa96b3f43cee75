#pragma once

// perception.idl: classified door observations.

#include "convert/checked.h"
#include "messages/messages.h"
#include "perception.h"

namespace stickrep::convert {

// Refused: DOOR_REJECTED or a class beyond the enum, a non-finite or non-positive width, a
// non-finite position.
Checked<message::LandmarkObservation> FromIdl(const msgs::LandmarkObservation& m);
msgs::LandmarkObservation ToIdl(const message::LandmarkObservation& s);

}  // namespace stickrep::convert
