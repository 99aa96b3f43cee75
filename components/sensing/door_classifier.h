#pragma once

#include <optional>
#include <string>
#include <vector>

#include "stickrep/map.h"

namespace stickrep::sensing {

// The legal door widths of the domain (§4.1.2, §6.1; SPEC §1): the map's door classes, one
// definition for the map, the sensors, the messages and the localizer.
using DoorClass = map::DoorClass;
inline const char* ToString(DoorClass c) { return map::DoorClassName(c); }  // "30" … "36/36"
inline double NominalWidthIn(DoorClass c) { return map::DoorClassWidthIn(c); }  // 30 … 72

// One decision region of the Bayes rule: widths in [low_in, high_in) are this class.
struct ClassBoundary {
  DoorClass door_class;
  double low_in;
  double high_in;
};

// Table 4.1 exactly as printed: 32, 36, 40, 30/30 and 36/36.
std::vector<ClassBoundary> Table41Boundaries();

// Table 4.1 plus door30, whose region is derived in the Bayes manner (see DeriveBayes-
// Boundaries and docs/sensing.md): door30 = [derived low, derived 30|32 boundary) and the
// door32 low boundary moves up to that 30|32 boundary.
std::vector<ClassBoundary> DefaultBoundaries();

// Classifies a measured ribbon width against `regions`; nullopt outside every region (the
// candidate is rejected, §4.1.2). NaN is rejected too.
std::optional<DoorClass> ClassifyWidth(const std::vector<ClassBoundary>& regions, double width_in);

// The measurement-error model behind a Bayes derivation of the boundaries.
//
// Class-conditional density of a measured width w for a door of nominal width c: normal with
// mean c and standard deviation sigma_rel * c (width error scales with the width because
// the geometry scales with range). Priors: door counts of Table 6.8 (30: 22, 32: 4, 36: 412,
// 40: 22; the double doors are not in the census). Candidates that are not doors
// (false positives, 15.91 % of Table 6.10) have a uniform width density over
// [clutter_low_in, clutter_high_in]. Each boundary is where the two neighbouring weighted
// densities (or a door's and the clutter's) are equal.
struct BayesModel {
  // Fitted to Table 4.1's interior boundaries by FitSigmaToTable41() (rounded); the report
  // prints the fit.
  double sigma_rel = 0.0227;
  double prior_door30 = 22;
  double prior_door32 = 4;
  double prior_door36 = 412;
  double prior_door40 = 22;
  double prior_double30 = 4;  // not in Table 6.8: the smallest census count (door32)
  double prior_double36 = 4;
  double clutter_fraction = 0.1591;  // Table 6.10 false positives
  double clutter_low_in = 12.0;
  double clutter_high_in = 96.0;
};

// Bayes decision regions under `model`, ordered by width. A class that is never the most
// probable decision (with the census priors: the double doors) has no region.
std::vector<ClassBoundary> DeriveBayesBoundaries(const BayesModel& model);

// The relative width error sigma_rel whose Bayes boundaries best reproduce Table 4.1's
// interior boundaries 32|36 (33.5 in) and 36|40 (38.8 in), least squares, with the other
// parameters of `model`. door30 is left out of the fit (Table 4.1 has no door30).
double FitSigmaToTable41(BayesModel model);

}  // namespace stickrep::sensing
