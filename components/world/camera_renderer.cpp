#include "world/camera_renderer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <string>

#include "common/units.h"

namespace stickrep::world {
namespace {

// Lambert-like shading: a face seen obliquely is a little darker, so an open leaf and the
// wall behind it differ even when painted alike.
constexpr double kAmbientShare = 0.8;

// Gap left around the warped footprint of the output image on the ideal canvas, in pixels,
// so bilinear sampling never reads past the canvas edge.
constexpr int kCanvasMarginPx = 2;

}  // namespace

double CameraModel::focal_px() const {
  return (width_px / 2.0) / std::tan(DegToRad(fov_deg) / 2.0);
}

CameraRenderer::CameraRenderer(CameraModel model, RenderOptions options)
    : model_(model), options_(options) {
  if (!(model_.fov_deg > 1.0 && model_.fov_deg < 170.0) || model_.width_px <= 0 ||
      model_.height_px <= 0 || options_.supersample < 1 || !(std::abs(model_.roll_deg) < 45.0) ||
      !(model_.k1 >= -0.3 && model_.k1 <= 0.5) || !(options_.max_range_in > 0.0) ||
      !(std::abs(model_.pitch_deg) < 30.0)) {
    throw std::invalid_argument(
        "camera: need 1 < fov_deg < 170, positive image size, supersample >= 1, |roll_deg| < "
        "45, |pitch_deg| < 30, -0.3 <= k1 <= 0.5, max_range_in > 0");
  }
  f_px_ = model_.focal_px();
  const int w = model_.width_px;
  const int h = model_.height_px;
  const double roll = DegToRad(model_.roll_deg);
  const double c = std::cos(roll);
  const double s = std::sin(roll);
  const double cp = std::cos(DegToRad(model_.pitch_deg));
  const double sp = std::sin(DegToRad(model_.pitch_deg));

  // Undo distortion (fixed-point iteration; converges fast for |k1| r^2 << 1) and roll for
  // every output pixel: its normalised ideal coordinates.
  cv::Mat ideal_x(h, w, CV_64F);
  cv::Mat ideal_y(h, w, CV_64F);
  double xf_min = std::numeric_limits<double>::infinity();
  double xf_max = -xf_min;
  double yf_min = xf_min;
  double yf_max = -xf_min;
  for (int v = 0; v < h; ++v) {
    for (int u = 0; u < w; ++u) {
      const double xd = (u - model_.cx_px()) / f_px_;
      const double yd = (v - model_.cy_px()) / f_px_;
      double xr = xd;
      double yr = yd;
      for (int it = 0; it < 30; ++it) {
        const double scale = 1.0 + model_.k1 * (xr * xr + yr * yr);
        xr = xd / scale;
        yr = yd / scale;
      }
      // Undo roll, then pitch: the ray (x_c, y_c, 1) of the tilted camera in the level
      // camera's frame.
      const double x_c = c * xr - s * yr;
      const double y_c = s * xr + c * yr;
      const double z_l = cp - y_c * sp;
      const double x = x_c / z_l;
      const double y = (y_c * cp + sp) / z_l;
      ideal_x.at<double>(v, u) = x;
      ideal_y.at<double>(v, u) = y;
      xf_min = std::min(xf_min, x * f_px_);
      xf_max = std::max(xf_max, x * f_px_);
      yf_min = std::min(yf_min, y * f_px_);
      yf_max = std::max(yf_max, y * f_px_);
    }
  }
  // Align the canvas grid with the output grid (integer margins) so that without roll and
  // distortion the warp is an exact copy, not an interpolation.
  const double left_edge = -w / 2.0;  // x * f of the left side of column 0
  const double top_edge = -h / 2.0;
  const int m_left = std::max(0, static_cast<int>(std::ceil(left_edge - xf_min))) + kCanvasMarginPx;
  const int m_top = std::max(0, static_cast<int>(std::ceil(top_edge - yf_min))) + kCanvasMarginPx;
  x_min_ = (left_edge - m_left) / f_px_;
  y_min_ = (top_edge - m_top) / f_px_;
  canvas_w_ = static_cast<int>(std::ceil(xf_max - x_min_ * f_px_)) + kCanvasMarginPx;
  canvas_h_ = static_cast<int>(std::ceil(yf_max - y_min_ * f_px_)) + kCanvasMarginPx;

  cv::Mat map_x(h, w, CV_32F);
  cv::Mat map_y(h, w, CV_32F);
  for (int v = 0; v < h; ++v) {
    for (int u = 0; u < w; ++u) {
      map_x.at<float>(v, u) = static_cast<float>((ideal_x.at<double>(v, u) - x_min_) * f_px_ - 0.5);
      map_y.at<float>(v, u) = static_cast<float>((ideal_y.at<double>(v, u) - y_min_) * f_px_ - 0.5);
    }
  }
  cv::convertMaps(map_x, map_y, map1_, map2_, CV_16SC2);
}

Pose2d CameraRenderer::CameraPose(const Pose2d& X_WR) const {
  const double ct = std::cos(X_WR.theta_rad);
  const double st = std::sin(X_WR.theta_rad);
  Pose2d X_WC;
  X_WC.x_in = X_WR.x_in + ct * model_.mount_forward_in - st * model_.mount_left_in;
  X_WC.y_in = X_WR.y_in + st * model_.mount_forward_in + ct * model_.mount_left_in;
  X_WC.theta_rad = std::remainder(X_WR.theta_rad + DegToRad(model_.mount_yaw_deg), 2.0 * kPi);
  return X_WC;
}

std::optional<Eigen::Vector2d> CameraRenderer::Project(const Pose2d& X_WC,
                                                       const Eigen::Vector3d& p_W_in) const {
  const Eigen::Vector2d a{std::cos(X_WC.theta_rad), std::sin(X_WC.theta_rad)};
  const Eigen::Vector2d r{a.y(), -a.x()};
  const Eigen::Vector2d rel = p_W_in.head<2>() - X_WC.position();
  const double zc = rel.dot(a);
  if (zc <= 1e-6) return std::nullopt;
  const double xl = rel.dot(r) / zc;
  const double yl = (model_.height_in - p_W_in.z()) / zc;
  // Level camera -> tilted camera (pitch), then roll.
  const double cp = std::cos(DegToRad(model_.pitch_deg));
  const double sp = std::sin(DegToRad(model_.pitch_deg));
  const double zt = yl * sp + cp;
  if (zt <= 1e-9) return std::nullopt;
  const double x = xl / zt;
  const double y = (yl * cp - sp) / zt;
  const double roll = DegToRad(model_.roll_deg);
  const double xr = std::cos(roll) * x + std::sin(roll) * y;
  const double yr = -std::sin(roll) * x + std::cos(roll) * y;
  const double k = 1.0 + model_.k1 * (xr * xr + yr * yr);
  return Eigen::Vector2d{model_.cx_px() + f_px_ * xr * k, model_.cy_px() + f_px_ * yr * k};
}

std::optional<double> CameraRenderer::ColumnAtCenterRow(const Pose2d& X_WC,
                                                        const Eigen::Vector2d& p_W_in) const {
  const auto crossing = CrossCenterRow(X_WC, p_W_in);
  if (!crossing) return std::nullopt;
  return crossing->column_px;
}

std::optional<CameraRenderer::CenterRowCrossing> CameraRenderer::CrossCenterRow(
    const Pose2d& X_WC, const Eigen::Vector2d& p_W_in) const {
  const Eigen::Vector2d a{std::cos(X_WC.theta_rad), std::sin(X_WC.theta_rad)};
  const Eigen::Vector2d r{a.y(), -a.x()};
  const Eigen::Vector2d rel = p_W_in - X_WC.position();
  const double zc = rel.dot(a);
  if (zc <= 1e-6) return std::nullopt;
  // In the level pinhole image the line is x = x0 for every y. The centre row is where the
  // rolled coordinate y_r is 0 (distortion is radial about the principal point): with the
  // pitch p and roll g that is y = (tan(g) x0 + sin p) / cos p in the level image.
  const double x0 = rel.dot(r) / zc;
  const double roll = DegToRad(model_.roll_deg);
  const double cp = std::cos(DegToRad(model_.pitch_deg));
  const double sp = std::sin(DegToRad(model_.pitch_deg));
  const double y = (std::tan(roll) * x0 + sp) / cp;
  const double zt = y * sp + cp;
  if (zt <= 1e-9) return std::nullopt;
  const double x_c = x0 / zt;
  const double y_c = (y * cp - sp) / zt;
  const double xr = std::cos(roll) * x_c + std::sin(roll) * y_c;
  CenterRowCrossing out;
  out.column_px = model_.cx_px() + f_px_ * xr * (1.0 + model_.k1 * xr * xr);
  out.height_in = model_.height_in - y * zc;
  return out;
}

namespace {

// Where the plan ray origin + t dir (t > 0) lies over a ceiling light: [t0, t1], or empty.
bool LightSpan(const CeilingLight& light, const Eigen::Vector2d& origin,
               const Eigen::Vector2d& dir, double* t0, double* t1) {
  const Eigen::Vector2d q = origin - light.center_in;
  const Eigen::Vector2d v{-light.along.y(), light.along.x()};
  double lo = 0.0, hi = std::numeric_limits<double>::infinity();
  for (const auto& [axis, half] : {std::pair{light.along, 0.5 * light.length_in},
                                   std::pair{v, 0.5 * light.width_in}}) {
    const double q0 = q.dot(axis), d0 = dir.dot(axis);
    if (std::abs(d0) < 1e-12) {
      if (std::abs(q0) > half) return false;
      continue;
    }
    double a = (-half - q0) / d0, b = (half - q0) / d0;
    if (a > b) std::swap(a, b);
    lo = std::max(lo, a);
    hi = std::min(hi, b);
  }
  if (!(hi > lo)) return false;
  *t0 = lo;
  *t1 = hi;
  return true;
}

// One supersampled column of the ideal canvas: what its ray crosses (panels, nearest first;
// ceiling lights as spans of depth) and the rows where the grey level changes, so the
// column is filled as a few constant runs. Depth t is along the optical axis (the ray's
// direction has unit depth); a row at normalised y sees height h - y t at depth t.
class CanvasColumn {
 public:
  CanvasColumn(const World& world, double camera_height_in)
      : cam_h_(camera_height_in),
        ceiling_(world.ceiling_height_in),
        floor_value_(static_cast<float>(world.floor_intensity)),
        ceiling_value_(static_cast<float>(world.ceiling_intensity)),
        reflectance_(static_cast<float>(world.floor_reflectance)) {}

