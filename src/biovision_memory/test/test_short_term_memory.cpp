#include <cmath>
#include <limits>
#include <stdexcept>

#include <gtest/gtest.h>

#include "biovision_memory/long_term_memory.hpp"
#include "biovision_memory/short_term_memory.hpp"
#include "biovision_memory/view_scanner.hpp"
#include "synthetic_view.hpp"

using biovision_memory::Pose2D;
using biovision_memory::ShortTermMemory;
using biovision_memory::ViewScan;
using namespace biovision_memory_test;

namespace
{
constexpr double kDeg = M_PI / 180.0;
constexpr double kTilt = 15 * kDeg;

// One strip that saw an obstacle at `point` (base_link), the others blind.
ViewScan scanWithObstacle(const Eigen::Vector2d& point)
{
  ViewScan scan;
  scan.max_range = 3.0;
  ViewScan::Strip s;
  s.centre_bearing = std::atan2(point.y(), point.x());
  s.nearest_point = point;
  s.nearest_range = static_cast<float>(point.norm());
  s.observed = true;
  scan.strips.push_back(s);
  return scan;
}
}  // namespace

TEST(ShortTermMemorySectors, TileMinus90To90In20DegreeSteps)
{
  ShortTermMemory stm;
  EXPECT_EQ(stm.sectorOf(-89.9 * kDeg), 0);
  EXPECT_EQ(stm.sectorOf(-70.1 * kDeg), 0);
  EXPECT_EQ(stm.sectorOf(-69.9 * kDeg), 1);
  EXPECT_EQ(stm.sectorOf(0.0), 4);
  EXPECT_EQ(stm.sectorOf(9.9 * kDeg), 4);
  EXPECT_EQ(stm.sectorOf(10.1 * kDeg), 5);
  EXPECT_EQ(stm.sectorOf(89.9 * kDeg), 8);
  EXPECT_EQ(stm.sectorOf(90.5 * kDeg), -1);
  EXPECT_EQ(stm.sectorOf(-91 * kDeg), -1);
  EXPECT_EQ(stm.sectorOf(M_PI), -1);
  EXPECT_NEAR(stm.sectorCentre(0), -80 * kDeg, 1e-9);
  EXPECT_NEAR(stm.sectorCentre(8), 80 * kDeg, 1e-9);
}

// A post 1.5 m away at bearing theta; the head panned to look at it from several pans. The post's sector
// holds its distance, the other sectors the strips look into are free, the rest unknown.
TEST(ShortTermMemorySectors, APostLandsInItsSectorAtSeveralPans)
{
  const auto cam = camera160();
  for (double pan_deg : {-60.0, -35.0, 0.0, 25.0, 55.0})
  {
    for (double offset_deg : {-12.0, 0.0, 12.0})  // the post in the right, centre and left strip
    {
      const double pan = pan_deg * kDeg, theta = (pan_deg + offset_deg) * kDeg;
      const double range = 1.5, radius = 0.1;
      const Cylinder post{range * std::cos(theta), range * std::sin(theta), radius, 1.0};
      ShortTermMemory stm;
      const auto pose = cameraPose(pan, kTilt);
      stm.update(renderDisparity(cam, pose, {post}), cam, pose, Pose2D{}, 1.0);
      const auto sectors = stm.sectors();
      const int expected = stm.sectorOf(theta);
      SCOPED_TRACE("pan " + std::to_string(pan_deg) + " offset " + std::to_string(offset_deg));
      ASSERT_GE(expected, 0);
      EXPECT_TRUE(sectors[expected].obstacle);
      EXPECT_NEAR(sectors[expected].distance, range - radius, 0.06);
      EXPECT_DOUBLE_EQ(sectors[expected].confidence, 1.0);
      int known = 0;
      for (int i = 0; i < 9; ++i)
      {
        if (sectors[i].confidence > 0)
          ++known;
        if (i != expected)
        {
          EXPECT_FALSE(sectors[i].obstacle) << "sector " << i;
        }
        // A sector far from the view is untouched.
        if (std::abs(stm.sectorCentre(i) - pan) > 40 * kDeg)
        {
          EXPECT_EQ(sectors[i].confidence, 0.0) << "sector " << i;
        }
      }
      EXPECT_GE(known, 1);
      EXPECT_LE(known, 3);
    }
  }
}

