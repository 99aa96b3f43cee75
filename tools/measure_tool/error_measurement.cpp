#include "measure_tool/error_measurement.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <memory>
#include <random>
#include <stdexcept>

#include "common/seeds.h"
#include "common/worker_pool.h"
#include "common/units.h"
#include "stickrep/map.h"
#include "world/camera_renderer.h"
#include "world/map_world.h"
#include "world/robot_models.h"
#include "world/scene.h"
#include "world/sonar_error_adapter.h"
#include "world/sonar_ring.h"

namespace stickrep::measure {
namespace {

// Room the robot needs around the camera: the sonar head (7.5 in) and a little more.
constexpr double kClearanceIn = 12.0;
constexpr int kMaxPlacementTries = 50;
// A sensed jamb within this of the true one found the right edge (docs/vision.md: 2 px).
constexpr double kJambTolerancePx = 3.0;

static_assert(kClassCount == map::kDoorClassCount);

// The door classes by index (map::DoorClass order): their names, and the class of a nominal
// width.
const char* ClassName(int index) { return map::DoorClassName(static_cast<map::DoorClass>(index)); }

int ClassIndexOfWidth(int width_in) {
  for (int i = 0; i < map::kDoorClassCount; ++i) {
    if (map::DoorClassWidthIn(static_cast<map::DoorClass>(i)) == width_in) return i;
  }
  return -1;
}

double Pct(long num, long den) { return den > 0 ? 100.0 * num / den : 0.0; }

// One simulated building per (map, ring, doors open or not).
struct RingWorld {
  int map_index = 0;
  std::unique_ptr<world::Scene> closed_scene;
  std::unique_ptr<world::Scene> open_scene;
  world::MapWorld geometry;             // of the closed world (same walls as the open one)
  std::vector<double> cumulative_in;    // cumulative edge length along the ring
  std::vector<std::size_t> door_edges;  // edges of the ring that are doorways
};

// Everything the workers share, read-only.
struct Setup {
  const MeasureConfig* config = nullptr;
  world::RobotModels models;
  std::vector<double> roll_deg;  // [0] = 0, then the rolled angles
  std::vector<std::unique_ptr<world::CameraRenderer>> renderers;
  std::unique_ptr<world::SonarRingSimulator> sonar;
  world::SurfaceTableSonarErrorModel sonar_error;
  std::unique_ptr<landmark::LandmarkPipeline> pipeline;
  std::vector<std::vector<RingWorld>> rings_of_map;
  std::vector<std::vector<double>> ring_weight_of_map;  // cumulative ring lengths
};

void CheckConfig(const MeasureConfig& c, std::size_t maps) {
  auto fail = [](const std::string& what) { throw std::invalid_argument("measure: " + what); };
  if (maps == 0) fail("no map given");
  if (c.frames < 1) fail("frames must be >= 1");
  if (c.threads < 1 || c.threads > 256) fail("threads must be in 1..256");
  if (!(c.hallway_width_in >= 48.0 && c.hallway_width_in <= 600.0)) {
    fail("hallway_width_in must be in 48..600 in");
  }
  if (!(c.envelope_share >= 0.0 && c.envelope_share <= 1.0)) fail("envelope_share in [0, 1]");
  if (!(c.door_aim_share >= 0.0 && c.door_aim_share <= 1.0)) fail("door_aim_share in [0, 1]");
  if (!(c.open_door_fraction >= 0.0 && c.open_door_fraction <= 1.0)) {
    fail("open_door_fraction in [0, 1]");
  }
  if (!(c.max_roll_deg >= 0.0 && c.max_roll_deg <= 20.0)) fail("max_roll_deg in [0, 20] deg");
  if (!(c.outside_lateral_in >= c.envelope_lateral_in && c.envelope_lateral_in >= 0.0 &&
        c.hallway_width_in / 2.0 - c.outside_lateral_in >= 2.0 * kClearanceIn)) {
    fail("need 0 <= envelope_lateral_in <= outside_lateral_in <= hallway/2 - 24 in");
  }
  if (!(c.outside_stare_deg >= c.envelope_stare_deg && c.envelope_stare_deg >= 0.0 &&
        c.outside_stare_deg <= 45.0)) {
    fail("need 0 <= envelope_stare_deg <= outside_stare_deg <= 45 deg");
  }
}

Setup Prepare(const std::vector<map::Map>& maps, const sensing::RobotConfig& robot,
              const MeasureConfig& config) {
  Setup s;
  s.config = &config;
  s.models = world::RobotModelsFromConfig(robot);
  s.roll_deg.push_back(0.0);
  for (double k : {-4.0, -3.0, -2.0, -1.0, 1.0, 2.0, 3.0, 4.0}) {
    if (config.max_roll_deg > 0.0) s.roll_deg.push_back(k / 4.0 * config.max_roll_deg);
  }
  if (config.realism.camera_misalignment) {
    // Cameras as real ones are mounted, in place of the roll set.
    s.roll_deg.clear();
    std::mt19937_64 camera_rng(StreamSeed(config.seed, 1ull << 42));
    for (int k = 0; k < kRealCameras; ++k) {
      const world::CameraModel camera =
          world::DrawCamera(config.realism, s.models.camera, camera_rng);
      s.roll_deg.push_back(camera.roll_deg);
      s.renderers.push_back(std::make_unique<world::CameraRenderer>(camera));
    }
  } else {
    for (double roll : s.roll_deg) {
      world::CameraModel camera = s.models.camera;
      camera.roll_deg = roll;
      s.renderers.push_back(std::make_unique<world::CameraRenderer>(camera));
    }
  }
  s.sonar = std::make_unique<world::SonarRingSimulator>(s.models.sonar);
  s.pipeline = std::make_unique<landmark::LandmarkPipeline>(
      robot, config.detector, config.estimator, config.casing, config.gate);
  for (std::size_t m = 0; m < maps.size(); ++m) {
    std::vector<RingWorld> rings;
    std::vector<double> weights;
    double total = 0.0;
    for (int r = 0; r < maps[m].RingCount(); ++r) {
      world::MapWorldOptions options;
      options.hallway_width_in = config.hallway_width_in;
      options.opposite_wall = world::OppositeWall::kAlways;
      RingWorld rw;
      rw.map_index = static_cast<int>(m);
      // The worlds have seeds of their own, apart from the frames' (index >= 2^40).
      std::mt19937_64 closed_rng(StreamSeed(config.seed, (1ull << 40) + m * 4096 + r));
      rw.geometry = world::BuildRingWorld(maps[m], r, options, closed_rng);
      // The same clutter in the closed and the open world of a ring.
      const std::uint64_t realism_seed = StreamSeed(config.seed, (1ull << 43) + m * 4096 + r);
      std::mt19937_64 realism_rng(realism_seed);
      world::ApplyRealism(config.realism, realism_rng, &rw.geometry.world);
      rw.closed_scene = std::make_unique<world::Scene>(rw.geometry.world);
      options.open_door_fraction = config.open_door_fraction;
      std::mt19937_64 open_rng(StreamSeed(config.seed, (1ull << 41) + m * 4096 + r));
      world::World open = world::BuildRingWorld(maps[m], r, options, open_rng).world;
      realism_rng.seed(realism_seed);
      world::ApplyRealism(config.realism, realism_rng, &open);
      rw.open_scene = std::make_unique<world::Scene>(std::move(open));
      double length = 0.0;
      for (const world::MapEdgeGeometry& g : rw.geometry.edges) {
        if (g.door_index >= 0) rw.door_edges.push_back(rw.cumulative_in.size());
        length += (g.end_in - g.start_in).norm();
        rw.cumulative_in.push_back(length);
      }
      total += length;
      weights.push_back(total);
      rings.push_back(std::move(rw));
    }
    s.rings_of_map.push_back(std::move(rings));
    s.ring_weight_of_map.push_back(std::move(weights));
  }
  return s;
}

// Where the camera stands for one frame.
struct Placement {
  world::Pose2d X_WR;
  bool ok = false;
};

Placement Place(const Setup& s, const RingWorld& rw, const world::Scene& scene, double lateral_in,
                double stare_rad, bool aim_at_door, std::mt19937_64& rng) {
  const MeasureConfig& c = *s.config;
  std::uniform_real_distribution<double> along(0.0, rw.cumulative_in.back());
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int attempt = 0; attempt < kMaxPlacementTries; ++attempt) {
    double u = along(rng);
    if (aim_at_door && !rw.door_edges.empty()) {
      // A point on a door edge, moved along the wall by up to half the view's width at
      // the axis range so the door is whole in some frames and cut in others.
      const std::size_t k = std::min<std::size_t>(
          static_cast<std::size_t>(unit(rng) * rw.door_edges.size()), rw.door_edges.size() - 1);
      const std::size_t e = rw.door_edges[k];
      const double len = rw.cumulative_in[e] - (e > 0 ? rw.cumulative_in[e - 1] : 0.0);
      const double half_view =
          c.hallway_width_in / 2.0 * std::tan(DegToRad(s.models.camera.fov_deg) / 2.0);
      u = rw.cumulative_in[e] - len / 2.0 + (2.0 * unit(rng) - 1.0) * half_view;
      u = std::clamp(u, 0.0, std::nextafter(rw.cumulative_in.back(), 0.0));
    }
    const std::size_t e = std::upper_bound(rw.cumulative_in.begin(), rw.cumulative_in.end(), u) -
                          rw.cumulative_in.begin();
    if (e >= rw.geometry.edges.size()) continue;
    const world::MapEdgeGeometry& g = rw.geometry.edges[e];
    const Eigen::Vector2d edge = g.end_in - g.start_in;
    const double len = edge.norm();
    const Eigen::Vector2d dir = edge / len;
    const double into = u - (rw.cumulative_in[e] - len);
    const Eigen::Vector2d p = g.start_in + dir * into;
    const Eigen::Vector2d n{-dir.y(), dir.x()};  // toward the hallway (maps/README.md)
    const double d = c.hallway_width_in / 2.0 + lateral_in;
    // The line of sight from the wall to the camera must be free, and the camera must have
    // room round it (not in a corner, an alcove or past the end of an open ring).
    const auto back = scene.Raycast(p + n * 0.5, n, d + kClearanceIn);
    if (back) continue;
    const Eigen::Vector2d camera = p + n * d;
    bool clear = true;
    for (int k = 0; k < 8 && clear; ++k) {
      const double a = k * kPi / 4.0;
      if (scene.Raycast(camera, {std::cos(a), std::sin(a)}, kClearanceIn)) clear = false;
    }
    if (!clear) continue;
    const double heading = std::atan2(-n.y(), -n.x()) + stare_rad;
    Placement out;
    out.X_WR.theta_rad = heading - DegToRad(s.models.camera.mount_yaw_deg);
    const double ct = std::cos(out.X_WR.theta_rad), st = std::sin(out.X_WR.theta_rad);
    const double fwd = s.models.camera.mount_forward_in, left = s.models.camera.mount_left_in;
    out.X_WR.x_in = camera.x() - (ct * fwd - st * left);
    out.X_WR.y_in = camera.y() - (st * fwd + ct * left);
    out.ok = true;
    return out;
  }
  return {};
}

// What a frame draws before the camera is placed: its world, its offsets from the hallway
// axis, the camera's roll and the light.
struct FrameDraw {
  const RingWorld* ring = nullptr;
  const world::Scene* scene = nullptr;
  double lateral_in = 0.0;
  double stare_deg = 0.0;
  std::size_t roll_index = 0;
  world::Illumination light;
};

// Every draw of frame `index` before its placement, in one fixed order (the frames are
// reproducible from their seeds only if it never changes); the choices are kept in `out`.
FrameDraw DrawFrame(const Setup& s, std::uint64_t index, std::mt19937_64& rng, FrameResult& out) {
  const MeasureConfig& c = *s.config;
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  FrameDraw draw;
  out.map_index = static_cast<int>(index % s.rings_of_map.size());
  const std::vector<double>& weights = s.ring_weight_of_map[out.map_index];
  const std::size_t ring = std::min<std::size_t>(
      std::upper_bound(weights.begin(), weights.end(), unit(rng) * weights.back()) -
          weights.begin(),
      weights.size() - 1);
  draw.ring = &s.rings_of_map[out.map_index][ring];
  out.doors_open = c.open_door_fraction > 0.0 && unit(rng) < 0.5;
  draw.scene = out.doors_open ? draw.ring->open_scene.get() : draw.ring->closed_scene.get();

  // Inside the §6.4.2 envelope, or outside it in range, stare or both.
  out.in_envelope = unit(rng) < c.envelope_share;
  int outside_mode = std::uniform_int_distribution<int>(0, 2)(rng);
  const double sign_l = unit(rng) < 0.5 ? -1.0 : 1.0;
  const double sign_s = unit(rng) < 0.5 ? -1.0 : 1.0;
  const double u_l = unit(rng), u_s = unit(rng);
  draw.lateral_in = sign_l * u_l * c.envelope_lateral_in;
  draw.stare_deg = sign_s * u_s * c.envelope_stare_deg;
  if (!out.in_envelope) {
    if (outside_mode != 1) {
      draw.lateral_in =
          sign_l * (c.envelope_lateral_in + u_l * (c.outside_lateral_in - c.envelope_lateral_in));
    }
    if (outside_mode != 0) {
      draw.stare_deg =
          sign_s * (c.envelope_stare_deg + u_s * (c.outside_stare_deg - c.envelope_stare_deg));
    }
  }
  if (c.realism.camera_misalignment) {
    draw.roll_index = std::uniform_int_distribution<std::size_t>(0, s.roll_deg.size() - 1)(rng);
  } else if (s.roll_deg.size() > 1 && unit(rng) < 0.5) {
    draw.roll_index = std::uniform_int_distribution<std::size_t>(1, s.roll_deg.size() - 1)(rng);
  }
  out.rolled = std::abs(s.roll_deg[draw.roll_index]) > 0.5;
  draw.light.gain = c.min_gain + unit(rng) * (c.max_gain - c.min_gain);
  draw.light.offset = c.min_offset + unit(rng) * (c.max_offset - c.min_offset);
  draw.light.gradient = (2.0 * unit(rng) - 1.0) * c.max_gradient;
  draw.light.noise_stddev = c.min_noise + unit(rng) * (c.max_noise - c.min_noise);

  out.aimed_at_door = unit(rng) < c.door_aim_share;
  if (c.realism.illumination) draw.light = world::DrawIllumination(c.realism, draw.light, rng);
  return draw;
}

// The sonar sweep from the frame's pose, as the landmark process receives it.
sensing::SonarScan SenseSonar(const Setup& s, const world::Scene& scene, const world::Pose2d& X_WR,
                              std::mt19937_64& rng) {
  sensing::SonarScan scan;
  for (const world::SonarReading& r : s.sonar->Sense(scene, X_WR, s.sonar_error, rng)) {
    scan.ranges_in.push_back(r.valid ? r.range_in : 0.0);
    scan.valid.push_back(r.valid);
  }
  return scan;
}

// A door wholly in view: its jambs' columns and its class index.
struct WholeDoor {
  double left, right;
  int cls;
};

// Ground truth: the doors wholly in view. Sets the frame's truth, and marks it when part of
// a door is in view.
std::vector<WholeDoor> WholeDoorsInView(const MeasureConfig& c, const world::RenderedFrame& frame,
                                        FrameResult& out) {
  std::vector<WholeDoor> whole;
  const double right_limit = frame.image.cols - 1 - c.whole_door_margin_px;
  for (const world::DoorTruth& d : frame.truth.doors) {
    const bool inside = d.both_jambs_visible && d.left_column_px >= c.whole_door_margin_px &&
                        d.right_column_px <= right_limit;
    const int cls = d.class_in ? ClassIndexOfWidth(*d.class_in) : -1;
    if (inside && cls >= 0) {
      whole.push_back({d.left_column_px, d.right_column_px, cls});
    } else {
      out.partial_door = true;
    }
  }
  out.truth = whole.empty() ? FrameResult::Truth::kNegative : FrameResult::Truth::kPositive;
  return whole;
}

// The outcome of a frame: what the pipeline sensed against the whole doors in view.
void Score(const landmark::FrameOutcome& sensed, const std::vector<WholeDoor>& whole,
           FrameResult& out) {
  if (sensed.kind == landmark::FrameOutcome::Kind::kNoRange ||
      sensed.kind == landmark::FrameOutcome::Kind::kBadFrame) {
    out.outcome = FrameResult::Outcome::kDropped;
    return;
  }
  const bool door = sensed.kind == landmark::FrameOutcome::Kind::kObservation;
  if (door) {
    out.sensed_class = static_cast<int>(sensed.observation.door_class);
    out.sensed_width_in = sensed.observation.width_in;
  }
  if (whole.empty()) {
    out.outcome = door ? FrameResult::Outcome::kFalsePositive : FrameResult::Outcome::kTrueNegative;
    return;
  }
  if (!door) {
    out.true_class = whole.front().cls;
    out.outcome = FrameResult::Outcome::kFalseNegative;
    return;
  }
  // The whole door the sensed ribbon lies on (its centre between the jambs), else the
  // nearest one.
  const double centre =
      0.5 * (sensed.observation.footprints.lj_px + sensed.observation.footprints.rj_px);
  const WholeDoor* match = nullptr;
  double best = 1e300;
  for (const WholeDoor& w : whole) {
    const double dist = centre < w.left    ? w.left - centre
                        : centre > w.right ? centre - w.right
                                           : 0.0;
    if (dist < best) {
      best = dist;
      match = &w;
    }
  }
  out.sensed_off_door = best > 0.0;
  out.true_class = match->cls;
  out.jamb_error_px = std::max(std::abs(sensed.observation.footprints.lj_px - match->left),
                               std::abs(sensed.observation.footprints.rj_px - match->right));
  out.outcome = out.sensed_class == match->cls ? FrameResult::Outcome::kTruePositive
                                               : FrameResult::Outcome::kMissizedPositive;
}

// The jamb pairs offered against the whole doors in view.
void ScorePairs(const landmark::FrameOutcome& sensed, const std::vector<WholeDoor>& whole,
                FrameResult& out) {
  out.pairs_offered = static_cast<int>(sensed.ranked.size());
  out.pair_cap_hit = sensed.candidates > 0 && sensed.pairs_before_cap > sensed.candidates;
  auto on_door = [&](const sensing::JambCandidate& c) {
    for (const WholeDoor& w : whole) {
      if (std::abs(c.footprints.lj_px - w.left) <= kJambTolerancePx &&
          std::abs(c.footprints.rj_px - w.right) <= kJambTolerancePx) {
        return true;
      }
    }
    return false;
  };
  // The classifier's order: highest confidence first (the casing rule may promote one).
  std::vector<const sensing::JambCandidate*> order;
  for (const sensing::JambCandidate& c : sensed.ranked) order.push_back(&c);
  std::stable_sort(order.begin(), order.end(), [](const auto* a, const auto* b) {
    return a->confidence > b->confidence;
  });
  for (std::size_t k = 0; k < order.size() && k < 3; ++k) {
    if (!on_door(*order[k])) continue;
    out.top3_pair_on_door = true;
    if (k == 0) out.top_pair_on_door = true;
  }
}

FrameResult RunFrame(const Setup& s, std::uint64_t index) {
  std::mt19937_64 rng(StreamSeed(s.config->seed, index));
  FrameResult out;
  const FrameDraw draw = DrawFrame(s, index, rng, out);
  const world::Scene& scene = *draw.scene;
  const Placement place = Place(s, *draw.ring, scene, draw.lateral_in, DegToRad(draw.stare_deg),
                                out.aimed_at_door, rng);
  if (!place.ok) return out;  // dropped: nowhere to stand on this ring

  const world::RenderedFrame frame =
      s.renderers[draw.roll_index]->Render(scene, place.X_WR, draw.light, rng);
  const sensing::SonarScan scan = SenseSonar(s, scene, place.X_WR, rng);
  const std::vector<WholeDoor> whole = WholeDoorsInView(*s.config, frame, out);

  const cv::Mat& img = frame.image;
  const vision::ImageView view{img.cols, img.rows, static_cast<int>(img.step),
                               "mono8",  img.data, img.total()};
  const landmark::FrameOutcome sensed = s.pipeline->Process(view, scan);
  Score(sensed, whole, out);
  ScorePairs(sensed, whole, out);
  return out;
}

}  // namespace

