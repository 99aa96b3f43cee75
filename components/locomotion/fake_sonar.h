#pragma once

// A sonar ring against line segments for the locomotion tests, independent of the
// estimator's closed form. Hallway frame: x along the axis, y to the left.

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "common/units.h"
#include "locomotion/hallway_follower.h"

namespace stickrep::locomotion::fake {

struct Point {
  double x, y;
};
struct Segment {
  Point a, b;
};

inline double Cross(double ax, double ay, double bx, double by) { return ax * by - ay * bx; }

// A sonar ring against line segments, independent of the estimator's closed form: each
// transducer reports the distance to the nearest segment point inside its cone (§5.4.1),
// found by clipping every segment to the cone's wedge. Hallway frame: x along the axis, y
// to the left; the base at (x, y) with heading psi.
inline std::vector<SonarRange> Scan(const std::vector<Segment>& walls, double x_in,
                                    double y_in, double psi_rad,
                                    const HallwayFollowerConfig& c = {}) {
  std::vector<SonarRange> scan(c.sensor_count);
  const double h = DegToRad(c.cone_deg) / 2.0;
  for (int k = 0; k < c.sensor_count; ++k) {
    const double b = psi_rad + SensorBearingRad(k, c);
    const Point p{x_in + c.head_radius_in * std::cos(b), y_in + c.head_radius_in * std::sin(b)};
    const double lo_x = std::cos(b - h), lo_y = std::sin(b - h);
    const double hi_x = std::cos(b + h), hi_y = std::sin(b + h);
    double best = std::numeric_limits<double>::infinity();
    for (const Segment& s : walls) {
      // P(t) = a + t (b - a); inside the wedge: cross(lo, P - p) >= 0, cross(P - p, hi) >= 0.
      const double ax = s.a.x - p.x, ay = s.a.y - p.y;
      const double dx = s.b.x - s.a.x, dy = s.b.y - s.a.y;
      double t0 = 0.0, t1 = 1.0;
      auto clip = [&](double c0, double c1) {  // c0 + c1 t >= 0
        if (std::abs(c1) < 1e-12) {
          if (c0 < 0.0) t0 = 2.0, t1 = -1.0;
        } else if (c1 > 0.0) {
          t0 = std::max(t0, -c0 / c1);
        } else {
          t1 = std::min(t1, -c0 / c1);
        }
      };
      clip(Cross(lo_x, lo_y, ax, ay), Cross(lo_x, lo_y, dx, dy));
      clip(Cross(ax, ay, hi_x, hi_y), Cross(dx, dy, hi_x, hi_y));
      if (t0 > t1) continue;
      const double len2 = dx * dx + dy * dy;
      const double t = std::clamp(-(ax * dx + ay * dy) / len2, t0, t1);
      best = std::min(best, std::hypot(ax + t * dx, ay + t * dy));
    }
    if (best >= 12.0 && best <= 420.0) scan[k] = {best, true};
  }
  return scan;
}

// A straight 96 in hallway from x = -1000 to x = 1000 in.
inline std::vector<Segment> Hallway(double half_width_in = 48.0) {
  return {{{-1000, half_width_in}, {1000, half_width_in}},
          {{-1000, -half_width_in}, {1000, -half_width_in}}};
}

}  // namespace stickrep::locomotion::fake