TEST(ShortTermMemorySectors, EmptyFloorIsFreeInTheViewedSectorsOnly)
{
  const auto cam = camera160();
  ShortTermMemory stm;
  const auto pose = cameraPose(40 * kDeg, kTilt);
  stm.update(renderDisparity(cam, pose, {}), cam, pose, Pose2D{}, 0.5);
  const auto sectors = stm.sectors();
  // Strip centres at 40 and 40 ± 14.3 deg: sectors 5 (10..30), 6 (30..50) and 7 (50..70).
  for (int i = 0; i < 9; ++i)
  {
    const bool viewed = i >= 5 && i <= 7;
    EXPECT_EQ(sectors[i].confidence > 0, viewed) << i;
    EXPECT_FALSE(sectors[i].obstacle) << i;
    EXPECT_TRUE(std::isinf(sectors[i].distance)) << i;
  }
}

// The camera cannot see the floor under its lowest rows, but it sees anything standing there: the ray to the
// nearest floor point passes lower than min_obstacle_height from (1 − h/H) of its length on.
TEST(ViewScanFreeSpace, StartsWhereTheRayToTheNearestFloorPointIsLowerThanAnObstacle)
{
  const auto cam = camera160();
  const double tilt = 0.3, height = 1.1;
  const auto pose = cameraPose(0.0, tilt, height);
  const biovision_memory::ViewScanParameters p;
  const ViewScan scan = biovision_memory::ViewScanner(p).scan(renderDisparity(cam, pose, {}), cam, pose);
  // The lowest sampled row (pixel_step 2 from row 1) of the centre column.
  const int v = 1 + 2 * ((120 - 1 - 1) / 2);
  const double nearest_floor = height / std::tan(tilt + std::atan((v - cam.cy) / cam.fy));
  const ViewScan::Bin& b = scan.bins[scan.binOf(0.0)];
  EXPECT_NEAR(b.free_from, nearest_floor * (1 - p.min_obstacle_height / height), 0.03);
  EXPECT_LT(b.free_from, nearest_floor - 0.15);
  EXPECT_GE(b.free_to, p.max_range - 1e-3);
  // The floor's extent along the rays, from the camera (at base_link's origin here), and the camera's height.
  EXPECT_NEAR(b.floor_near, nearest_floor, 0.03);
  EXPECT_GT(b.floor_far, b.floor_near);
  EXPECT_NEAR(scan.camera_height, height, 1e-9);
}

namespace
{
// A post of `height` [m] `x` m ahead of a camera 1.1 m up tilted 0.3 rad down, seen in 3 frames, then taken
// away and the empty view seen 6 times: the LTM cells round it before and after, and the free_from of the
// empty view straight ahead.
struct ShownAndTakenAway
{
  int cells_before = 0, cells_after = 0;
  float free_from = 0.0f;
};
ShownAndTakenAway showAndTakeAway(double x, double height)
{
  const auto cam = camera160();
  const auto pose = cameraPose(0.0, 0.3, 1.1);
  ShortTermMemory stm;
  biovision_memory::LongTermMemory ltm;
  double t = 0.0;
  for (int i = 0; i < 3; ++i, t += 0.5)
  {
    stm.update(renderDisparity(cam, pose, {{x, 0.0, 0.1, height}}), cam, pose, Pose2D{}, t);
    ltm.update(stm.lastScan(), Pose2D{}, t);
  }
  auto cellsNear = [&] {
    int n = 0;
    for (double cx = x - 0.2; cx <= x + 0.2; cx += 0.1)
      for (double cy = -0.2; cy <= 0.2; cy += 0.1)
        n += ltm.cellAt(cx, cy) != nullptr;
    return n;
  };
  ShownAndTakenAway r;
  r.cells_before = cellsNear();
  const ViewScan empty =
      biovision_memory::ViewScanner(stm.parameters().scan).scan(renderDisparity(cam, pose, {}), cam, pose);
  r.free_from = empty.bins[empty.binOf(0.0)].free_from;
  for (int i = 0; i < 6; ++i, t += 0.5)
    ltm.update(empty, Pose2D{}, t);
  r.cells_after = cellsNear();
  return r;
}
}  // namespace