  // Collects the crossings and light spans of the ray origin + t dir.
  void Cast(const Scene& scene, const Eigen::Vector2d& origin, const Eigen::Vector2d& dir,
            double max_range_in, const std::vector<int>& near,
            const std::vector<const CeilingLight*>& lights) {
    scene.CastAll(origin, dir, max_range_in, &crossings_, &near);
    hits_.clear();
    breaks_.clear();
    spans_.clear();
    // Visible crossings, cut after the first panel that spans floor to ceiling.
    for (const Scene::Crossing& c : crossings_) {
      const Panel& p = scene.panels()[c.panel_index];
      const double shade = kAmbientShare + (1.0 - kAmbientShare) * c.cos_incidence;
      hits_.push_back({c.t, p.bottom_in, p.top_in, static_cast<float>(p.intensity * shade)});
      // Rows where this crossing's floor, ceiling, bottom or top edge is seen, directly or
      // in the floor.
      for (double z : {0.0, ceiling_, p.bottom_in, p.top_in}) {
        breaks_.push_back((cam_h_ - z) / c.t);
        if (reflectance_ > 0.0f) breaks_.push_back((cam_h_ + z) / c.t);
      }
      if (p.bottom_in <= 0.0 && p.top_in >= ceiling_) break;
    }
    for (const CeilingLight* l : lights) {
      double t0 = 0.0, t1 = 0.0;
      if (!LightSpan(*l, origin, dir, &t0, &t1)) continue;
      spans_.push_back({t0, t1, static_cast<float>(l->intensity)});
      for (double t : {t0, t1}) {
        if (t <= 0.0) continue;
        breaks_.push_back(-(ceiling_ - cam_h_) / t);
        if (reflectance_ > 0.0f) breaks_.push_back((ceiling_ + cam_h_) / t);
      }
    }
    breaks_.push_back(0.0);  // the horizon, where an empty column turns from ceiling to floor
    std::sort(breaks_.begin(), breaks_.end());
  }

