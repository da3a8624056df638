// Unit tests of the ROS-free simulator core.
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "biovision_sim/differential_drive.hpp"
#include "biovision_sim/floor_plan.hpp"
#include "biovision_sim/kinematic_chain.hpp"
#include "biovision_sim/room_world_generator.hpp"
#include "biovision_sim/scene_renderer.hpp"
#include "biovision_sim/servo.hpp"
#include "biovision_sim/simulator_parameters.hpp"
#include "biovision_sim/stereo_calibration.hpp"
#include "biovision_sim/world.hpp"

using namespace biovision_sim;

namespace
{
// Optical frame (z forward, x right, y down) looking along world +x from `position`.
Eigen::Isometry3d lookingAlongX(const Eigen::Vector3d& position)
{
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  t.translation() = position;
  return t;
}

World wallWorld(double distance)
{
  World w = World::parse("name: test\nfloor: {size: 2}\n");
  Texture::Spec noise;
  noise.type = "noise";
  noise.colour_a = {40, 40, 40};
  noise.colour_b = {220, 220, 220};
  noise.period = 1.0;
  noise.feature = 0.02;
  World::Object wall;
  wall.label = "wall";
  wall.shape = "box";
  wall.position = Eigen::Vector3d(distance + 0.05, 0, 1.0);
  wall.size = Eigen::Vector3d(0.1, 8, 4);
  wall.texture = w.addTexture(noise);
  w.addObject(wall);
  return w;
}

// The message of the std::invalid_argument `f` throws, or "no error".
std::string invalidArgument(const std::function<void()>& f)
{
  try
  {
    f();
  }
  catch (const std::invalid_argument& e)
  {
    return e.what();
  }
  return "no error";
}

const double kNaN = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();
}  // namespace

TEST(SceneRenderer, FrontoParallelPlaneGivesTheAnalyticDisparity)
{
  const double baseline = 0.12;
  for (double z : {1.0, 2.5})
  {
    const World w = wallWorld(z);
    const SceneRenderer r(w, 2);
    const PinholeCamera cam = PinholeCamera::fromFieldOfView(320, 240, 43 * M_PI / 180);
    cv::Mat img, depth;
    r.render(lookingAlongX({0, 0, 1.0}), cam, img, depth);
    const double expected = cam.fx * baseline / z;
    int checked = 0;
    for (int y = 20; y < 220; y += 10)
      for (int x = 20; x < 300; x += 10)
      {
        const double d = cam.fx * baseline / depth.at<float>(y, x);
        EXPECT_NEAR(d, expected, 0.5) << "at " << x << "," << y;
        ++checked;
      }
    EXPECT_GT(checked, 500);
    // Textured, not blank.
    cv::Scalar mean, sd;
    cv::meanStdDev(img, mean, sd);
    EXPECT_GT(sd[0], 20.0);
  }
}

TEST(SceneRenderer, RightViewIsTheLeftShiftedByTheDisparity)
{
  // Rendering the right camera 0.12 m to the right shifts the wall by f B / Z pixels.
  const double z = 2.0, baseline = 0.12;
  const World w = wallWorld(z);
  const SceneRenderer r(w, 2);
  const PinholeCamera cam = PinholeCamera::fromFieldOfView(320, 240, 43 * M_PI / 180);
  cv::Mat left, right, depth;
  const Eigen::Isometry3d pose = lookingAlongX({0, 0, 1.0});
  r.render(pose, cam, left, depth);
  r.render(pose * Eigen::Translation3d(baseline, 0, 0), cam, right, depth);
  const int d = static_cast<int>(std::lround(cam.fx * baseline / z));
  const cv::Mat a = left(cv::Rect(60 + d, 40, 150, 150)), b = right(cv::Rect(60, 40, 150, 150));
  cv::Mat diff;
  cv::absdiff(a, b, diff);
  EXPECT_LT(cv::mean(diff)[0], 6.0) << "left(x) != right(x - d)";
  cv::absdiff(left(cv::Rect(60, 40, 150, 150)), b, diff);
  EXPECT_GT(cv::mean(diff)[0], 10.0) << "texture too flat for the check";
}

