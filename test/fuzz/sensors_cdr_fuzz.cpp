// sensors.idl as the sonar, camera, landmark, locomotion and localizer processes read it.
// An image FromIdl accepts then goes through the camera's frame check (camera/frame_check.h).
#include "camera/frame_check.h"
#include "cdr_fuzz.h"
#include "sensorsPubSubTypes.h"

namespace {

using namespace stickrep;
using fuzz::Bytes;

message::Header Stamp() { return {1'000'000'000, 7}; }

void FeedImage(const std::uint8_t* data, std::size_t size) {
  msgs::Image m;
  if (!fuzz::Deserialize<msgs::ImagePubSubType>(data, size, &m)) return;
  const auto checked = convert::FromIdl(m);
  if (!checked.value) return;
  const message::Image& i = *checked.value;
  camera::CheckFrame({i.width_px, i.height_px, i.step_bytes, i.encoding, i.data.size()}, 0, 0);
  camera::CheckFrame({i.width_px, i.height_px, i.step_bytes, i.encoding, i.data.size()}, 8, 4);
}

std::vector<fuzz::CdrType> Types() {
  return {
      {"SonarEcho", &fuzz::FeedChecked<msgs::SonarEchoPubSubType>,
       [] {
         message::SonarEcho s{Stamp(), {}};
         for (std::size_t k = 0; k < s.range_in.size(); ++k) s.range_in[k] = 30.0f + k;
         return fuzz::Serialize<msgs::SonarEchoPubSubType>(convert::ToIdl(s));
       }},
      {"SonarScan", &fuzz::FeedChecked<msgs::SonarScanPubSubType>,
       [] {
         message::SonarScan s;
         s.header = Stamp();
         for (std::size_t k = 0; k < s.range_in.size(); ++k) s.range_in[k] = 40.0f + k;
         s.valid_count = static_cast<int>(s.range_in.size());
         return fuzz::Serialize<msgs::SonarScanPubSubType>(convert::ToIdl(s));
       }},
      {"Image", &FeedImage,
       [] {
         message::Image i{Stamp(), 8, 4, "mono8", 8, std::vector<std::uint8_t>(32, 128)};
         return fuzz::Serialize<msgs::ImagePubSubType>(convert::ToIdl(i));
       }},
  };
}

}  // namespace

STICKREP_CDR_FUZZ_TARGET(Types)