void UseDetectorBeforeIssue17(MeasureConfig* config) {
  vision::RibbonDetectorParams& d = config->detector;
  d.confidence = vision::RibbonDetectorParams::Confidence::kEnergyShare;
  d.appearance_rule = false;
  d.outer_row_fraction = 0.75;
  d.min_pair_width_px = 12.0;
  d.max_pair_width_px = 1e9;
  d.max_clump_width_px = 1 << 20;
  config->gate.enabled = false;
}

void PairTally::Add(const FrameResult& r) {
  if (r.outcome == FrameResult::Outcome::kDropped) return;
  ++frames;
  pairs += r.pairs_offered;
  with_pairs += r.pairs_offered > 0;
  capped += r.pair_cap_hit;
  top_on_door += r.top_pair_on_door;
  if (r.truth == FrameResult::Truth::kPositive) {
    ++positives;
    top_on_door_of_positives += r.top_pair_on_door;
    top3_on_door += r.top3_pair_on_door;
  } else {
    ++negatives;
    negatives_with_pairs += r.pairs_offered > 0;
    negative_pairs += r.pairs_offered;
  }
}

double PairTally::precision_pct() const { return Pct(top_on_door, with_pairs); }
double PairTally::recall_pct() const { return Pct(top_on_door_of_positives, positives); }
double PairTally::recall3_pct() const { return Pct(top3_on_door, positives); }