TEST(SceneRenderer, BackgroundHasInfiniteDepth)
{
  const World w = World::parse("floor: {size: 1}\n");
  const SceneRenderer r(w, 1);
  const PinholeCamera cam = PinholeCamera::fromFieldOfView(64, 48, 1.0);
  cv::Mat img, depth;
  r.render(lookingAlongX({-5, 0, 1.0}), cam, img, depth);  // looking over the small floor
  EXPECT_TRUE(std::isinf(depth.at<float>(0, 32)));
  EXPECT_EQ(img.at<cv::Vec3b>(0, 32), w.background());
}

TEST(Servo, ReachesTheTargetWithinTheSpeedBoundAndStaysInsideTheLimits)
{
  Servo pan(-M_PI / 2, M_PI / 2, 3.0);
  EXPECT_FALSE(pan.command(1.2));
  double t = 0;
  while (std::abs(pan.position() - 1.2) > 1e-9 && t < 10)
  {
    const double before = pan.position();
    pan.step(0.02);
    EXPECT_LE(std::abs(pan.position() - before), 3.0 * 0.02 + 1e-12);
    t += 0.02;
  }
  EXPECT_NEAR(t, 1.2 / 3.0, 0.021);
  // Random commands, far beyond the limits, and NaN: never outside.
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> any(-10, 10);
  for (int i = 0; i < 2000; ++i)
  {
    pan.command(i % 97 == 0 ? NAN : any(rng));
    pan.step(0.02);
    ASSERT_GE(pan.position(), -M_PI / 2);
    ASSERT_LE(pan.position(), M_PI / 2);
  }
  EXPECT_TRUE(pan.command(5.0));  // clamped
  EXPECT_DOUBLE_EQ(pan.target(), M_PI / 2);
}

TEST(DifferentialDrive, IntegrationMatchesTheKinematicModel)
{
  const World empty = World::parse("floor: {size: 100}\n");
  DifferentialDrive::Limits lim;
  lim.linear_accel = 1e9;  // ideal speeds, to compare with the closed form
  lim.angular_accel = 1e9;
  DifferentialDrive base(lim);
  const double v = 0.5, w = 0.4;
  base.command(v, w);
  const double T = 3.0, dt = 0.02;
  for (double t = 0; t < T - 1e-9; t += dt)
    base.step(dt, empty);
  // Closed form of the circular arc.
  EXPECT_NEAR(base.x(), v / w * std::sin(w * T), 1e-6);
  EXPECT_NEAR(base.y(), v / w * (1 - std::cos(w * T)), 1e-6);
  EXPECT_NEAR(base.yaw(), w * T, 1e-9);
  // Limits clamp commands; NaN stops.
  base.command(10, 100);
  base.step(dt, empty);
  EXPECT_LE(base.linear(), lim.max_linear);
  EXPECT_LE(base.angular(), lim.max_angular);
  base.command(NAN, 0);
  base.step(dt, empty);
  EXPECT_EQ(base.linear(), 0.0);
}

TEST(DifferentialDrive, AccelerationIsLimited)
{
  const World empty = World::parse("floor: {size: 100}\n");
  DifferentialDrive base{DifferentialDrive::Limits()};
  base.command(1.0, 0);
  base.step(0.1, empty);
  EXPECT_NEAR(base.linear(), 0.03, 1e-9);  // 0.3 m/s^2 for 0.1 s
}

TEST(DifferentialDrive, CollisionStopsTheBase)
{
  const World w = wallWorld(2.0);  // wall face at x = 2.0
  DifferentialDrive base{DifferentialDrive::Limits()};
  base.command(0.5, 0);
  bool collided = false;
  for (int i = 0; i < 2000 && !collided; ++i)
    collided = base.step(0.02, w);
  ASSERT_TRUE(collided);
  EXPECT_EQ(base.collidedWith(), "wall");
  EXPECT_LE(base.x(), 2.0 - base.limits().radius + 1e-6);
  EXPECT_EQ(base.linear(), 0.0);
  const double x = base.x();
  base.step(0.02, w);  // stays stopped
  EXPECT_EQ(base.x(), x);
}

