#include "convert/perception_convert.h"

#include <cmath>

#include "convert/header.h"

namespace stickrep::convert {

// The IDL enum is the door classes after DOOR_REJECTED, in sensing::DoorClass's order.
static_assert(static_cast<int>(msgs::DOOR_30) == 1 + static_cast<int>(sensing::DoorClass::k30));
static_assert(static_cast<int>(msgs::DOOR_36_36) ==
              1 + static_cast<int>(sensing::DoorClass::k36_36));
static_assert(static_cast<int>(msgs::MARK_POSTER) == static_cast<int>(map::DoorMark::kPoster) &&
              static_cast<int>(msgs::MARK_UNKNOWN) == static_cast<int>(map::DoorMark::kUnknown));

Checked<message::LandmarkObservation> FromIdl(const msgs::LandmarkObservation& m) {
  const long long code = static_cast<long long>(m.door_class());
  if (code < static_cast<long long>(msgs::DOOR_30) ||
      code > static_cast<long long>(msgs::DOOR_36_36)) {
    return Checked<message::LandmarkObservation>::Refused("not a door class");
  }
  if (!std::isfinite(m.width_in()) || m.width_in() <= 0.0 ||
      !std::isfinite(m.odometry_distance_in()) || !std::isfinite(m.center_offset_in())) {
    return Checked<message::LandmarkObservation>::Refused(
        "non-finite or non-positive width or position");
  }
  const long long mark = static_cast<long long>(m.mark());
  if (mark < static_cast<long long>(msgs::MARK_UNKNOWN) ||
      mark > static_cast<long long>(msgs::MARK_POSTER)) {
    return Checked<message::LandmarkObservation>::Refused("not a door mark");
  }
  message::LandmarkObservation s;
  s.header = FromIdl(m.header());
  s.door_class = static_cast<sensing::DoorClass>(code - 1);
  s.width_in = m.width_in();
  s.confidence = m.confidence();
  s.left_jamb_px = m.left_jamb_px();
  s.right_jamb_px = m.right_jamb_px();
  s.range_in = m.range_in();
  s.center_offset_in = m.center_offset_in();
  s.look_angle_rad = m.look_angle_rad();
  s.in_envelope = m.in_envelope();
  s.odometry_distance_in = m.odometry_distance_in();
  s.image_stamp_ns = m.image_stamp_ns();
  s.mark = static_cast<map::DoorMark>(mark);
  return Checked<message::LandmarkObservation>::Ok(s);
}

msgs::LandmarkObservation ToIdl(const message::LandmarkObservation& s) {
  msgs::LandmarkObservation m;
  m.header(ToIdl(s.header));
  m.door_class(static_cast<msgs::DoorClass>(1 + static_cast<int>(s.door_class)));
  m.width_in(s.width_in);
  m.confidence(s.confidence);
  m.left_jamb_px(s.left_jamb_px);
  m.right_jamb_px(s.right_jamb_px);
  m.range_in(s.range_in);
  m.center_offset_in(s.center_offset_in);
  m.look_angle_rad(s.look_angle_rad);
  m.in_envelope(s.in_envelope);
  m.odometry_distance_in(s.odometry_distance_in);
  m.image_stamp_ns(s.image_stamp_ns);
  m.mark(static_cast<msgs::DoorMark>(s.mark));
  return m;
}

}  // namespace stickrep::convert
