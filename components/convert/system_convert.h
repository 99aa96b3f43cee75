#pragma once

// system.idl: the processes' status (heartbeats).

#include "convert/checked.h"
#include "messages/messages.h"
#include "system.h"

namespace stickrep::convert {

// Refused: a state beyond the enum.
Checked<message::ComponentStatus> FromIdl(const msgs::ComponentStatus& m);
msgs::ComponentStatus ToIdl(const message::ComponentStatus& s);

}  // namespace stickrep::convert