namespace
{
// A disc of radius 0.5 at (3, 0) and a 2 x 1 box at (0, 4) turned by 90 deg (so 1 wide in x, 2 long in y).
World twoObstacles()
{
  World w = World::parse("name: test\nfloor: {size: 2}\n");
  World::Object disc;
  disc.label = "bin";
  disc.shape = "cylinder";
  disc.position = Eigen::Vector3d(3, 0, 0.3);
  disc.size = Eigen::Vector3d(1.0, 1.0, 0.6);
  w.addObject(disc);
  World::Object box;
  box.label = "crate";
  box.shape = "box";
  box.position = Eigen::Vector3d(0, 4, 0.5);
  box.yaw = M_PI / 2;
  box.size = Eigen::Vector3d(2, 1, 1);
  w.addObject(box);
  World::Object lamp = box;  // hangs above the robot: not in the plan
  lamp.label = "lamp";
  lamp.position = Eigen::Vector3d(-3, 0, 2.0);
  lamp.size = Eigen::Vector3d(0.5, 0.5, 0.2);
  w.addObject(lamp);
  World::Object rug = box;  // obstacle: false
  rug.label = "rug";
  rug.obstacle = false;
  rug.position = Eigen::Vector3d(-3, -3, 0.01);
  w.addObject(rug);
  return w;
}
}  // namespace

TEST(FloorPlan, KeepsOnlyFootprintsTheBaseCanHit)
{
  const FloorPlan plan(twoObstacles());
  ASSERT_EQ(plan.footprints().size(), 2u);
  EXPECT_EQ(plan.footprints()[0].label, "bin");
  EXPECT_TRUE(plan.footprints()[0].disc);
  EXPECT_EQ(plan.footprints()[1].label, "crate");
}

TEST(FloorPlan, ClearanceIsTheDistanceToTheNearestBoundary)
{
  const FloorPlan plan(twoObstacles());
  EXPECT_NEAR(plan.clearance(1.0, 0.0), 1.5, 1e-9);  // disc edge at x = 2.5
  EXPECT_NEAR(plan.clearance(0.0, 2.0), 1.0, 1e-9);  // the turned box spans y in [3, 5]
  EXPECT_NEAR(plan.clearance(1.5, 4.0), 1.0, 1e-9);  // and x in [-0.5, 0.5]
  EXPECT_EQ(plan.clearance(3.1, 0.1), 0.0);          // inside the disc
  EXPECT_EQ(plan.obstacleAt(2.0, 0.0, 0.6), "bin");
  EXPECT_EQ(plan.obstacleAt(2.0, 0.0, 0.4), "");
  EXPECT_EQ(plan.obstacleAt(-3.0, 0.0, 0.4), "");  // under the lamp
  EXPECT_EQ(FloorPlan(World::parse("name: e\n")).clearance(0, 0), kInf);
}

TEST(FloorPlan, RangeMeetsTheFirstBoundaryAlongTheBearing)
{
  const FloorPlan plan(twoObstacles());
  EXPECT_NEAR(plan.range(0, 0, 0.0, 10), 2.5, 1e-9);
  EXPECT_NEAR(plan.range(0, 0, M_PI / 2, 10), 3.0, 1e-9);
  EXPECT_EQ(plan.range(0, 0, M_PI / 2, 2.9), kInf);  // beyond max_range
  EXPECT_EQ(plan.range(0, 0, M_PI, 10), kInf);       // nothing behind
  // Grazing the disc's top at y = 0.4: enters where x = 3 - sqrt(0.25 - 0.16) = 2.7.
  EXPECT_NEAR(plan.range(0, 0.4, 0.0, 10), 2.7, 1e-9);
  EXPECT_EQ(plan.range(3, 0, 1.0, 10), 0.0);  // from inside
  // Along a diagonal into the box's corner region: the ray from (2, 2) at 135 deg enters x = 0.5 at y = 3.5.
  EXPECT_NEAR(plan.range(2, 2, 3 * M_PI / 4, 10), std::hypot(1.5, 1.5), 1e-9);
}