double Tally::correct_pct() const { return Pct(tp + tn, frames()); }
double Tally::tp_pct() const { return Pct(tp, positives()); }
double Tally::tn_pct() const { return Pct(tn, negatives()); }
double Tally::misclassified_pct() const { return Pct(missized + fn + fp, frames()); }
double Tally::fp_pct() const { return Pct(fp, negatives()); }
double Tally::missized_pct() const { return Pct(missized, positives()); }
double Tally::fn_pct() const { return Pct(fn, positives()); }

void Tally::Add(const FrameResult& r) {
  switch (r.outcome) {
    case FrameResult::Outcome::kTruePositive:
      ++tp;
      break;
    case FrameResult::Outcome::kMissizedPositive:
      ++missized;
      break;
    case FrameResult::Outcome::kFalseNegative:
      ++fn;
      break;
    case FrameResult::Outcome::kTrueNegative:
      ++tn;
      break;
    case FrameResult::Outcome::kFalsePositive:
      ++fp;
      break;
    case FrameResult::Outcome::kDropped:
      ++dropped;
      break;
  }
}

Measurement MeasurePipeline(const std::vector<map::Map>& maps, const sensing::RobotConfig& robot,
                            const MeasureConfig& config) {
  CheckConfig(config, maps.size());
  const auto start = std::chrono::steady_clock::now();
  Measurement m;
  m.config = config;
  for (const map::Map& mp : maps) m.map_names.push_back(mp.info().name);
  const Setup setup = Prepare(maps, robot, config);

  m.frames.resize(static_cast<std::size_t>(config.frames));
  // Each frame is drawn from its own seed (StreamSeed of its index): the same frames
  // whatever the number of threads.
  ParallelFor(m.frames.size(), config.threads,
              [&]() -> IndexTask { return [&](std::size_t i) { m.frames[i] = RunFrame(setup, i); }; });

  m.per_map.resize(maps.size());
  for (const FrameResult& r : m.frames) {
    m.all.Add(r);
    m.pairs.Add(r);
    m.per_map[r.map_index].Add(r);
    (r.in_envelope ? m.in_envelope : m.outside_envelope).Add(r);
    (r.rolled ? m.rolled : m.level).Add(r);
    (r.doors_open ? m.open_worlds : m.closed_worlds).Add(r);
    switch (r.outcome) {
      case FrameResult::Outcome::kTruePositive:
        ++m.true_positive_by_class[r.true_class];
        ++m.positives_by_class[r.true_class];
        break;
      case FrameResult::Outcome::kMissizedPositive:
        ++m.missized_to[r.true_class][r.sensed_class];
        ++m.positives_by_class[r.true_class];
        if (r.sensed_off_door) {
          ++m.missized_off_door;
        } else if (r.jamb_error_px <= kJambTolerancePx) {
          ++m.missized_right_jambs;
        }
        break;
      case FrameResult::Outcome::kFalseNegative:
        ++m.positives_by_class[r.true_class];
        break;
      case FrameResult::Outcome::kFalsePositive:
        ++m.false_door_classes[r.sensed_class];
        if (r.partial_door) ++m.fp_on_partial_doors;
        break;
      default:
        break;
    }
  }
  m.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return m;
}

