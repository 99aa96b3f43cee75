#include "sensing/door_classifier.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "common/units.h"

namespace stickrep::sensing {

std::vector<ClassBoundary> Table41Boundaries() {
  return {{DoorClass::k32, 29.1, 33.5},
          {DoorClass::k36, 33.5, 38.8},
          {DoorClass::k40, 38.8, 42.7},
          {DoorClass::k30_30, 56.4, 64.0},
          {DoorClass::k36_36, 67.9, 76.3}};
}

std::vector<ClassBoundary> DefaultBoundaries() {
  // door30 from DeriveBayesBoundaries(BayesModel{}) rounded to 0.1 in (the derivation is
  // printed by `stickrep-sensing report`; a test checks these stay in step with it).
  constexpr double kDoor30Low = 28.5;
  constexpr double kDoor30High = 31.4;
  std::vector<ClassBoundary> out = {{DoorClass::k30, kDoor30Low, kDoor30High}};
  for (ClassBoundary b : Table41Boundaries()) {
    if (b.door_class == DoorClass::k32) b.low_in = kDoor30High;
    out.push_back(b);
  }
  return out;
}

std::optional<DoorClass> ClassifyWidth(const std::vector<ClassBoundary>& regions, double width_in) {
  if (!std::isfinite(width_in)) return std::nullopt;
  for (const ClassBoundary& b : regions) {
    if (width_in >= b.low_in && width_in < b.high_in) return b.door_class;
  }
  return std::nullopt;
}

namespace {

struct WeightedClass {
  DoorClass c;
  double weight;  // prior (unnormalised)
};

double LogWeightedDensity(const WeightedClass& k, double sigma_rel, double w) {
  const double mu = NominalWidthIn(k.c);
  const double sigma = sigma_rel * mu;
  const double z = (w - mu) / sigma;
  return std::log(k.weight) - std::log(sigma * std::sqrt(2.0 * kPi)) - 0.5 * z * z;
}

// Finds where f changes sign in [a, b] (f(a), f(b) of opposite sign) by bisection.
template <typename F>
double Bisect(F f, double a, double b) {
  double fa = f(a);
  for (int i = 0; i < 200; ++i) {
    const double m = 0.5 * (a + b);
    const double fm = f(m);
    if ((fm > 0) == (fa > 0)) {
      a = m;
      fa = fm;
    } else {
      b = m;
    }
  }
  return 0.5 * (a + b);
}

}  // namespace

std::vector<ClassBoundary> DeriveBayesBoundaries(const BayesModel& m) {
  const std::array<WeightedClass, 6> classes = {{{DoorClass::k30, m.prior_door30},
                                                 {DoorClass::k32, m.prior_door32},
                                                 {DoorClass::k36, m.prior_door36},
                                                 {DoorClass::k40, m.prior_door40},
                                                 {DoorClass::k30_30, m.prior_double30},
                                                 {DoorClass::k36_36, m.prior_double36}}};
  double door_total = 0;
  for (const auto& k : classes) door_total += k.weight;
  // Clutter weight on the same scale as the door counts: fraction/(1-fraction) of them,
  // spread uniformly over its interval.
  const double clutter_weight = door_total * m.clutter_fraction / (1.0 - m.clutter_fraction);
  const double log_clutter =
      std::log(clutter_weight) - std::log(m.clutter_high_in - m.clutter_low_in);

  // The Bayes decision at w: the class with the largest weighted density, or clutter.
  auto decide = [&](double w) -> int {
    int best = -1;
    double best_log = log_clutter;
    for (int i = 0; i < static_cast<int>(classes.size()); ++i) {
      const double l = LogWeightedDensity(classes[i], m.sigma_rel, w);
      if (l > best_log) {
        best_log = l;
        best = i;
      }
    }
    return best;
  };

  // Scan at 0.05 in (the abscissa granularity of §4.1.2) and refine each change by bisection.
  std::vector<ClassBoundary> out;
  const double step = 0.05;
  int current = decide(m.clutter_low_in);
  double start = m.clutter_low_in;
  for (double w = m.clutter_low_in + step; w <= m.clutter_high_in; w += step) {
    const int d = decide(w);
    if (d == current) continue;
    const int before = current;
    const double edge =
        Bisect([&](double x) { return decide(x) == before ? 1.0 : -1.0; }, w - step, w);
    if (before >= 0) out.push_back({classes[before].c, start, edge});
    current = d;
    start = edge;
  }
  if (current >= 0) out.push_back({classes[current].c, start, m.clutter_high_in});
  return out;
}

}  // namespace stickrep::sensing

namespace stickrep::sensing {

double FitSigmaToTable41(BayesModel model) {
  model.prior_door30 = 0.0;  // Table 4.1 was derived without a door30 class
  auto cost = [&](double sigma_rel) {
    model.sigma_rel = sigma_rel;
    double c32_36 = 0.0, c36_40 = 0.0;
    bool have_a = false, have_b = false;
    for (const ClassBoundary& b : DeriveBayesBoundaries(model)) {
      if (b.door_class == DoorClass::k36) {
        c32_36 = b.low_in;
        c36_40 = b.high_in;
        have_a = have_b = true;
      }
    }
    if (!have_a || !have_b) return 1e9;
    return (c32_36 - 33.5) * (c32_36 - 33.5) + (c36_40 - 38.8) * (c36_40 - 38.8);
  };
  // Golden-section search over 0.5 % .. 8 %.
  double a = 0.005, b = 0.08;
  const double g = (std::sqrt(5.0) - 1.0) / 2.0;
  double x1 = b - g * (b - a), x2 = a + g * (b - a);
  double f1 = cost(x1), f2 = cost(x2);
  for (int i = 0; i < 60; ++i) {
    if (f1 < f2) {
      b = x2;
      x2 = x1;
      f2 = f1;
      x1 = b - g * (b - a);
      f1 = cost(x1);
    } else {
      a = x1;
      x1 = x2;
      f1 = f2;
      x2 = a + g * (b - a);
      f2 = cost(x2);
    }
  }
  return 0.5 * (a + b);
}

}  // namespace stickrep::sensing
