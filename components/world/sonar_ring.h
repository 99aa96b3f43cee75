#pragma once

#include <optional>
#include <random>
#include <vector>

#include "world/scene.h"
#include "world/world.h"

namespace stickrep::world {

// Geometry of the sonar ring on the robot head. Defaults follow configs/robot.yaml
// (`robot.sonar_ring`) so a caller can fill this from the robot description.
struct SonarRingModel {
  int count = 24;               // §5.3: "the 24 sensors"
  double spacing_deg = 15.0;    // §5.3: sectors of 15°
  double head_radius_in = 7.5;  // not in the text; configs/robot.yaml
  double cone_deg = 23.6;       // §5.4: "the 23.6° sensing cone"
  double min_range_in = 12.0;   // §4.3: useful range 1 to 35 ft
  double max_range_in = 420.0;  // 35 ft
  double height_in = 30.0;      // transducer height above the floor; not in the text
  // Bearing of sensor 0 relative to the robot heading. Sensor 0 is coaxial with the
  // optical axis (constraint C3, §5.1; robot.camera.coaxial_sensor = 0), so this equals the
  // camera mounting yaw; +90° looks to the robot's left.
  double coaxial_yaw_deg = 90.0;
  // Sensor k points (k * spacing_deg) toward the image's right, i.e. clockwise seen from
  // above (configs/robot.yaml: "sensor k looks (k * 15°) toward the image's right").
};

// What one transducer returned.
struct SonarReading {
  bool valid = false;          // false: no echo inside [min_range_in, max_range_in]
  double range_in = 0.0;       // reported range from the transducer face (after the model)
  double true_range_in = 0.0;  // nearest point in the cone, before the error model
  double incidence_rad = 0.0;  // acoustic axis vs surface normal at that point (phi, §4.3)
  SurfaceType surface = SurfaceType::kConcrete;
  double bearing_rad = 0.0;  // sensor axis in the world frame
};

// Hook for the surface- and incidence-dependent range error of §4.3 (Tables 4.2, 4.3) and
// the composite model of §5.4.2. The sensing library supplies the measured model; the
// world only needs this interface. Returns the range the sensor reports, or nullopt when
// the echo is lost (the "++" entries of Tables 4.2/4.3).
class SonarErrorModel {
 public:
  virtual ~SonarErrorModel() = default;
  virtual std::optional<double> Apply(double true_range_in, SurfaceType surface,
                                      double incidence_rad, std::mt19937_64& rng) const = 0;
};

// The default: a perfect transducer that reports the nearest point in its cone.
class ExactSonarErrorModel final : public SonarErrorModel {
 public:
  std::optional<double> Apply(double true_range_in, SurfaceType, double,
                              std::mt19937_64&) const override {
    return true_range_in;
  }
};

// Simulates the 24-transducer ring against a scene.
//
// Model (§5.4, Figure 5.2 and the three cases of §5.4.1): "its range value is directly
// related to the sensor's distance from the nearest object within its sensing cone". Each
// transducer sits on the head perimeter at radius head_radius_in along its bearing and
// reports the distance to the nearest acoustic surface point inside its cone (a wedge of
// cone_deg in the building plane). Against a plane this is the perpendicular distance when
// the normal lies inside the cone (Case 1) and the range along the cone limit nearest the
// normal otherwise (Cases 2 and 3) — the same geometry the text derives. It is computed
// exactly (segment clipping), not by sampling rays. The incidence angle handed to the error
// model is between the sensor axis and the normal of the surface that returned the echo.
class SonarRingSimulator {
 public:
  explicit SonarRingSimulator(SonarRingModel model = {});

  const SonarRingModel& model() const { return model_; }

  // Bearing of sensor k in the world frame for a robot at X_WR.
  double SensorBearing(const Pose2d& X_WR, int k) const;

  // One reading per transducer, sensor 0 first.
  std::vector<SonarReading> Sense(const Scene& scene, const Pose2d& X_WR,
                                  const SonarErrorModel& error_model, std::mt19937_64& rng) const;

  // The same with the exact model (no randomness used).
  std::vector<SonarReading> SenseExact(const Scene& scene, const Pose2d& X_WR) const;

 private:
  SonarRingModel model_;
};

}  // namespace stickrep::world
