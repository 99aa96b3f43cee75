#include "convert/sensors_convert.h"

#include <cmath>

#include "convert/header.h"

namespace stickrep::convert {

Checked<message::SonarEcho> FromIdl(const msgs::SonarEcho& m) {
  message::SonarEcho s;
  s.header = FromIdl(m.header());
  for (int k = 0; k < sonar::kRingSize; ++k) s.range_in[k] = m.range_in()[k];
  return Checked<message::SonarEcho>::Ok(std::move(s));
}

msgs::SonarEcho ToIdl(const message::SonarEcho& s) {
  msgs::SonarEcho m;
  m.header(ToIdl(s.header));
  for (int k = 0; k < sonar::kRingSize; ++k) m.range_in()[k] = s.range_in[k];
  return m;
}

Checked<message::SonarScan> FromIdl(const msgs::SonarScan& m) {
  message::SonarScan s;
  s.header = FromIdl(m.header());
  for (int k = 0; k < sonar::kRingSize; ++k) {
    const auto state = EnumFrom(m.reading_state()[k], sonar::ReadingState::kMalformed);
    if (!state) return Checked<message::SonarScan>::Refused("a reading state out of range");
    const float r = m.range_in()[k];
    const bool echo =
        *state == sonar::ReadingState::kValid || *state == sonar::ReadingState::kOutsideFootprint;
    if (echo && (!std::isfinite(r) || r <= 0.0f)) {
      return Checked<message::SonarScan>::Refused("a reading with an echo is not a positive range");
    }
    s.range_in[k] = r;
    s.state[k] = *state;
  }
  s.valid_count = m.valid_count();
  return Checked<message::SonarScan>::Ok(std::move(s));
}

msgs::SonarScan ToIdl(const message::SonarScan& s) {
  msgs::SonarScan m;
  m.header(ToIdl(s.header));
  for (int k = 0; k < sonar::kRingSize; ++k) {
    m.range_in()[k] = s.range_in[k];
    m.reading_state()[k] = static_cast<msgs::SonarReadingState>(s.state[k]);
  }
  m.valid_count(static_cast<uint16_t>(s.valid_count));
  return m;
}

Checked<message::Image> FromIdl(const msgs::Image& m) {
  message::Image s;
  s.header = FromIdl(m.header());
  s.width_px = m.width_px();
  s.height_px = m.height_px();
  s.encoding = m.encoding();
  s.step_bytes = m.step_bytes();
  s.data = m.data();
  return Checked<message::Image>::Ok(std::move(s));
}

msgs::Image ToIdl(const message::Image& s) {
  msgs::Image m;
  m.header(ToIdl(s.header));
  m.width_px(s.width_px);
  m.height_px(s.height_px);
  m.encoding(s.encoding);
  m.step_bytes(s.step_bytes);
  m.data(s.data);
  return m;
}

static_assert(static_cast<int>(msgs::SONAR_MALFORMED) ==
              static_cast<int>(sonar::ReadingState::kMalformed));

}  // namespace stickrep::convert