// A box seen 1.5 m ahead, then taken away (mission_director shows the robot its target there): the robot
// standing still must forget it, although its cells are nearer than any floor point the camera sees.
TEST(ViewScanFreeSpace, AnObstacleRemovedFromTheBlindFloorIsForgottenByTheLongTermMemory)
{
  const auto r = showAndTakeAway(1.5, 0.4);
  ASSERT_GT(r.cells_before, 0) << "the box was not mapped";
  ASSERT_GT(r.free_from, 0.0f);
  EXPECT_EQ(r.cells_after, 0);
}

// The same nearer than the floor the camera sees (free_from): the post's top, which the camera saw, would be
// in view; a ray to the floor crosses its cell below that top. (Before the cells kept their top, such a post
// — the demo's target, shown 2.2 m ahead and approached — stayed for good.)
TEST(ViewScanFreeSpace, AnObstacleRemovedNearerThanTheFloorSeenIsForgottenByItsTop)
{
  const double x = 1.2;  // a 0.6 m post; the camera sees the floor from 1.66 m and the post from 0.37 m up
  const auto r = showAndTakeAway(x, 0.6);
  ASSERT_GT(r.cells_before, 0) << "the post was not mapped";
  ASSERT_GT(r.free_from, x + 0.2) << "the post must stand nearer than the floor seen";
  EXPECT_EQ(r.cells_after, 0);
}

TEST(ShortTermMemorySectors, ABlindOrNanViewChangesNothing)
{
  const auto cam = camera160();
  ShortTermMemory stm;
  const auto pose = cameraPose(0.0, kTilt);
  cv::Mat nan(120, 160, CV_32F, cv::Scalar(std::numeric_limits<float>::quiet_NaN()));
  stm.update(nan, cam, pose, Pose2D{}, 1.0);
  for (const auto& s : stm.sectors())
    EXPECT_EQ(s.confidence, 0.0);
  EXPECT_EQ(stm.lastScan().valid_pixels, 0);
  EXPECT_GT(stm.lastScan().invalid_pixels, 0);
}

TEST(ShortTermMemorySectors, BadInputThrowsAndKeepsTheMemory)
{
  ShortTermMemory stm;
  stm.update(scanWithObstacle({1.0, 0.0}), Pose2D{}, 1.0);
  const auto cam = camera160();
  EXPECT_THROW(stm.update(cv::Mat(), cam, cameraPose(0, kTilt), Pose2D{}, 2.0), std::invalid_argument);
  EXPECT_THROW(stm.update(cv::Mat(120, 160, CV_8U, cv::Scalar(0)), cam, cameraPose(0, kTilt), Pose2D{}, 2.0),
               std::invalid_argument);
  auto bad = cam;
  bad.baseline = 0.0;
  EXPECT_THROW(stm.update(cv::Mat(120, 160, CV_32F, cv::Scalar(5)), bad, cameraPose(0, kTilt), Pose2D{}, 2.0),
               std::invalid_argument);
  EXPECT_TRUE(stm.sectors()[4].obstacle);
  EXPECT_NEAR(stm.sectors()[4].distance, 1.0, 1e-9);
}

