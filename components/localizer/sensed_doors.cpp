#include "localizer/sensed_doors.h"

namespace stickrep::localizer {

map::DoorClass ToMapDoorClass(sensing::DoorClass c) {
  switch (c) {
    case sensing::DoorClass::kDoor30: return map::DoorClass::k30;
    case sensing::DoorClass::kDoor32: return map::DoorClass::k32;
    case sensing::DoorClass::kDoor36: return map::DoorClass::k36;
    case sensing::DoorClass::kDoor40: return map::DoorClass::k40;
    case sensing::DoorClass::kDouble30: return map::DoorClass::k30_30;
    case sensing::DoorClass::kDouble36: return map::DoorClass::k36_36;
  }
  return map::DoorClass::k36;
}

std::optional<map::DoorClass> SensedDoorClass(double width_in) {
  static const std::vector<sensing::ClassBoundary> regions = sensing::DefaultBoundaries();
  const std::optional<sensing::DoorClass> c = sensing::ClassifyWidth(regions, width_in);
  if (!c) return std::nullopt;
  return ToMapDoorClass(*c);
}

}  // namespace stickrep::localizer
