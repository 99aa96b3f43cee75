#pragma once

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <optional>
#include <random>
#include <vector>

#include "world/scene.h"
#include "world/world.h"

namespace stickrep::world {

// The monochrome camera on the robot head. Defaults follow configs/robot.yaml
// (`robot.camera`) where the text gives a value; the rest are documented guesses.
struct CameraModel {
  double fov_deg = 55.817;  // horizontal field of view, §5.4
  int width_px = 512;       // not in the text; configs/robot.yaml assumes 512 x 480
  int height_px = 480;
  // Optical axis relative to the robot heading. The camera looks sideways, orthogonal to
  // travel (§6.4.2 navigation envelope); +90° looks to the robot's left, toward the feature
  // wall of MakeStraightHallway.
  double mount_yaw_deg = 90.0;
  double mount_forward_in = 0.0;  // optical centre ahead of the head centre (robot.yaml: 0)
  double mount_left_in = 0.0;
  double height_in = 40.0;  // optical centre above the floor; not in the text
  // Roll misalignment about the optical axis; the detector must tolerate up to 10° (§4.1.1).
  // Positive roll turns the scene counter-clockwise in the image.
  double roll_deg = 0.0;
  // Pitch misalignment: positive tilts the optical axis down toward the floor. The text
  // assumes a level camera (C1, §5.1); real mounts are off by a degree or more.
  double pitch_deg = 0.0;
  // Radial distortion x_d = x_u (1 + k1 r_u^2) in normalised coordinates; k1 > 0 is the
  // pincushion of the 6 mm lens (§4.1.1). 0.10 makes a vertical edge at the side of the
  // image bow by about 6 px between the centre row and the top row (0.1 * 0.53 * 0.50^2 *
  // 484 px), the text's "edges one pixel wide ... bow across seven pixels at a viewing
  // range of six feet".
  double k1 = 0.10;

  // Focal length in pixels: the image edge (column -0.5 or width - 0.5) lies at FOV/2 in
  // the undistorted pinhole image.
  double focal_px() const;
  double cx_px() const { return (width_px - 1) / 2.0; }  // pixel centres at integers
  double cy_px() const { return (height_px - 1) / 2.0; }
};

// Lighting and sensor noise of one frame: out = gain * radiance * (1 + gradient * (u/W -
// 1/2)) * (1 + vertical_gradient * (v/H - 1/2)) * (1 - vignetting * r^2) + offset +
// N(0, noise_stddev), clipped to 0..255, with r the distance from the image centre over the
// half diagonal. The gradients model uneven hallway lighting, the vignetting a webcam lens.
struct Illumination {
  double gain = 1.0;
  double offset = 0.0;
  double gradient = 0.0;
  double vertical_gradient = 0.0;
  double vignetting = 0.0;
  double noise_stddev = 2.0;  // grey levels
};

// Renderer quality knobs.
struct RenderOptions {
  // Horizontal supersampling: vertical edges fall between pixels, and their sub-pixel
  // position is what the detector's centre of mass recovers (§4.1.1).
  int supersample = 4;
  double max_range_in = 1200.0;  // 100 ft; nothing farther is drawn
};

// A jamb (one side of a door opening) as seen in a frame.
struct JambTruth {
  int door_index = -1;
  bool image_left = false;     // the jamb nearer column 0 of the pair
  double column_px = 0.0;      // where the jamb's vertical edge crosses the centre row
  double depth_in = 0.0;       // along the optical axis
  Eigen::Vector2d point_W_in;  // the jamb edge in the building plane
};

// A door at least partly in view.
struct DoorTruth {
  int door_index = -1;
  std::optional<int> class_in;  // legal class of its width, if any
  double width_in = 0.0;
  DoorState state = DoorState::kClosed;
  bool both_jambs_visible = false;
  double left_column_px = 0.0;  // centre-row columns of its two jambs, left < right
  double right_column_px = 0.0;
};

// Ground truth of one frame.
struct FrameTruth {
  Pose2d X_WR;                   // robot
  Pose2d X_WC;                   // camera: position and optical axis heading
  double axis_range_in = 0.0;    // camera to the first surface along the optical axis; NaN if none
  std::vector<JambTruth> jambs;  // every jamb in the frame and not hidden
  std::vector<DoorTruth> doors;
};

struct RenderedFrame {
  cv::Mat image;  // CV_8UC1, height_px x width_px
  FrameTruth truth;
};

// Renders mono8 camera frames of a scene with ground truth. The geometry is cast column by
// column into an ideal (pinhole, no roll) canvas supersampled horizontally, downsampled by
// area, then warped by one precomputed remap for roll and pincushion; illumination and
// noise come last. Construction precomputes the warp, so reuse one renderer per camera.
class CameraRenderer {
 public:
  // Throws std::invalid_argument on a bad model (FOV outside (1°, 170°), non-positive
  // size, supersample < 1, |roll| >= 45°, |pitch| >= 30°, k1 outside [-0.3, 0.5]).
  explicit CameraRenderer(CameraModel model, RenderOptions options = {});

  const CameraModel& model() const { return model_; }

  // Pose of the camera in the world for a robot at X_WR (theta = optical axis heading).
  Pose2d CameraPose(const Pose2d& X_WR) const;

  // Final (distorted, rolled) pixel of a world point, or nullopt behind the camera.
  std::optional<Eigen::Vector2d> Project(const Pose2d& X_WC, const Eigen::Vector3d& p_W_in) const;

  // Column where the vertical line through p_W_in crosses the centre row, or nullopt when
  // the line is behind the camera.
  std::optional<double> ColumnAtCenterRow(const Pose2d& X_WC, const Eigen::Vector2d& p_W_in) const;
  // The same, with the height (in) of the line's point seen there.
  struct CenterRowCrossing {
    double column_px = 0.0;
    double height_in = 0.0;
  };
  std::optional<CenterRowCrossing> CrossCenterRow(const Pose2d& X_WC,
                                                  const Eigen::Vector2d& p_W_in) const;

  RenderedFrame Render(const Scene& scene, const Pose2d& X_WR, const Illumination& light,
                       std::mt19937_64& rng) const;

  // Ground truth alone (no image).
  FrameTruth Truth(const Scene& scene, const Pose2d& X_WR) const;

 private:
  // The ideal canvas, transposed (one row per supersampled column) so that each column is
  // filled as a few constant runs.
  void RenderCanvas(const Scene& scene, const Pose2d& X_WC, cv::Mat* canvas_t) const;

  CameraModel model_;
  RenderOptions options_;
  double f_px_;
  // Normalised extent of the ideal canvas (covers every output pixel after undoing
  // distortion and roll) and its size at 1x.
  double x_min_ = 0.0, y_min_ = 0.0;
  int canvas_w_ = 0, canvas_h_ = 0;
  cv::Mat map1_, map2_;  // output pixel -> canvas pixel, fixed-point for cv::remap
};

}  // namespace stickrep::world