TEST(ShortTermMemoryMapCompletion, TheMapFillsWhatTheStmDoesNotKnowWithinTheRadius)
{
  ShortTermMemory stm;                                             // map_completion_radius 0.6 m
  stm.update(scanWithObstacle({1.0, 0.0}), Pose2D{0, 0, 0}, 0.0);  // an obstacle 1 m ahead, sector 4
  biovision_memory::LongTermMemory ltm;
  // The base stands at (2, 1) in the map facing +y (yaw 90 deg): map point (2 - 0.45, 1 + 0.26) is 0.45 m to
  // its left and 0.26 m ahead, at bearing atan2(0.45, 0.26) = +60 deg (sector 7: +50..+70 deg).
  const Pose2D base{2.0, 1.0, 90 * kDeg};
  ltm.observe(2.0 - 0.45, 1.0 + 0.26, 0.0);
  ltm.observe(2.0 + 0.7, 1.0, 0.0);          // 0.7 m to the right: beyond the radius
  ltm.observe(2.0 + 0.05, 1.0 + 0.55, 0.0);  // 0.55 m ahead, nearer than the STM's 1 m: it wins
  const auto plain = stm.sectors();
  const auto completed = stm.sectors(ltm, base);
  ASSERT_EQ(completed.size(), plain.size());
  const double cell = ltm.parameters().cell_size;
  const double side = std::hypot(ltm.cellCentre(ltm.cellIndex(2.0 - 0.45)) - 2.0,
                                 ltm.cellCentre(ltm.cellIndex(1.0 + 0.26)) - 1.0);
  EXPECT_EQ(plain[7].confidence, 0.0);
  EXPECT_TRUE(completed[7].obstacle);
  EXPECT_NEAR(completed[7].distance, side - cell / 2, 1e-9);
  EXPECT_NEAR(completed[7].offset, 2.0 - ltm.cellCentre(ltm.cellIndex(2.0 - 0.45)) - cell / 2, 1e-9)
      << "the cell's distance from the line ahead, less half a cell";
  EXPECT_EQ(completed[7].confidence, 1.0);
  for (int i : {0, 1, 2, 3})
    EXPECT_EQ(completed[i].confidence, 0.0) << "sector " << i << ": nothing within 0.6 m on the right";
  EXPECT_LT(completed[4].distance, 0.6) << "the map's nearer obstacle ahead";
  // The STM's own obstacle stays where it is nearer than the map's.
  ltm.clear();
  ltm.observe(2.0, 1.0 + 0.58, 0.0);
  stm.update(scanWithObstacle({0.4, 0.0}), Pose2D{0, 0, 0}, 0.1);
  EXPECT_NEAR(stm.sectors(ltm, base)[4].distance, 0.4, 1e-9);
  // Radius 0 (the thesis), a non-finite or absurd pose: the STM alone.
  for (const Pose2D& pose : {Pose2D{NAN, 0, 0}, Pose2D{1e30, 0, 0}, Pose2D{0, 0, INFINITY}})
    EXPECT_EQ(stm.sectors(ltm, pose)[7].confidence, 0.0);
  auto parameters = stm.parameters();
  parameters.map_completion_radius = 0.0;
  stm.setParameters(parameters);
  ltm.observe(2.0 - 0.45, 1.0 + 0.26, 0.1);
  EXPECT_EQ(stm.sectors(ltm, base)[7].confidence, 0.0);
  parameters.map_completion_radius = -1.0;
  EXPECT_THROW(stm.setParameters(parameters), std::invalid_argument);
}

TEST(ShortTermMemoryMapCompletion, AFartherCellNearerTheLineAheadBoundsTheSectorsOffset)
{
  // The STM's point 0.22 m out at 45 deg, taken to reach its sector's near edge (+30 deg: 0.11 m off the line
  // ahead); a map cell farther out in the same sector (+30..+50 deg) but nearer the line (0.1 m): the distance
  // stays the STM's, the offset is the cell's.
  ShortTermMemory stm;
  stm.update(scanWithObstacle({0.155, 0.155}), Pose2D{0, 0, 0}, 0.0);
  biovision_memory::LongTermMemory ltm;
  ltm.observe(0.25, 0.15, 0.0);
  const double cell = ltm.parameters().cell_size;
  const double ahead = ltm.cellCentre(ltm.cellIndex(0.25)), left = ltm.cellCentre(ltm.cellIndex(0.15));
  ASSERT_EQ(stm.sectorOf(std::atan2(left, ahead)), 6);
  ASSERT_GT(std::hypot(ahead, left) - cell / 2, std::hypot(0.155, 0.155));
  ASSERT_LT(std::hypot(ahead, left), stm.parameters().map_completion_radius);
  const auto s = stm.sectors(ltm, Pose2D{0, 0, 0});
  EXPECT_NEAR(s[6].distance, std::hypot(0.155, 0.155), 1e-9);
  const double point_offset = std::hypot(0.155, 0.155) * std::sin(30 * kDeg);
  ASSERT_LT(left - cell / 2, point_offset);
  EXPECT_NEAR(s[6].offset, left - cell / 2, 1e-9);
  EXPECT_NEAR(stm.sectors()[6].offset, point_offset, 1e-9) << "without the map: the STM's point";
}

