#pragma once

// One table of the StickRep IDL types: for each type name, its Fast DDS support class and its
// JSON form. The console (echo, bw), the recorder and the replayer all look types up here,
// so a type added to the IDL is added once.

#include <fastdds/dds/topic/TopicDataType.hpp>
#include <nlohmann/json.hpp>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace stickrep::console {

struct MessageType {
  std::string name;  // the DDS type name, e.g. "stickrep::msgs::SonarScan"
  std::vector<std::string> topics;  // the StickRep topics that carry it (configs/qos.yaml)
  // A new instance of the fastddsgen support class (the caller owns it).
  std::function<eprosima::fastdds::dds::TopicDataType*()> make_support;
  // A serialized CDR payload (with its encapsulation header) in the console's JSON form.
  // Throws PayloadError when the bytes do not deserialize to this type.
  std::function<nlohmann::json(const std::uint8_t* data, std::size_t size)> decode_json;
};

// A payload that does not deserialize to the type it was recorded as.
class PayloadError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Every StickRep type by name.
const std::map<std::string, MessageType>& MessageTypes();
// The type a StickRep topic carries; nullptr for a topic that is not StickRep's.
const MessageType* TypeOfTopic(const std::string& topic);
// nullptr for a name this build does not know.
const MessageType* FindMessageType(const std::string& name);

}  // namespace stickrep::console
