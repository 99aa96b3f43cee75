#pragma once

// A sample kept as its serialized CDR payload (encapsulation header included), for the
// tools that carry samples without looking inside: the recorder, the replayer and the
// console. The DDS type is named as the real type, so it matches the real writers and
// readers of a topic; keys are computed by the real type's support class.

#include <fastdds/dds/topic/TopicDataType.hpp>

#include <cstdint>
#include <memory>
#include <vector>

namespace stickrep::runtime {

struct RawSample {
  std::vector<std::uint8_t> data;
};

class RawPubSubType : public eprosima::fastdds::dds::TopicDataType {
 public:
  using type = RawSample;
  // Takes the real type's support class: its name, size bound and key.
  explicit RawPubSubType(std::unique_ptr<eprosima::fastdds::dds::TopicDataType> real);

  bool serialize(void* data, eprosima::fastrtps::rtps::SerializedPayload_t* payload) override;
  bool deserialize(eprosima::fastrtps::rtps::SerializedPayload_t* payload, void* data) override;
  std::function<uint32_t()> getSerializedSizeProvider(void* data) override;
  void* createData() override;
  void deleteData(void* data) override;
  bool getKey(void* data, eprosima::fastrtps::rtps::InstanceHandle_t* handle,
              bool force_md5) override;

 private:
  std::unique_ptr<eprosima::fastdds::dds::TopicDataType> real_;
};

}  // namespace stickrep::runtime