// Odometry: the remembered obstacle is rotated and translated with the base, not re-indexed.
TEST(ShortTermMemoryOdometry, RotationMovesAnObstacleToTheSectorOfItsNewBearing)
{
  ShortTermMemory stm;
  stm.update(scanWithObstacle({1.0, 0.0}), Pose2D{0, 0, 0}, 0.0);
  ASSERT_TRUE(stm.sectors()[4].obstacle);
  // The base turns 35 deg left: the obstacle is now at -35 deg, sector 2 (-50..-30 deg).
  stm.moveTo(Pose2D{0, 0, 35 * kDeg}, 0.1);
  auto s = stm.sectors();
  EXPECT_FALSE(s[4].obstacle);
  EXPECT_TRUE(s[2].obstacle);
  EXPECT_NEAR(s[2].distance, 1.0, 1e-9);
  // Turning back right by 50 deg: +15 deg, sector 5.
  stm.moveTo(Pose2D{0, 0, -15 * kDeg}, 0.2);
  s = stm.sectors();
  EXPECT_TRUE(s[5].obstacle);
  EXPECT_NEAR(s[5].distance, 1.0, 1e-9);
  // 100 deg to the left: the obstacle is at -115 deg, outside the field: dropped.
  stm.moveTo(Pose2D{0, 0, 100 * kDeg}, 0.3);
  for (const auto& sec : stm.sectors())
    EXPECT_FALSE(sec.obstacle);
}

TEST(ShortTermMemoryOdometry, TranslationChangesDistanceAndBearing)
{
  ShortTermMemory stm;
  stm.update(scanWithObstacle({2.0, 0.5}), Pose2D{1.0, 1.0, 0.0}, 0.0);  // 14 deg: sector 5
  ASSERT_TRUE(stm.sectors()[5].obstacle);
  // Forward 1.5 m: the obstacle at (0.5, 0.5) in the new base frame: 45 deg, sector 6, 0.707 m.
  stm.moveTo(Pose2D{2.5, 1.0, 0.0}, 1.0);
  auto s = stm.sectors();
  EXPECT_FALSE(s[5].obstacle);
  ASSERT_TRUE(s[6].obstacle);
  EXPECT_NEAR(s[6].distance, std::hypot(0.5, 0.5), 1e-9);
  EXPECT_NEAR(s[6].offset, std::hypot(0.5, 0.5) * std::sin(30 * kDeg), 1e-9) << "at its sector's near edge";
  // Travelled 1.5 m of horizon_distance, seen 1 s ago of obstacle_horizon_time: the lower share left.
  const auto& p = stm.parameters();
  EXPECT_NEAR(s[6].confidence, std::min(1.0 - 1.5 / p.horizon_distance, 1.0 - 1.0 / p.obstacle_horizon_time), 1e-9);
  // Back towards it (it stays ahead, in the field): kept just short of horizon_distance travelled, gone past it.
  const double back = p.horizon_distance - 1.5;
  stm.moveTo(Pose2D{2.5 - (back - 0.01), 1.0, 0.0}, 1.5);
  EXPECT_TRUE(stm.sectors()[5].obstacle || stm.sectors()[4].obstacle);
  stm.moveTo(Pose2D{2.5 - (back + 0.01), 1.0, 0.0}, 1.6);
  for (const auto& sec : stm.sectors())
    EXPECT_FALSE(sec.obstacle);
}