  // Fills `rows` values; row i looks along y = y_min + (i + 0.5) / f.
  void Fill(float* out, int rows, double y_min, double f_px) const {
    auto row_of = [&](double y) { return (y - y_min) * f_px - 0.5; };
    int i = 0;
    for (size_t b = 0; b <= breaks_.size() && i < rows; ++b) {
      // Rows up to and including the last one strictly before the next break.
      int end = rows;
      if (b < breaks_.size()) {
        end = std::clamp(static_cast<int>(std::ceil(row_of(breaks_[b]))), 0, rows);
      }
      if (end <= i) continue;
      std::fill(out + i, out + end, Shade(y_min + (i + 0.5) / f_px));
      i = end;
    }
  }

 private:
  struct Hit {
    double t, bottom, top;
    float value;
  };
  struct Span {
    double t0, t1;
    float value;
  };

  float Shade(double y) const {
    for (const Hit& hit : hits_) {
      const double z = cam_h_ - y * hit.t;
      if (z < 0.0) return FloorAt(y);
      if (z > ceiling_) return CeilingAt((ceiling_ - cam_h_) / -y);
      if (z >= hit.bottom && z <= hit.top) return hit.value;
    }
    return y > 0.0 ? FloorAt(y) : CeilingAt((ceiling_ - cam_h_) / -y);
  }
  // The ceiling point at depth t: a light or the plain ceiling.
  float CeilingAt(double t) const {
    for (const Span& sp : spans_) {
      if (t >= sp.t0 && t <= sp.t1) return sp.value;
    }
    return ceiling_value_;
  }
  float FloorAt(double y) const {
    if (reflectance_ <= 0.0f || y <= 0.0) return floor_value_;
    return (1.0f - reflectance_) * floor_value_ + reflectance_ * Mirrored(y);
  }
  // What the ray seen in a glossy floor at row y (> 0) meets: the mirrored height at depth
  // t beyond the floor point is y t - h.
  float Mirrored(double y) const {
    const double t_floor = cam_h_ / y;
    for (const Hit& hit : hits_) {
      if (hit.t <= t_floor) continue;
      const double z = y * hit.t - cam_h_;
      if (z > ceiling_) break;
      if (z >= hit.bottom && z <= hit.top) return hit.value;
    }
    return CeilingAt((ceiling_ + cam_h_) / y);
  }