namespace {

std::string Fmt(const char* fmt, ...) __attribute__((format(printf, 1, 2)));
std::string Fmt(const char* fmt, ...) {
  char buf[512];
  va_list args;
  va_start(args, fmt);
  std::vsnprintf(buf, sizeof(buf), fmt, args);
  va_end(args);
  return buf;
}

template <typename... Args>
std::string Line(const char* fmt, Args... args) {
  return Fmt(fmt, args...) + "\n";
}

std::string Rates(const char* label, const Tally& t) {
  return Line("  %-24s %6ld  %6.2f  %6.2f  %6.2f  %6.2f  %6.2f  %6.2f  %6.2f", label, t.frames(),
              t.correct_pct(), t.tp_pct(), t.tn_pct(), t.misclassified_pct(), t.fp_pct(),
              t.missized_pct(), t.fn_pct());
}

// The run's parameters, and how its frames split into positives and negatives.
std::string ReportHeader(const Measurement& m) {
  const MeasureConfig& c = m.config;
  const Tally& a = m.all;
  std::string s;
  s += "stickrep-measure: the landmark pipeline (ribbon detector, casing rule, Short Side, Bayes "
       "classes) on rendered frames\n";
  s += Line("seed %llu  frames %d (%ld used, %ld dropped)  threads %d  %.1f s",
            static_cast<unsigned long long>(c.seed), c.frames, a.frames(), a.dropped, c.threads,
            m.seconds);
  s += "maps:";
  for (const std::string& n : m.map_names) s += " " + n;
  s += "\n";
  s += Line(
      "hallway %.0f in; %.0f %% of frames in the 6.4.2 envelope (|offset| <= %.0f in, "
      "|stare| <= %.1f deg), the rest up to %.0f in / %.1f deg; roll 0 or up to +-%.1f deg; "
      "open doors (%.0f %%) in half the frames; %.0f %% of frames aimed at a door",
      c.hallway_width_in, 100.0 * c.envelope_share, c.envelope_lateral_in, c.envelope_stare_deg,
      c.outside_lateral_in, c.outside_stare_deg, c.max_roll_deg, 100.0 * c.open_door_fraction,
      100.0 * c.door_aim_share);
  long partial_negatives = 0;
  for (const FrameResult& r : m.frames) {
    partial_negatives += r.outcome != FrameResult::Outcome::kDropped &&
                         r.truth == FrameResult::Truth::kNegative && r.partial_door;
  }
  s += Line(
      "positives (a whole door in view) %ld; negatives (no whole door in view) %ld, of "
      "which %ld show part of a door",
      a.positives(), a.negatives(), partial_negatives);
  return s;
}

// Table 6.10, the paper's rates beside ours.
std::string Table610(const Tally& a) {
  std::string s = "\nTable 6.10  Empirical error model (%)        paper    ours\n";
  const struct {
    const char* name;
    double paper, ours;
  } rows[] = {{"Correct Classifications", PaperTable610::kCorrect, a.correct_pct()},
              {"True Positives", PaperTable610::kTruePositives, a.tp_pct()},
              {"True Negatives", PaperTable610::kTrueNegatives, a.tn_pct()},
              {"Misclassifications", PaperTable610::kMisclassifications, a.misclassified_pct()},
              {"False Positives", PaperTable610::kFalsePositives, a.fp_pct()},
              {"Missized True Positives", PaperTable610::kMissizedTruePositives, a.missized_pct()},
              {"False Negatives", PaperTable610::kFalseNegatives, a.fn_pct()}};
  for (const auto& r : rows) s += Line("  %-40s %6.2f  %6.2f", r.name, r.paper, r.ours);
  return s;
}

// The rates over subsets of the frames: envelope, roll, open doors and map.
std::string Breakdown(const Measurement& m) {
  std::string s =
      "\nBreakdown (%)               frames correct     TP     TN  miscl     FP  missz     FN\n";
  s += Rates("all", m.all);
  s += Rates("inside 6.4.2 envelope", m.in_envelope);
  s += Rates("outside the envelope", m.outside_envelope);
  s += Rates("level camera", m.level);
  s += Rates("rolled camera", m.rolled);
  s += Rates("all doors closed", m.closed_worlds);
  s += Rates("some doors open", m.open_worlds);
  for (std::size_t i = 0; i < m.per_map.size(); ++i) {
    s += Rates(m.map_names[i].c_str(), m.per_map[i]);
  }
  return s;
}

// The confusions: positives by true and sensed class, and the classes of false positives.
std::string Confusions(const Measurement& m) {
  const Tally& a = m.all;
  std::string s =
      "\nPositives by true class: sensed as (rows: true class; TP on the diagonal; - = missed)\n";
  s += "  true    frames";
  for (int k = 0; k < kClassCount; ++k) s += Fmt("%7s", ClassName(k));
  s += "      -\n";
  for (int t = 0; t < kClassCount; ++t) {
    if (m.positives_by_class[t] == 0) continue;
    long missed = m.positives_by_class[t] - m.true_positive_by_class[t];
    std::string row = Fmt("  %-6s %7ld", ClassName(t), m.positives_by_class[t]);
    for (int k = 0; k < kClassCount; ++k) {
      const long n = k == t ? m.true_positive_by_class[t] : m.missized_to[t][k];
      missed -= k == t ? 0 : n;
      row += Fmt("%7ld", n);
    }
    row += Line("%7ld", missed);
    s += row;
  }
  s += Line(
      "  of the %ld mis-sized: %ld with both jambs within %.0f px of the truth (the width "
      "from the geometry is wrong), %ld on a wrong edge of the door (a casing edge), %ld "
      "beside the door",
      a.missized, m.missized_right_jambs, kJambTolerancePx,
      a.missized - m.missized_right_jambs - m.missized_off_door, m.missized_off_door);
  s += "False positives by sensed class:";
  for (int k = 0; k < kClassCount; ++k) {
    s += Fmt(" %s %ld", ClassName(k), m.false_door_classes[k]);
  }
  s += Line("\n  (%ld of %ld false positives on frames showing part of a door)",
            m.fp_on_partial_doors, a.fp);
  return s;
}

}  // namespace