TEST(FloorPlan, VisibleFootprintsAreInViewInRangeAndNotHidden)
{
  const FloorPlan plan(twoObstacles());  // bin at (3, 0), crate at (0, 4)
  auto labelsOf = [](const FloorPlan& p, const std::vector<FloorPlan::Sighting>& s) {
    std::string l;
    for (const auto& v : s)
      l += p.footprints().at(v.index).label + " ";
    return l;
  };
  auto labels = [&](const std::vector<FloorPlan::Sighting>& s) { return labelsOf(plan, s); };
  EXPECT_EQ(labels(plan.visible(0, 0, 0.0, 0.4, 10)), "bin ");
  EXPECT_EQ(labels(plan.visible(0, 0, M_PI / 2, 0.4, 10)), "crate ");
  EXPECT_EQ(labels(plan.visible(0, 0, M_PI / 4, M_PI / 2, 10)), "bin crate ");
  EXPECT_EQ(labels(plan.visible(0, 0, 0.0, 0.4, 2.9)), "");  // the bin's centre is 3 m away
  EXPECT_EQ(labels(plan.visible(6, 0, M_PI, 0.4, 10)), "bin ");
  // A viewer behind the crate at (0, 6) looking down -y with a narrow view sees the crate 2 m away.
  const auto s = plan.visible(0, 6, -M_PI / 2, 0.1, 10);
  ASSERT_EQ(s.size(), 1u);
  EXPECT_NEAR(s[0].distance, 2.0, 1e-9);
  EXPECT_NEAR(s[0].bearing, -M_PI / 2, 1e-9);
  // Hidden: a viewer at (6, 0) with a second disc put between it and the bin.
  World w = twoObstacles();
  World::Object blocker;
  blocker.label = "blocker";
  blocker.shape = "cylinder";
  blocker.position = Eigen::Vector3d(4.5, 0, 0.3);
  blocker.size = Eigen::Vector3d(0.4, 0.4, 0.6);
  w.addObject(blocker);
  const FloorPlan hidden(w);
  EXPECT_EQ(labelsOf(hidden, hidden.visible(6, 0, M_PI, 0.4, 10)), "blocker ");
}

TEST(FloorPlan, RasterMarksTheFootprintCells)
{
  const FloorPlan plan(twoObstacles());
  const cv::Mat1b grid = plan.rasterize(-1.0, -1.0, 0.1, 70, 50);  // x in [-1, 4), y in [-1, 6)
  auto at = [&](double x, double y) { return grid(int((y + 1.0) / 0.1), int((x + 1.0) / 0.1)); };
  EXPECT_EQ(at(3.05, 0.05), 255);  // disc centre
  EXPECT_EQ(at(0.05, 4.05), 255);  // box centre
  EXPECT_EQ(at(1.05, 1.05), 0);    // free
  EXPECT_EQ(at(3.05, -0.95), 0);   // beside the disc
  // The disc covers about pi r^2 = 0.785 m^2 = 78.5 cells, grown by half a cell all round.
  const cv::Mat1b disc = grid(cv::Rect(30, 0, 20, 20));
  EXPECT_NEAR(cv::countNonZero(disc), M_PI * 0.55 * 0.55 / 0.01, 8);
}

TEST(RoomWorldGenerator, RoomsAreSeededWithStartAndGoalApartAndClear)
{
  const RoomWorldGenerator generator;
  for (unsigned seed = 1; seed <= 20; ++seed)
  {
    const RoomWorldGenerator::Room room = generator.generate(seed);
    const FloorPlan plan(room.world);
    EXPECT_GE(std::hypot(room.goal_x - room.start_x, room.goal_y - room.start_y), 4.0) << "seed " << seed;
    EXPECT_GE(plan.clearance(room.goal_x, room.goal_y), generator.options().free_radius) << "seed " << seed;
    EXPECT_GE(plan.clearance(room.start_x, room.start_y), generator.options().free_radius) << "seed " << seed;
    EXPECT_GE(plan.footprints().size(), 4u + generator.options().min_clutter / 2) << "walls and some clutter";
    // Inside the room.
    EXPECT_GT(room.goal_x, 0);
    EXPECT_LT(room.goal_x, room.width);
    EXPECT_LT(std::abs(room.goal_y), room.depth / 2);
  }
  const RoomWorldGenerator::Room a = generator.generate(7), b = generator.generate(7), c = generator.generate(8);
  ASSERT_EQ(a.world.objects().size(), b.world.objects().size());
  for (size_t i = 0; i < a.world.objects().size(); ++i)
    EXPECT_EQ(a.world.objects()[i].position, b.world.objects()[i].position) << "the same seed, the same world";
  EXPECT_EQ(a.goal_x, b.goal_x);
  EXPECT_NE(a.goal_x, c.goal_x) << "another seed, another world";
}

