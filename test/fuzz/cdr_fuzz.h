#pragma once

// The path of every sample a StickRep node reads, on arbitrary bytes: the type's support
// class as the endpoints register it (runtime/guarded_type.h) deserializes the CDR payload,
// as the DataReader does before handing the sample over, then convert::FromIdl checks it
// (runtime/component_node.h, Feed). A payload is refused by deserialize returning false or
// by FromIdl's reason; an exception out of deserialize, a crash or a sanitizer report is a
// bug, and so is a sample that FromIdl accepts but refuses once converted back (ToIdl).
//
// A family's target takes one byte for the type (modulo the family's size), then the
// payload. With STICKREP_FUZZ_WRITE_SEEDS=DIR it writes one seed per type instead (a
// valid sample of the type, serialized) and exits: the seed corpus.

#include <fastdds/rtps/common/SerializedPayload.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "convert/convert.h"
#include "runtime/guarded_type.h"
#include "yaml_fuzz.h"

namespace stickrep::fuzz {

using Bytes = std::vector<std::uint8_t>;

// Deserializes `size` bytes as the support class does; false when it refuses them.
template <typename PubSubType>
bool Deserialize(const std::uint8_t* data, std::size_t size, typename PubSubType::type* m) {
  eprosima::fastrtps::rtps::SerializedPayload_t payload(static_cast<std::uint32_t>(size));
  if (size > 0) std::memcpy(payload.data, data, size);
  payload.length = static_cast<std::uint32_t>(size);
  runtime::GuardedPubSubType<PubSubType> support;
  return support.deserialize(&payload, m);
}

// The payload a writer sends for `m`.
template <typename PubSubType>
Bytes Serialize(typename PubSubType::type m) {
  PubSubType support;
  eprosima::fastrtps::rtps::SerializedPayload_t payload(support.getSerializedSizeProvider(&m)());
  if (!support.serialize(&m, &payload)) FuzzFail("a seed sample does not serialize");
  return Bytes(payload.data, payload.data + payload.length);
}

// Deserialize, then FromIdl and the round trip through ToIdl.
template <typename PubSubType>
void FeedChecked(const std::uint8_t* data, std::size_t size) {
  typename PubSubType::type m;
  if (!Deserialize<PubSubType>(data, size, &m)) return;
  const auto checked = convert::FromIdl(m);
  if (!checked.value) {
    if (checked.reason.empty()) FuzzFail("FromIdl refused a sample without a reason");
    return;
  }
  const auto again = convert::FromIdl(convert::ToIdl(*checked.value));
  if (!again.value) {
    FuzzFail("FromIdl accepted a sample, then refused it converted back: " + again.reason);
  }
}

// One IDL type of a family: how its payloads are read, and its seed.
struct CdrType {
  const char* name;
  void (*feed)(const std::uint8_t* data, std::size_t size);
  Bytes (*seed)();
};

// Writes one seed file per type into $STICKREP_FUZZ_WRITE_SEEDS and exits, if it is set.
inline void WriteSeedsIfAsked(const std::vector<CdrType>& types) {
  const char* dir = std::getenv("STICKREP_FUZZ_WRITE_SEEDS");
  if (dir == nullptr) return;
  for (std::size_t i = 0; i < types.size(); ++i) {
    Bytes bytes = types[i].seed();
    bytes.insert(bytes.begin(), static_cast<std::uint8_t>(i));
    std::ofstream out(std::string(dir) + "/" + types[i].name + ".cdr", std::ios::binary);
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<long>(bytes.size()));
    if (!out) FuzzFail(std::string("cannot write the seed of ") + types[i].name);
  }
  std::exit(0);
}

// The first byte picks the type, the rest is its payload.
inline void FeedFamily(const std::vector<CdrType>& types, const std::uint8_t* data,
                       std::size_t size) {
  if (size == 0) return;
  types[data[0] % types.size()].feed(data + 1, size - 1);
}

}  // namespace stickrep::fuzz

// A family's target: the table of its types, the seeds, and the libFuzzer entry points.
#define STICKREP_CDR_FUZZ_TARGET(types)                                        \
  extern "C" int LLVMFuzzerInitialize(int*, char***) {                          \
    stickrep::fuzz::WriteSeedsIfAsked(types());                                 \
    return 0;                                                                   \
  }                                                                             \
  extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) { \
    static const std::vector<stickrep::fuzz::CdrType> table = types();         \
    stickrep::fuzz::FeedFamily(table, data, size);                              \
    return 0;                                                                   \
  }