// Jamb pairs against the renderer's truth, and false doors per wall frame.
std::string PairReport(const Measurement& m) {
  const PairTally& p = m.pairs;
  std::string s = "\nJamb pairs (the candidates handed to the classifier; a hit: both jambs within ";
  s += Fmt("%.0f px of a whole door's)\n", kJambTolerancePx);
  s += Line("  precision of the first pair          %6.2f %%  (%ld of %ld frames with a pair)",
            p.precision_pct(), p.top_on_door, p.with_pairs);
  s += Line("  recall, first pair                   %6.2f %%  (%ld of %ld frames with a whole door)",
            p.recall_pct(), p.top_on_door_of_positives, p.positives);
  s += Line("  recall, first three pairs            %6.2f %%", p.recall3_pct());
  s += Line("  frames with pairs                    %6.2f %%  (%.1f pairs a frame; %.2f %% at the cap)",
            Pct(p.with_pairs, p.frames), p.frames > 0 ? double(p.pairs) / p.frames : 0.0,
            Pct(p.capped, p.frames));
  s += Line("  wall frames (no whole door) with pairs %5.2f %%  (%.2f pairs a wall frame)",
            Pct(p.negatives_with_pairs, p.negatives),
            p.negatives > 0 ? double(p.negative_pairs) / p.negatives : 0.0);
  s += Line("  false doors per wall frame           %6.4f  (%ld of %ld)",
            m.all.negatives() > 0 ? double(m.all.fp) / m.all.negatives() : 0.0, m.all.fp,
            m.all.negatives());
  return s;
}