  double cam_h_, ceiling_;
  float floor_value_, ceiling_value_, reflectance_;
  std::vector<Scene::Crossing> crossings_;
  std::vector<Hit> hits_;
  std::vector<Span> spans_;
  std::vector<double> breaks_;
};

}  // namespace

void CameraRenderer::RenderCanvas(const Scene& scene, const Pose2d& X_WC, cv::Mat* canvas_t) const {
  const int ss = options_.supersample;
  const int cols = canvas_w_ * ss;
  // Transposed: one contiguous line of canvas_h_ values per supersampled image column.
  canvas_t->create(cols, canvas_h_, CV_32F);
  const Eigen::Vector2d origin = X_WC.position();
  const Eigen::Vector2d a{std::cos(X_WC.theta_rad), std::sin(X_WC.theta_rad)};
  const Eigen::Vector2d r{a.y(), -a.x()};
  const std::vector<int> near = scene.PanelsNear(origin, a, options_.max_range_in);
  std::vector<const CeilingLight*> lights;
  for (const CeilingLight& l : scene.world().ceiling_lights) {
    const double reach = options_.max_range_in + 0.5 * (l.length_in + l.width_in);
    if ((l.center_in - origin).norm() <= reach) lights.push_back(&l);
  }
  CanvasColumn column(scene.world(), model_.height_in);
  for (int j = 0; j < cols; ++j) {
    const double x = x_min_ + (j + 0.5) / (f_px_ * ss);
    column.Cast(scene, origin, a + x * r, options_.max_range_in, near, lights);
    column.Fill(canvas_t->ptr<float>(j), canvas_h_, y_min_, f_px_);
  }
}

RenderedFrame CameraRenderer::Render(const Scene& scene, const Pose2d& X_WR,
                                     const Illumination& light, std::mt19937_64& rng) const {
  RenderedFrame frame;
  const Pose2d X_WC = CameraPose(X_WR);
  cv::Mat canvas_t;
  RenderCanvas(scene, X_WC, &canvas_t);
  cv::Mat ideal_t;
  if (options_.supersample > 1) {
    // Area-average each group of supersampled columns (rows of the transposed canvas).
    cv::resize(canvas_t, ideal_t, cv::Size(canvas_h_, canvas_w_), 0, 0, cv::INTER_AREA);
  } else {
    ideal_t = canvas_t;
  }
  cv::Mat ideal;
  cv::transpose(ideal_t, ideal);
  cv::Mat warped;
  cv::remap(ideal, warped, map1_, map2_, cv::INTER_LINEAR, cv::BORDER_REPLICATE);

  // Illumination: a gain ramp across the columns, then offset and sensor noise.
  const int w = model_.width_px;
  const int h = model_.height_px;
  std::vector<float> column_gain(w);
  for (int u = 0; u < w; ++u) {
    column_gain[u] =
        static_cast<float>(light.gain * (1.0 + light.gradient * ((u + 0.5) / w - 0.5)));
  }
  const bool vignette = light.vignetting != 0.0;
  const double half_diag2 = 0.25 * (static_cast<double>(w) * w + static_cast<double>(h) * h);
  cv::Mat noise;
  if (light.noise_stddev > 0.0) {
    cv::RNG cv_rng(rng());  // seeded from the caller's generator: no global state
    noise.create(warped.size(), CV_32F);
    cv_rng.fill(noise, cv::RNG::NORMAL, 0.0, light.noise_stddev);
  }
  const float offset = static_cast<float>(light.offset);
  for (int v = 0; v < warped.rows; ++v) {
    float* row = warped.ptr<float>(v);
    const float* n = noise.empty() ? nullptr : noise.ptr<float>(v);
    const float row_gain =
        static_cast<float>(1.0 + light.vertical_gradient * ((v + 0.5) / h - 0.5));
    const double dv = v - model_.cy_px();
    for (int u = 0; u < w; ++u) {
      float g = column_gain[u] * row_gain;
      if (vignette) {
        const double du = u - model_.cx_px();
        g *= static_cast<float>(1.0 - light.vignetting * (du * du + dv * dv) / half_diag2);
      }
      row[u] = row[u] * g + offset + (n != nullptr ? n[u] : 0.0f);
    }
  }
  warped.convertTo(frame.image, CV_8U);  // rounds and saturates to 0..255
  frame.truth = Truth(scene, X_WR);
  return frame;
}

FrameTruth CameraRenderer::Truth(const Scene& scene, const Pose2d& X_WR) const {
  FrameTruth truth;
  truth.X_WR = X_WR;
  truth.X_WC = CameraPose(X_WR);
  const Eigen::Vector2d origin = truth.X_WC.position();
  const Eigen::Vector2d a{std::cos(truth.X_WC.theta_rad), std::sin(truth.X_WC.theta_rad)};
  const std::optional<RayHit> axis_hit =
      scene.Raycast(origin, a, options_.max_range_in, model_.height_in);
  truth.axis_range_in = axis_hit ? axis_hit->distance_in : std::numeric_limits<double>::quiet_NaN();

  std::vector<Scene::Crossing> crossings;
  const std::vector<Panel>& panels = scene.panels();
  for (int d = 0; d < static_cast<int>(scene.world().doors.size()); ++d) {
    const auto [p0, p1] = scene.JambPoints(d);
    std::vector<JambTruth> seen;
    for (const Eigen::Vector2d& p : {p0, p1}) {
      const Eigen::Vector2d rel = p - origin;
      const double depth = rel.dot(a);
      if (depth < 1.0) continue;
      const auto crossing = CrossCenterRow(truth.X_WC, p);
      if (!crossing || crossing->column_px < -0.5 || crossing->column_px > model_.width_px - 0.5) {
        continue;
      }
      const std::optional<double> col = crossing->column_px;
      // Height where the centre row meets the jamb line (roll and pitch, §4.1.1).
      const double z = crossing->height_in;
      // Hidden when a panel covering the line of sight at that height comes more than 2 in
      // before the jamb (the frame casing ends at the jamb itself).
      const double dist = rel.norm();
      scene.CastAll(origin, rel, 1.0 - 2.0 / dist, &crossings);
      bool hidden = false;
      for (const Scene::Crossing& c : crossings) {
        const Panel& panel = panels[c.panel_index];
        const double z_at = model_.height_in + (z - model_.height_in) * c.t;
        if (z_at >= panel.bottom_in && z_at <= panel.top_in) {
          hidden = true;
          break;
        }
      }
      if (hidden) continue;
      JambTruth jamb;
      jamb.door_index = d;
      jamb.column_px = *col;
      jamb.depth_in = depth;
      jamb.point_W_in = p;
      seen.push_back(jamb);
    }
    if (seen.empty()) continue;
    std::sort(seen.begin(), seen.end(),
              [](const JambTruth& l, const JambTruth& rr) { return l.column_px < rr.column_px; });
    if (seen.size() == 2) {
      seen.front().image_left = true;
    } else {
      // One jamb in view: it is the left one when its partner projects farther right (or
      // behind the camera on the right-hand side).
      const Eigen::Vector2d other = (seen.front().point_W_in - p0).norm() < 1e-9 ? p1 : p0;
      const std::optional<double> other_col = ColumnAtCenterRow(truth.X_WC, other);
      seen.front().image_left =
          other_col ? *other_col > seen.front().column_px
                    : (other - origin).dot(Eigen::Vector2d{a.y(), -a.x()}) > 0.0;
    }
    const DoorFeature& door = scene.world().doors[d];
    DoorTruth dt;
    dt.door_index = d;
    dt.class_in = DoorClassForWidth(door.width_in);
    dt.width_in = door.width_in;
    dt.state = door.state;
    dt.both_jambs_visible = seen.size() == 2;
    dt.left_column_px = seen.front().column_px;
    dt.right_column_px = seen.back().column_px;
    truth.doors.push_back(dt);
    for (const JambTruth& j : seen) truth.jambs.push_back(j);
  }
  return truth;
}

}  // namespace stickrep::world
