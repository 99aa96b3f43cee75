#include "convert/localization_convert.h"

#include "convert/header.h"

namespace stickrep::convert {

static_assert(static_cast<int>(msgs::LOCALIZATION_LOST) ==
              static_cast<int>(message::LocalizationStatus::kLost));

namespace {

message::PoseHypothesis FromIdl(const msgs::PoseHypothesis& m) {
  return {m.ring_id(),      static_cast<int>(m.edge_index()), m.forward(), m.offset_in(),
          m.pose().x_in(), m.pose().y_in(), m.pose().heading_rad(), m.probability()};
}

msgs::PoseHypothesis ToIdl(const message::PoseHypothesis& s) {
  msgs::PoseHypothesis m;
  m.ring_id(s.ring_id);
  m.edge_index(static_cast<uint32_t>(s.edge_index));
  m.forward(s.forward);
  m.offset_in(s.offset_in);
  m.pose().x_in(s.x_in);
  m.pose().y_in(s.y_in);
  m.pose().heading_rad(s.heading_rad);
  m.probability(s.probability);
  return m;
}

}  // namespace

Checked<message::LocalizationPose> FromIdl(const msgs::LocalizationPose& m) {
  const auto status = EnumFrom(m.status(), message::LocalizationStatus::kLost);
  if (!status) return Checked<message::LocalizationPose>::Refused("a status out of range");
  message::LocalizationPose s;
  s.header = FromIdl(m.header());
  s.status = *status;
  s.candidate_count = static_cast<int>(m.candidate_count());
  s.best = FromIdl(m.best());
  s.confidence = m.confidence();
  s.edges_sensed = static_cast<int>(m.edges_sensed());
  s.message = m.message();
  return Checked<message::LocalizationPose>::Ok(std::move(s));
}

msgs::LocalizationPose ToIdl(const message::LocalizationPose& s) {
  msgs::LocalizationPose m;
  m.header(ToIdl(s.header));
  m.status(static_cast<msgs::LocalizationStatus>(s.status));
  m.candidate_count(static_cast<uint32_t>(s.candidate_count));
  m.best(ToIdl(s.best));
  m.confidence(s.confidence);
  m.edges_sensed(static_cast<uint32_t>(s.edges_sensed));
  m.message(s.message);
  return m;
}

Checked<message::PoseHypotheses> FromIdl(const msgs::PoseHypotheses& m) {
  message::PoseHypotheses s;
  s.header = FromIdl(m.header());
  for (const msgs::PoseHypothesis& h : m.hypotheses()) s.hypotheses.push_back(FromIdl(h));
  return Checked<message::PoseHypotheses>::Ok(std::move(s));
}

msgs::PoseHypotheses ToIdl(const message::PoseHypotheses& s) {
  msgs::PoseHypotheses m;
  m.header(ToIdl(s.header));
  for (const message::PoseHypothesis& h : s.hypotheses) m.hypotheses().push_back(ToIdl(h));
  return m;
}

}  // namespace stickrep::convert
