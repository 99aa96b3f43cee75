// The map -> world conversion, the robot description loader and the Tables 4.2/4.3 sonar
// error adapter.
#include "world/map_world.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

#include "common/units.h"
#include "sensing/robot_config.h"
#include "stickrep/map_io.h"
#include "stickrep/test_maps.h"
#include "world/camera_renderer.h"
#include "world/robot_models.h"
#include "world/scene.h"
#include "world/sonar_error_adapter.h"
#include "world/sonar_ring.h"

namespace stickrep::world {
namespace {

using ::testing::DoubleNear;
using ::testing::Optional;

map::Map BoxMap() { return map::ParseMap(map::testing::kBoxMapYaml, "box.yaml"); }

MapWorld BoxRing(MapWorldOptions options = {}, std::uint64_t seed = 7) {
  std::mt19937_64 rng(seed);
  return BuildRingWorld(BoxMap(), 0, options, rng);
}

TEST(MapWorldTest, MergesCoplanarEdgesIntoOneWallPerSide) {
  const MapWorld mw = BoxRing();
  // Four sides, four opposite walls, one room behind the only door.
  int ring_walls = 0;
  for (int r : mw.wall_ring) ring_walls += r == 0 ? 1 : 0;
  EXPECT_EQ(ring_walls, 4);
  EXPECT_EQ(mw.opposite_wall_count, 4);
  EXPECT_EQ(mw.world.walls.size(), 9u);
  ASSERT_EQ(mw.edges.size(), 6u);
  EXPECT_EQ(mw.edges[0].wall_index, mw.edges[2].wall_index);  // the north side
  EXPECT_NE(mw.edges[2].wall_index, mw.edges[3].wall_index);  // a corner
}

TEST(MapWorldTest, PlacesTheDoorAtItsEdgeWithItsClassWidth) {
  const MapWorld mw = BoxRing();
  ASSERT_EQ(mw.world.doors.size(), 1u);
  EXPECT_EQ(mw.door_edges[0].ring, 0);
  EXPECT_EQ(mw.door_edges[0].edge, 1);
  EXPECT_DOUBLE_EQ(mw.world.doors[0].width_in, 36.0);
  EXPECT_EQ(mw.world.doors[0].pattern, DoorPattern::kPoster);
  const Scene scene(mw.world);
  const auto [j0, j1] = scene.JambPoints(0);
  // The wall runs against ring order (hallway on its right), so its a end is x = 100.
  EXPECT_NEAR(j0.x(), 76.0, 1e-9);
  EXPECT_NEAR(j1.x(), 40.0, 1e-9);
  EXPECT_NEAR(j0.y(), 100.1, 1e-9);  // the casing face, 0.1 in proud of the wall
}

TEST(MapWorldTest, HallwayIsOnTheLeftOfRingOrderAndBoundedByTheOppositeWall) {
  const MapWorld mw = BoxRing();
  const Scene scene(mw.world);
  // From the hallway north of the box, looking south: the box's north face at y = 100.
  const auto south = scene.Raycast({20.0, 136.0}, {0.0, -1.0}, 1000.0);
  ASSERT_TRUE(south.has_value());
  EXPECT_NEAR(south->point_in.y(), 100.0, 1e-6);
  // Looking north: the opposite wall one hallway width (72 in) from the face.
  const auto north = scene.Raycast({20.0, 136.0}, {0.0, 1.0}, 1000.0);
  ASSERT_TRUE(north.has_value());
  EXPECT_NEAR(north->point_in.y(), 172.0, 1e-6);
  // The mitred corner: the opposite walls of the north and east sides meet at (172, 172).
  const auto east = scene.Raycast({150.0, 136.0}, {1.0, 0.0}, 1000.0);
  ASSERT_TRUE(east.has_value());
  EXPECT_NEAR(east->point_in.x(), 172.0, 1e-6);
}

// A 400 in square walked with the hallway inside, an alcove 13 in wide and 8 in deep set
// into its first side at x = 200.
map::Ring SquareWithAlcove() {
  const double xs[] = {0, 200, 200, 213, 213, 400, 400, 0};
  const double ys[] = {0, 0, -8, -8, 0, 0, 400, 400};
  map::Ring ring;
  ring.id = "alcove";
  ring.closed = true;
  for (int i = 0; i < 8; ++i) {
    map::Node n;
    n.x_in = xs[i];
    n.y_in = ys[i];
    ring.nodes.push_back(n);
    const double dx = xs[(i + 1) % 8] - xs[i], dy = ys[(i + 1) % 8] - ys[i];
    ring.edges.push_back(map::Edge::Wall(std::hypot(dx, dy)));
  }
  return ring;
}

TEST(MapWorldTest, ShallowStepsArePassedStraightAndTheOffsetFollowsTheRuns) {
  const map::Ring ring = SquareWithAlcove();
  ASSERT_EQ(SplitIntoWallRuns(ring).size(), 8u);
  const std::vector<WallRun> runs = WithoutSteps(SplitIntoWallRuns(ring), true, 36.0);
  ASSERT_EQ(runs.size(), 4u);
  // The alcove's side's three runs are one, on the line of the longer wall (y = 0).
  const auto side = std::find_if(runs.begin(), runs.end(), [](const WallRun& r) {
    return std::abs(r.dir.y()) < 1e-9 && r.dir.x() > 0.0;
  });
  ASSERT_NE(side, runs.end());
  EXPECT_THAT(side->start_in.y(), DoubleNear(0.0, 1e-9));
  EXPECT_THAT(side->length_in, DoubleNear(400.0, 1e-9));
  // Deeper steps stay: with a 5 in limit every corner is kept.
  EXPECT_EQ(WithoutSteps(SplitIntoWallRuns(ring), true, 5.0).size(), 8u);

  const std::vector<OffsetSegment> axis = OffsetRuns(runs, true, 60.0);
  ASSERT_EQ(axis.size(), 4u);
  const OffsetSegment& along = axis[static_cast<size_t>(side - runs.begin())];
  EXPECT_THAT(along.a_in.x(), DoubleNear(60.0, 1e-9));
  EXPECT_THAT(along.a_in.y(), DoubleNear(60.0, 1e-9));
  EXPECT_THAT(along.b_in.x(), DoubleNear(340.0, 1e-9));
  EXPECT_EQ(along.run, static_cast<int>(side - runs.begin()));
}

TEST(MapWorldTest, OppositeWallRunsStraightPastAnAlcove) {
  const map::Map map(map::MapInfo{"alcove", "", "", std::nullopt}, {SquareWithAlcove()});
  MapWorldOptions options;
  options.hallway_width_in = 120.0;
  options.opposite_wall = OppositeWall::kAlways;
  std::mt19937_64 rng(1);
  const MapWorld mw = BuildRingWorld(map, 0, options, rng);
  EXPECT_EQ(mw.opposite_wall_count, 4);
  const Scene scene(mw.world);
  // Abreast of the alcove the opposite wall stands 120 in from the mapped line, not 128.
  const auto north = scene.Raycast({206.0, 60.0}, {0.0, 1.0}, 1000.0);
  ASSERT_TRUE(north.has_value());
  EXPECT_NEAR(north->point_in.y(), 120.0, 1e-6);
}

TEST(MapWorldTest, CameraInTheHallwaySeesTheMappedDoorWithItsClass) {
  const MapWorld mw = BoxRing();
  const Scene scene(mw.world);
  const CameraRenderer renderer(CameraModel{});
  // The camera looks left of the heading: heading west (pi) looks south at the door.
  const FrameTruth truth = renderer.Truth(scene, Pose2d{58.0, 172.0 - 36.0, kPi});
  ASSERT_EQ(truth.doors.size(), 1u);
  EXPECT_THAT(truth.doors[0].class_in, Optional(36));
  EXPECT_TRUE(truth.doors[0].both_jambs_visible);
  EXPECT_NEAR(truth.axis_range_in, 36.0 + 1.0, 1e-6);  // to the leaf, 1 in behind the face
}

TEST(MapWorldTest, OnlyOneRingGetsAnOppositeWallByDefault) {
  std::mt19937_64 rng(1);
  const MapWorld all = BuildMapWorld(BoxMap(), {}, rng);
  EXPECT_EQ(all.opposite_wall_count, 0);
  EXPECT_EQ(all.rings.size(), 2u);
  EXPECT_EQ(all.world.doors.size(), 2u);
  MapWorldOptions always;
  always.opposite_wall = OppositeWall::kAlways;
  EXPECT_GT(BuildMapWorld(BoxMap(), always, rng).opposite_wall_count, 0);
}

TEST(MapWorldTest, CorridorOutlineGetsNoOppositeWallAndOpeningsAreGaps) {
  const map::Map corridor = map::ParseMap(map::testing::kCorridorMapYaml, "corridor.yaml");
  std::mt19937_64 rng(3);
  MapWorldOptions options;
  options.opposite_wall = OppositeWall::kAlways;  // a corridor outline has both sides anyway
  const MapWorld mw = BuildRingWorld(corridor, 0, options, rng);
  EXPECT_EQ(mw.opposite_wall_count, 0);
  // The opening (edge 3) has no wall; the walls before and after it are separate pieces
  // that stop at its ends.
  EXPECT_EQ(mw.edges[3].wall_index, -1);
  const int before = mw.edges[2].wall_index, after = mw.edges[4].wall_index;
  ASSERT_GE(before, 0);
  ASSERT_GE(after, 0);
  EXPECT_NE(before, after);
  EXPECT_EQ(mw.edges[1].wall_index, before);  // the door is set in the piece before
  const WallSegment& wb = mw.world.walls[before];
  const WallSegment& wa = mw.world.walls[after];
  // Walls run against ring order: the piece before ends (a_in) where the opening starts.
  EXPECT_THAT(wb.a_in.y(), DoubleNear(200.0, 1e-9));
  EXPECT_THAT(wb.b_in.y(), DoubleNear(0.0, 1e-9));
  EXPECT_THAT(wa.b_in.y(), DoubleNear(290.0, 1e-9));
  EXPECT_THAT(wa.a_in.y(), DoubleNear(400.0, 1e-9));
  // Doors are as wide as measured, and lie where the map puts them.
  ASSERT_EQ(mw.world.doors.size(), 2u);
  const DoorFeature& wide = mw.world.doors[0];
  EXPECT_DOUBLE_EQ(wide.width_in, 53.0);
  EXPECT_TRUE(wide.double_door);
  EXPECT_THAT(wide.offset_in, DoubleNear(200.0 - 153.0, 1e-9));  // from the piece's a_in end
  EXPECT_DOUBLE_EQ(mw.world.doors[1].width_in, 34.0);
  // A point in the opening's gap is free: no wall within 30 in of the gap's middle, bar the
  // far side of the corridor.
  Scene scene(mw.world);
  const Eigen::Vector2d in_gap{96.0, 245.0};
  for (const Panel& p : scene.panels()) {
    const Eigen::Vector2d d = p.p1_in - p.p0_in;
    const double t = std::clamp((in_gap - p.p0_in).dot(d) / d.squaredNorm(), 0.0, 1.0);
    EXPECT_GT((in_gap - (p.p0_in + t * d)).norm(), 30.0);
  }
}

TEST(MapWorldTest, SideRingWithAWidthGetsItsOppositeWallThere) {
  std::string text = map::testing::kBoxMapYaml;
  text.replace(text.find("stickrep_map: 1"), 15, "stickrep_map: 2");
  text.replace(text.find("closed: true"), 12, "closed: true\n    width_in: 50");
  const map::Map box = map::ParseMap(text, "box.yaml");
  std::mt19937_64 rng(3);
  const MapWorld whole = BuildMapWorld(box, MapWorldOptions{}, rng);
  // Two rings: by default neither faced a wall; the ring with a width gets one, 50 in out.
  EXPECT_EQ(whole.opposite_wall_count, 4);
  bool found = false;
  for (size_t i = 0; i < whole.world.walls.size(); ++i) {
    if (whole.wall_ring[i] != -1) continue;
    const WallSegment& w = whole.world.walls[i];
    if (std::abs(w.a_in.y() - 150.0) < 1e-6 && std::abs(w.b_in.y() - 150.0) < 1e-6) found = true;
  }
  EXPECT_TRUE(found) << "no opposite wall 50 in north of the box";
}

TEST(MapWorldTest, LocatesAWorldPointOnItsEdge) {
  const MapWorld mw = BoxRing();
  const auto place = LocateOnMap(mw, {50.0, 100.5});
  ASSERT_TRUE(place.has_value());
  EXPECT_EQ(place->ref.ring, 0);
  EXPECT_EQ(place->ref.edge, 1);
  EXPECT_NEAR(place->offset_in, 10.0, 1e-9);
  EXPECT_NEAR(place->distance_in, 0.5, 1e-9);
  // The east face, 30 in down from its north end.
  const auto east = LocateOnMap(mw, {101.0, 70.0});
  ASSERT_TRUE(east.has_value());
  EXPECT_EQ(east->ref.edge, 3);
  EXPECT_NEAR(east->offset_in, 30.0, 1e-9);
  EXPECT_FALSE(LocateOnMap(mw, {50.0, 150.0}, 10.0).has_value());
}

TEST(MapWorldTest, OpenDoorsAreSeededAndReproducible) {
  MapWorldOptions options;
  options.open_door_fraction = 1.0;
  options.open_inward_share = 0.0;
  const MapWorld a = BoxRing(options, 99);
  const MapWorld b = BoxRing(options, 99);
  ASSERT_EQ(a.world.doors.size(), 1u);
  EXPECT_EQ(a.world.doors[0].state, DoorState::kOpenOutward);
  EXPECT_GE(a.world.doors[0].open_angle_rad, DegToRad(15.0));
  EXPECT_LE(a.world.doors[0].open_angle_rad, DegToRad(100.0));
  EXPECT_EQ(a.world.doors[0].open_angle_rad, b.world.doors[0].open_angle_rad);
  EXPECT_EQ(BoxRing().world.doors[0].state, DoorState::kClosed);
}

TEST(MapWorldTest, RejectsBadRingAndOptions) {
  std::mt19937_64 rng(1);
  EXPECT_THROW(BuildRingWorld(BoxMap(), 5, {}, rng), std::invalid_argument);
  MapWorldOptions bad;
  bad.hallway_width_in = 0.0;
  EXPECT_THROW(BuildRingWorld(BoxMap(), 0, bad, rng), std::invalid_argument);
  bad = {};
  bad.open_door_fraction = 1.5;
  EXPECT_THROW(BuildRingWorld(BoxMap(), 0, bad, rng), std::invalid_argument);
}

// Every shipped domain converts, ring by ring and whole, into a scene that compiles, with
// one world door per doorway edge.
TEST(MapWorldTest, EveryShippedMapBuildsAScene) {
  for (const char* name : {"engineering_building_3f", "wells_hall_7f", "wells_hall_7f_modified",
                           "regular_polygon_46", "storefront"}) {
    SCOPED_TRACE(name);
    const map::Map m = map::LoadMap(std::string(STICKREP_SOURCE_DIR) + "/maps/" + name + ".yaml");
    std::mt19937_64 rng(3);
    MapWorldOptions options;
    options.open_door_fraction = 0.3;
    const MapWorld whole = BuildMapWorld(m, options, rng);
    int doorways = 0;
    for (const map::Ring& ring : m.rings()) {
      for (const map::Edge& e : ring.edges) doorways += e.IsDoor() ? 1 : 0;
    }
    EXPECT_EQ(static_cast<int>(whole.world.doors.size()), doorways);
    EXPECT_EQ(static_cast<int>(whole.edges.size()), m.EdgeCount());
    EXPECT_NO_THROW(Scene{whole.world});
    for (int r = 0; r < m.RingCount(); ++r) {
      const MapWorld one = BuildRingWorld(m, r, options, rng);
      EXPECT_GT(one.opposite_wall_count, 0) << m.ring(r).id;
      EXPECT_NO_THROW(Scene{one.world});
    }
  }
}

TEST(MapWorldTest, ArtificialRibbonBecomesADarkFullHeightMark) {
  const map::Map m =
      map::LoadMap(std::string(STICKREP_SOURCE_DIR) + "/maps/wells_hall_7f_modified.yaml");
  std::mt19937_64 rng(3);
  const MapWorld mw = BuildMapWorld(m, {}, rng);
  int ribbons = 0;
  for (const WallDecoration& d : mw.world.decorations) {
    if (d.intensity == MapWorldOptions{}.ribbon_intensity) {
      ++ribbons;
      EXPECT_NEAR(d.width_in, 24.0, 1.0);
    }
  }
  EXPECT_EQ(ribbons, 1);
}

TEST(RobotModelsTest, FillsTheWorldModelsFromTheShippedRobotDescription) {
  const sensing::RobotConfig config =
      sensing::LoadRobotConfigFile(sensing::DefaultRobotConfigPath());
  const RobotModels m = RobotModelsFromConfig(config);
  EXPECT_EQ(m.sonar.count, config.sonar_ring.count);
  EXPECT_DOUBLE_EQ(m.sonar.cone_deg, config.sonar_ring.cone_deg);
  EXPECT_DOUBLE_EQ(m.sonar.head_radius_in, config.sonar_ring.head_radius_in);
  EXPECT_DOUBLE_EQ(m.sonar.coaxial_yaw_deg, m.camera.mount_yaw_deg);
  EXPECT_DOUBLE_EQ(m.camera.fov_deg, config.camera.fov_deg);
  EXPECT_EQ(m.camera.width_px, config.camera.image_width_px);
  EXPECT_EQ(m.camera.height_px, config.camera.image_height_px);
  EXPECT_DOUBLE_EQ(m.base.max_speed_ftps, config.base.max_speed_ftps);
  EXPECT_DOUBLE_EQ(m.base.wheel_base_in, config.base.wheel_base_in);
}

TEST(RobotModelsTest, CoaxialSensorAndCameraOffsetFollowTheConfig) {
  sensing::RobotConfig config;
  config.camera.coaxial_sensor = 2;
  config.camera.offset_forward_in = 3.0;
  const RobotModels m = RobotModelsFromConfig(config, 90.0);
  // Sensor 2 (2 x 15° clockwise of sensor 0) must lie on the optical axis.
  EXPECT_DOUBLE_EQ(m.sonar.coaxial_yaw_deg - 2 * m.sonar.spacing_deg, m.camera.mount_yaw_deg);
  EXPECT_NEAR(m.camera.mount_forward_in, 0.0, 1e-12);
  EXPECT_NEAR(m.camera.mount_left_in, 3.0, 1e-12);
}

TEST(RobotModelsTest, BadFileIsAnInputError) {
  EXPECT_THROW(LoadRobotModels("/nonexistent/robot.yaml"), InputError);
}

TEST(SonarErrorAdapterTest, SurfacesConvertBothWays) {
  for (SurfaceType s : {SurfaceType::kConcrete, SurfaceType::kWood, SurfaceType::kCloth}) {
    EXPECT_EQ(FromSensingSurface(ToSensingSurface(s)), s);
    EXPECT_STREQ(sensing::ToString(ToSensingSurface(s)), ToString(s));
  }
}

TEST(SonarErrorAdapterTest, ConcreteHeadOnReadsTheTableError) {
  SurfaceTableErrorOptions options;
  options.table = UltrasoundTable::kTable42;
  const SurfaceTableSonarErrorModel model(options);
  std::mt19937_64 rng(5);
  double sum = 0.0;
  const int n = 2000;
  for (int i = 0; i < n; ++i) sum += *model.Apply(100.0, SurfaceType::kConcrete, 0.0, rng);
  // Table 4.2, concrete at 0°: 0.71 % +- 0.03 %.
  EXPECT_NEAR(sum / n, 100.71, 0.01);
}

TEST(SonarErrorAdapterTest, ErrorGrowsWithIncidenceAndClothIsLostObliquely) {
  const SurfaceTableSonarErrorModel model;
  std::mt19937_64 rng(5);
  const double at0 = *model.Apply(100.0, SurfaceType::kWood, 0.0, rng);
  const double at30 = *model.Apply(100.0, SurfaceType::kWood, DegToRad(30.0), rng);
  EXPECT_LT(at0, 100.1);
  EXPECT_GT(at30, 108.0);  // Tables 4.2/4.3: 16 % or 8.9 % at 30°
  EXPECT_FALSE(model.Apply(100.0, SurfaceType::kCloth, DegToRad(45.0), rng).has_value());
  EXPECT_FALSE(model.Apply(100.0, SurfaceType::kConcrete, DegToRad(50.0), rng).has_value());
}

TEST(SonarErrorAdapterTest, GrossReadingsCanBeSpuriousLateEchoes) {
  SurfaceTableErrorOptions options;
  options.gross = GrossReading::kRandomLong;
  const SurfaceTableSonarErrorModel model(options);
  std::mt19937_64 rng(5);
  const auto r = model.Apply(100.0, SurfaceType::kConcrete, DegToRad(60.0), rng);
  ASSERT_TRUE(r.has_value());
  EXPECT_GE(*r, 100.0);
  EXPECT_LE(*r, 420.0);
}

TEST(SonarErrorAdapterTest, DrivesTheRingSimulator) {
  const MapWorld mw = BoxRing();
  const Scene scene(mw.world);
  const SonarRingSimulator ring;
  std::mt19937_64 rng(11);
  const Pose2d X_WR{20.0, 136.0, kPi};  // 36 in from the north face, sensor 0 facing it
  const auto exact = ring.SenseExact(scene, X_WR);
  const auto noisy = ring.Sense(scene, X_WR, SurfaceTableSonarErrorModel{}, rng);
  ASSERT_TRUE(exact[0].valid && noisy[0].valid);
  EXPECT_NEAR(exact[0].range_in, 36.0 - 7.5, 1e-6);
  // Concrete head-on: 0.6-0.71 % long.
  EXPECT_GT(noisy[0].range_in, exact[0].range_in);
  EXPECT_THAT(noisy[0].range_in / exact[0].range_in, DoubleNear(1.0066, 0.002));
}

}  // namespace
}  // namespace stickrep::world
