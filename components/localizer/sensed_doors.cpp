#include "localizer/sensed_doors.h"

namespace stickrep::localizer {

std::optional<map::DoorClass> SensedDoorClass(double width_in) {
  static const std::vector<sensing::ClassBoundary> regions = sensing::DefaultBoundaries();
  const std::optional<sensing::DoorClass> c = sensing::ClassifyWidth(regions, width_in);
  if (!c) return std::nullopt;
  return *c;
}

}  // namespace stickrep::localizer