std::string FormatReport(const Measurement& m) {
  std::string s = ReportHeader(m);
  s += Table610(m.all);
  s += PairReport(m);
  s += Breakdown(m);
  s += Confusions(m);
  return s;
}

std::string FormatErrorModelYaml(const Measurement& m) {
  const Tally& a = m.all;
  auto fixed = [](double v) {
    char buf[32];
    std::snprintf(buf, sizeof(buf), "%.6f", v);
    return std::string(buf);
  };
  auto rounded = [](double v) { return std::round(v * 1e6) / 1e6; };
  const double pos = std::max<long>(1, a.positives());
  const double correct = rounded(a.tp / pos);
  const double missized = rounded(a.missized / pos);
  const double missed = a.positives() > 0 ? 1.0 - correct - missized : 0.0;
  auto distribution = [&](const std::array<long, kClassCount>& counts) {
    long total = 0;
    for (long n : counts) total += n;
    std::string s = "{";
    bool first = true;
    for (int k = 0; k < kClassCount; ++k) {
      if (counts[k] == 0) continue;
      s += (first ? "\"" : ", \"") + std::string(ClassName(k)) +
           "\": " + fixed(static_cast<double>(counts[k]) / total);
      first = false;
    }
    return s + "}";
  };
  std::string missized_to = "{";
  bool first = true;
  for (int t = 0; t < kClassCount; ++t) {
    long row = 0;
    for (long n : m.missized_to[t]) row += n;
    if (row == 0) continue;
    missized_to += (first ? "\"" : ", \"") + std::string(ClassName(t)) +
                   "\": " + distribution(m.missized_to[t]);
    first = false;
  }
  missized_to += "}";
  std::string s;
  s += "# Measured landmark-pipeline error model (SPEC 5; layout of Table 6.10). Positives are\n";
  s += "# frames with a whole door in view, negatives frames with none: "
       "docs/measured_error_model.md\n";
  s += "error_model:\n";
  s += Line("  source: \"measured by stickrep-measure, seed %llu, %ld frames\"",
            static_cast<unsigned long long>(m.config.seed), a.frames());
  s += "  door_correct: " + fixed(correct) + "\n";
  s += "  door_missized: " + fixed(missized) + "\n";
  s += "  door_missed: " + fixed(std::max(0.0, missed)) + "\n";
  s += "  wall_false_door: " + fixed(a.fp / std::max<double>(1, a.negatives())) + "\n";
  s += "  missized_to: " + missized_to + "\n";
  s += "  false_door_classes: " + distribution(m.false_door_classes) + "\n";
  return s;
}

}  // namespace stickrep::measure