TEST(RoomWorldGenerator, BadOptionsThrowNamingTheField)
{
  RoomWorldGenerator::Options o;
  o.min_start_goal = 20.0;
  EXPECT_THROW(RoomWorldGenerator{o}, std::invalid_argument);
  o = RoomWorldGenerator::Options();
  o.min_clutter = 9;
  try
  {
    RoomWorldGenerator g(o);
    ADD_FAILURE() << "min_clutter > max_clutter accepted";
  }
  catch (const std::invalid_argument& e)
  {
    EXPECT_NE(std::string(e.what()).find("min_clutter"), std::string::npos) << e.what();
  }
}

TEST(KinematicChain, ComposesOriginsAndJoints)
{
  KinematicChain chain;
  KinematicChain::Link mast;
  mast.origin.translation() << 0, 0, 1.0;
  chain.append(mast);
  KinematicChain::Link pan;
  pan.joint = "pan";
  pan.axis = Eigen::Vector3d::UnitZ();
  chain.append(pan);
  KinematicChain::Link camera;
  camera.origin.translation() << 0.1, 0, 0;
  chain.append(camera);
  const Eigen::Isometry3d t = chain.evaluate({"pan"}, {M_PI / 2});
  EXPECT_NEAR(t.translation().x(), 0.0, 1e-12);
  EXPECT_NEAR(t.translation().y(), 0.1, 1e-12);
  EXPECT_NEAR(t.translation().z(), 1.0, 1e-12);
}

