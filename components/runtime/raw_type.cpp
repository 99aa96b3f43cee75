#include "runtime/raw_type.h"

#include <fastdds/rtps/common/SerializedPayload.h>

#include <cstring>

namespace stickrep::runtime {

namespace rtps = eprosima::fastrtps::rtps;

RawPubSubType::RawPubSubType(std::unique_ptr<eprosima::fastdds::dds::TopicDataType> real)
    : real_(std::move(real)) {
  setName(real_->getName());
  m_typeSize = real_->m_typeSize;
  m_isGetKeyDefined = real_->m_isGetKeyDefined;
  // No type object: endpoints match by type name, as the real ones do.
  auto_fill_type_object(false);
  auto_fill_type_information(false);
}

bool RawPubSubType::serialize(void* data, rtps::SerializedPayload_t* payload) {
  const auto& bytes = static_cast<RawSample*>(data)->data;
  if (bytes.size() < 4) return false;  // not even the encapsulation header
  if (payload->max_size < bytes.size()) payload->reserve(static_cast<uint32_t>(bytes.size()));
  std::memcpy(payload->data, bytes.data(), bytes.size());
  payload->length = static_cast<uint32_t>(bytes.size());
  // The header's second byte: 0 CDR big endian, 1 little endian (PL_ variants 2, 3).
  payload->encapsulation = (bytes[1] & 1) ? CDR_LE : CDR_BE;
  return true;
}

bool RawPubSubType::deserialize(rtps::SerializedPayload_t* payload, void* data) {
  auto& bytes = static_cast<RawSample*>(data)->data;
  bytes.assign(payload->data, payload->data + payload->length);
  return true;
}

std::function<uint32_t()> RawPubSubType::getSerializedSizeProvider(void* data) {
  return [data] { return static_cast<uint32_t>(static_cast<RawSample*>(data)->data.size()); };
}

void* RawPubSubType::createData() { return new RawSample(); }

void RawPubSubType::deleteData(void* data) { delete static_cast<RawSample*>(data); }

bool RawPubSubType::getKey(void* data, rtps::InstanceHandle_t* handle, bool force_md5) {
  if (!m_isGetKeyDefined) return false;
  // The key fields are inside the payload: decode with the real type and ask it.
  const auto& bytes = static_cast<RawSample*>(data)->data;
  rtps::SerializedPayload_t payload(static_cast<uint32_t>(bytes.size()));
  std::memcpy(payload.data, bytes.data(), bytes.size());
  payload.length = static_cast<uint32_t>(bytes.size());
  void* sample = real_->createData();
  bool ok = false;
  try {
    ok = real_->deserialize(&payload, sample) && real_->getKey(sample, handle, force_md5);
  } catch (const std::exception&) {
    ok = false;
  }
  real_->deleteData(sample);
  return ok;
}

}  // namespace stickrep::runtime
