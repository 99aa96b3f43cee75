#pragma once

#include "common.h"
#include "messages/messages.h"

namespace stickrep::convert {

inline message::Header FromIdl(const msgs::SampleHeader& h) {
  return {h.stamp_ns(), h.sequence_number()};
}
inline msgs::SampleHeader ToIdl(const message::Header& h) {
  msgs::SampleHeader m;
  m.stamp_ns(h.stamp_ns);
  m.sequence_number(h.sequence);
  return m;
}

}  // namespace stickrep::convert
