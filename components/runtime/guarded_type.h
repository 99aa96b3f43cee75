#pragma once

// A fastddsgen support class whose deserialize refuses a malformed payload instead of
// throwing. The generated deserialize catches only Fast CDR's NotEnoughMemoryException: a
// payload with a bad encapsulation header, or a boolean other than 0 or 1, throws
// BadParamException out of DataReader::take_next_sample, out of the reader's Drain on the
// executor thread, and ends the process. Refused here, DDS drops the sample ("wrong data")
// and the reader goes on with the next one. Every typed endpoint registers its type in this
// form (endpoint.h); the fuzz targets read payloads through it (test/fuzz/cdr_fuzz.h).

#include <fastdds/rtps/common/SerializedPayload.h>

#include <exception>

namespace stickrep::runtime {

template <typename PubSubType>
class GuardedPubSubType : public PubSubType {
 public:
  bool deserialize(eprosima::fastrtps::rtps::SerializedPayload_t* payload, void* data) override {
    try {
      return PubSubType::deserialize(payload, data);
    } catch (const std::exception&) {
      // Fast CDR's exceptions (bad parameter, not enough memory), and std::bad_alloc or
      // std::length_error for a sequence length no buffer can hold.
      return false;
    }
  }
};

}  // namespace stickrep::runtime