TEST(ShortTermMemoryOdometry, RotateAndTranslateTogether)
{
  ShortTermMemory stm;
  const Pose2D start{0.0, 0.0, 0.5};
  // An obstacle at odom (2, 2): in the start base frame.
  const Eigen::Vector2d odom_point(2.0, 2.0);
  const Eigen::Vector2d in_base = start.inverse().apply(odom_point);
  stm.update(scanWithObstacle(in_base), start, 0.0);
  const Pose2D end{1.0, 0.5, 1.2};  // moved and turned
  stm.moveTo(end, 0.5);
  const Eigen::Vector2d expected = end.inverse().apply(odom_point);
  const int sector = stm.sectorOf(std::atan2(expected.y(), expected.x()));
  ASSERT_GE(sector, 0);
  auto s = stm.sectors();
  ASSERT_TRUE(s[sector].obstacle);
  EXPECT_NEAR(s[sector].distance, expected.norm(), 1e-9);
}

TEST(ShortTermMemoryAgeing, FreeSpaceFadesFasterThanObstaclesAndNeverLooksFresh)
{
  const auto cam = camera160();
  ShortTermMemory stm;  // free horizon 3 s, obstacle horizon 10 s
  const auto pose = cameraPose(0.0, kTilt);
  const Cylinder post{1.2 * std::cos(-16 * kDeg), 1.2 * std::sin(-16 * kDeg), 0.1, 1.0};
  stm.update(renderDisparity(cam, pose, {post}), cam, pose, Pose2D{}, 0.0);
  auto s = stm.sectors();
  const int post_sector = stm.sectorOf(-16 * kDeg);  // 3
  ASSERT_TRUE(s[post_sector].obstacle);
  const int free_sector = stm.sectorOf(14.3 * kDeg);  // the left strip: 5
  ASSERT_FALSE(s[free_sector].obstacle);
  ASSERT_EQ(s[free_sector].confidence, 1.0);
  stm.moveTo(Pose2D{}, 1.5);
  s = stm.sectors();
  EXPECT_NEAR(s[free_sector].confidence, 0.5, 1e-9);
  EXPECT_NEAR(s[free_sector].age, 1.5, 1e-9);
  EXPECT_NEAR(s[post_sector].confidence, 0.85, 1e-9);
  stm.moveTo(Pose2D{}, 3.0);
  s = stm.sectors();
  EXPECT_EQ(s[free_sector].confidence, 0.0);  // unknown, not free
  EXPECT_TRUE(s[post_sector].obstacle);
  stm.moveTo(Pose2D{}, 10.0);
  s = stm.sectors();
  EXPECT_FALSE(s[post_sector].obstacle);
  EXPECT_EQ(s[post_sector].confidence, 0.0);
}

TEST(ShortTermMemoryAgeing, TimeGoingBackwardsResets)
{
  ShortTermMemory stm;
  stm.update(scanWithObstacle({1.0, 0.0}), Pose2D{}, 5.0);
  ASSERT_TRUE(stm.sectors()[4].obstacle);
  EXPECT_FALSE(stm.moveTo(Pose2D{}, 4.0));
  for (const auto& s : stm.sectors())
    EXPECT_EQ(s.confidence, 0.0);
  EXPECT_TRUE(stm.moveTo(Pose2D{}, 4.5));
}

TEST(ShortTermMemoryParameters, RejectNamesTheField)
{
  biovision_memory::ShortTermMemoryParameters p;
  p.scan.max_range = -1;
  try
  {
    ShortTermMemory stm(p);
    FAIL();
  }
  catch (const std::invalid_argument& e)
  {
    EXPECT_NE(std::string(e.what()).find("max_range"), std::string::npos);
  }
  ShortTermMemory stm;
  p = {};
  p.free_horizon_time = 0;
  EXPECT_THROW(stm.setParameters(p), std::invalid_argument);
  EXPECT_DOUBLE_EQ(stm.parameters().free_horizon_time, 3.0);
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