TEST(World, BadFilesNameTheLine)
{
  auto message = [](const std::string& yaml) {
    try
    {
      World::parse(yaml, "w.yaml");
    }
    catch (const std::runtime_error& e)
    {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message("objects:\n  - {label: a, shape: sphere}\n").find("w.yaml:2"), std::string::npos);
  EXPECT_NE(message("objects:\n  - {shape: box}\n").find("label"), std::string::npos);
  EXPECT_NE(message("objects:\n  - {label: a, position: [1, 2]}\n").find("w.yaml:2"), std::string::npos);
  EXPECT_NE(message("floor: {texture: {type: marble}}\n").find("marble"), std::string::npos);
  EXPECT_NE(message("objects: [\n").find("YAML syntax"), std::string::npos);
  EXPECT_NE(message("objects:\n  - {label: a, size: [1, 0, 1]}\n").find("positive"), std::string::npos);
  EXPECT_EQ(message("objects:\n  - {label: a, shape: cylinder, radius: 0.1, height: 0.3}\n"), "no error");
}

TEST(World, PlaceObjectAddsOrReplacesByLabelAndRefusesBadObjects)
{
  World w = World::parse("objects:\n  - {label: crate, position: [1, 0, 0.2], size: [0.4, 0.4, 0.4]}\n");
  EXPECT_EQ(w.placeObject("{label: bin, shape: cylinder, position: [2, 1, 0.3], radius: 0.2, height: 0.6}"), 1);
  ASSERT_EQ(w.objects().size(), 2u);
  EXPECT_DOUBLE_EQ(w.objects()[1].size.x(), 0.4);
  // The same label moves the object instead of adding a second one.
  EXPECT_EQ(w.placeObject("{label: crate, position: [-1, 2, 0.2], size: [0.4, 0.4, 0.4]}"), 0);
  ASSERT_EQ(w.objects().size(), 2u);
  EXPECT_DOUBLE_EQ(w.objects()[0].position.x(), -1.0);
  const size_t textures = w.textures().size();
  for (const char* bad : {"{shape: box}", "{label: x, shape: sphere}", "[1, 2]", "{label: x, size: [1, 0, 1]}",
                          "{label: crate, texture: {type: marble}}", "{label: x"})
  {
    EXPECT_THROW(w.placeObject(bad, "sim/place_object"), std::runtime_error) << bad;
    EXPECT_EQ(w.objects().size(), 2u) << bad;
    EXPECT_EQ(w.textures().size(), textures) << bad;
  }
  EXPECT_DOUBLE_EQ(w.objects()[0].position.x(), -1.0);
}

TEST(World, ShippedWorldsLoad)
{
  for (const char* f : {"tabletop.yaml", "corridor.yaml"})
  {
    const World w = World::load(std::string(BIOVISION_WORLDS_DIR) + "/" + f);
    EXPECT_GE(w.objects().size(), 5u) << f;
  }
  const World table = World::load(std::string(BIOVISION_WORLDS_DIR) + "/tabletop.yaml");
  int lookalikes = 0;
  for (const auto& o : table.objects())
    lookalikes += o.label.rfind("mug_red", 0) == 0;
  EXPECT_EQ(lookalikes, 2);
}

TEST(StereoCalibration, FocalLengthFollowsTheFieldOfView)
{
  // tan(45 deg) = 1: half the width is the focal length.
  const auto wide = StereoCalibration::fromFieldOfView(320, 240, M_PI / 2, 0.12);
  EXPECT_NEAR(wide.camera().fx, 160.0, 1e-9);
  EXPECT_NEAR(wide.left().K[4], 160.0, 1e-9);  // square pixels: fy = fx
  const auto bumblebee = StereoCalibration::fromFieldOfView(320, 240, 43 * M_PI / 180, 0.12);
  EXPECT_NEAR(bumblebee.camera().fx, 406.18, 0.01);  // 160 / tan(21.5 deg)
  const auto given = StereoCalibration::fromFocalLength(640, 480, 500.0, 0.12);
  EXPECT_EQ(given.left().K[0], 500.0);
  EXPECT_EQ(given.right().P[0], 500.0);
}

TEST(StereoCalibration, PrincipalPointIsTheImageCentre)
{
  const StereoCalibration::Camera left = StereoCalibration::fromFieldOfView(320, 240, 1.0, 0.12).left();
  EXPECT_EQ(left.width, 320);
  EXPECT_EQ(left.height, 240);
  // Pixel centres at integer coordinates: the centre of 320 columns is 159.5.
  EXPECT_EQ(left.K[2], 159.5);
  EXPECT_EQ(left.K[5], 119.5);
  EXPECT_EQ(left.P[2], 159.5);
  EXPECT_EQ(left.P[6], 119.5);
  const std::array<double, 9> k_pattern = {1, 0, 1, 0, 1, 1, 0, 0, 1};  // nonzero entries of K
  for (size_t i = 0; i < 9; ++i)
    EXPECT_EQ(left.K[i] != 0.0, k_pattern[i] != 0.0) << "K[" << i << "]";
  EXPECT_EQ(left.K[8], 1.0);
  EXPECT_EQ(left.P[10], 1.0);
}

TEST(StereoCalibration, RightProjectionGivesTheDisparityOfThePair)
{
  const double baseline = 0.12;
  const auto pair = StereoCalibration::fromFieldOfView(320, 240, 43 * M_PI / 180, baseline);
  const auto left = pair.left(), right = pair.right();
  EXPECT_EQ(left.P[3], 0.0);
  EXPECT_LT(right.P[3], 0.0);  // ROS convention: Tx = -fx * B
  EXPECT_NEAR(right.P[3], -pair.camera().fx * baseline, 1e-12);
  EXPECT_EQ(pair.baseline(), baseline);
  for (size_t i : {0u, 1u, 2u, 4u, 5u, 6u, 7u, 8u, 9u, 10u, 11u})
    EXPECT_EQ(left.P[i], right.P[i]) << "P[" << i << "]";
  // A point at depth Z in the left optical frame: u_left - u_right = fx * B / Z.
  const double x = 0.3, y = -0.1, z = 2.0;
  auto u = [&](const StereoCalibration::Camera& c) { return (c.P[0] * x + c.P[2] * z + c.P[3]) / z; };
  auto v = [&](const StereoCalibration::Camera& c) { return (c.P[5] * y + c.P[6] * z + c.P[7]) / z; };
  EXPECT_NEAR(u(left) - u(right), pair.camera().fx * baseline / z, 1e-9);
  EXPECT_EQ(v(left), v(right));  // rectified: same row
  EXPECT_EQ(StereoCalibration::fromFieldOfView(320, 240, 1.0, 0.0).right().P[3], 0.0);
}

TEST(StereoCalibration, BadInputThrowsNamingTheArgument)
{
  const std::vector<std::pair<std::function<void()>, std::string>> cases = {
      {[] { StereoCalibration::fromFieldOfView(0, 240, 1.0, 0.1); }, "width"},
      {[] { StereoCalibration::fromFieldOfView(320, -1, 1.0, 0.1); }, "height"},
      {[] { StereoCalibration::fromFieldOfView(320, 240, 0.0, 0.1); }, "horizontal_fov"},
      {[] { StereoCalibration::fromFieldOfView(320, 240, M_PI, 0.1); }, "horizontal_fov"},
      {[] { StereoCalibration::fromFieldOfView(320, 240, kNaN, 0.1); }, "horizontal_fov"},
      {[] { StereoCalibration::fromFieldOfView(320, 240, 1.0, -0.1); }, "baseline"},
      {[] { StereoCalibration::fromFieldOfView(320, 240, 1.0, kNaN); }, "baseline"},
      {[] { StereoCalibration::fromFieldOfView(320, 240, 1.0, kInf); }, "baseline"},
      {[] { StereoCalibration::fromFocalLength(320, 240, 0.0, 0.1); }, "focal_length"},
      {[] { StereoCalibration::fromFocalLength(320, 240, kInf, 0.1); }, "focal_length"},
      {[] { StereoCalibration::fromFocalLength(0, 240, 400.0, 0.1); }, "width"},
  };
  for (const auto& c : cases)
    EXPECT_NE(invalidArgument(c.first).find(c.second), std::string::npos)
        << c.second << ": " << invalidArgument(c.first);
  EXPECT_EQ(invalidArgument([] { StereoCalibration::fromFocalLength(1, 1, 1e-3, 0.0); }), "no error");
}

TEST(SimulatorParameters, DefaultsAndRangeLimitsAreValid)
{
  SimulatorParameters p;
  EXPECT_NE(invalidArgument([&] { p.validate(); }).find("world"), std::string::npos);  // required
  p.world = "tabletop.yaml";
  EXPECT_EQ(invalidArgument([&] { p.validate(); }), "no error");
  p.width = 32;
  p.height = 24;
  p.physics_rate = p.camera_rate;
  p.blur_sigma = 10;
  p.real_time_factor = 0;
  p.supersample = 4;
  EXPECT_EQ(invalidArgument([&] { p.validate(); }), "no error");
}

TEST(SimulatorParameters, EachBadFieldThrowsNamingIt)
{
  using Edit = std::function<void(SimulatorParameters&)>;
  const std::vector<std::pair<Edit, std::string>> cases = {
      {[](SimulatorParameters& p) { p.camera_rate = 0; }, "camera_rate"},
      {[](SimulatorParameters& p) { p.camera_rate = kNaN; }, "camera_rate"},
      {[](SimulatorParameters& p) { p.physics_rate = 9; }, "physics_rate"},
      {[](SimulatorParameters& p) { p.width = 31; }, "width"},
      {[](SimulatorParameters& p) { p.height = 23; }, "height"},
      {[](SimulatorParameters& p) { p.width = 1 << 30; }, "width"},  // crashed with a cv::Exception (issue #23)
      {[](SimulatorParameters& p) { p.height = -5; }, "height"},
      {[](SimulatorParameters& p) { p.width = SimulatorParameters::kMaxImageSide + 1; }, "width"},
      {[](SimulatorParameters& p) { p.horizontal_fov_deg = 1; }, "horizontal_fov_deg"},
      {[](SimulatorParameters& p) { p.horizontal_fov_deg = 179; }, "horizontal_fov_deg"},
      {[](SimulatorParameters& p) { p.supersample = 0; }, "supersample"},
      {[](SimulatorParameters& p) { p.supersample = 5; }, "supersample"},
      {[](SimulatorParameters& p) { p.noise_sigma = -1; }, "noise_sigma"},
      {[](SimulatorParameters& p) { p.blur_sigma = 10.5; }, "blur_sigma"},
      {[](SimulatorParameters& p) { p.real_time_factor = -0.5; }, "real_time_factor"},
      {[](SimulatorParameters& p) { p.start_x = kNaN; }, "start_x"},
      {[](SimulatorParameters& p) { p.start_y = kInf; }, "start_y"},
      {[](SimulatorParameters& p) { p.start_yaw = kNaN; }, "start_yaw"},
      {[](SimulatorParameters& p) { p.servo_speed = 0; }, "servo_speed"},
  };
  for (const auto& c : cases)
  {
    SimulatorParameters p;
    p.world = "tabletop.yaml";
    c.first(p);
    const std::string message = invalidArgument([&] { p.validate(); });
    EXPECT_NE(message.find(c.second + " = "), std::string::npos) << c.second << ": " << message;
  }
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
