#include "mission_trial.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <optional>
#include <random>
#include <sstream>
#include <stdexcept>

#include "biovision_attractor/base_attractor.hpp"
#include "biovision_attractor/head_attractor.hpp"
#include "biovision_memory/long_term_memory.hpp"
#include "biovision_memory/short_term_memory.hpp"
#include "biovision_sim/differential_drive.hpp"
#include "biovision_sim/floor_plan.hpp"
#include "biovision_sim/room_world_generator.hpp"
#include "biovision_sim/servo.hpp"
#include "biovision_tasks/task_manager.hpp"

namespace biovision_tasks
{
namespace
{
using biovision_attractor::BaseAttractor;
using biovision_attractor::HeadAttractor;
using biovision_memory::Pose2D;
using biovision_memory::ViewScan;

const char* kTarget = "target";

double wrap(double a)
{
  return std::remainder(a, 2 * M_PI);
}

// What the camera at pan `pan` sees of the floor plan, as the memory's ViewScan: one bin per degree
// across the view, the ranges of the plan (the stand-in for a disparity frame), 3 strips.
ViewScan groundTruthScan(const biovision_sim::FloorPlan& plan, const Pose2D& pose, double pan,
                         const MissionTrialOptions& o)
{
  ViewScan s;
  s.max_range = o.max_range;
  const int bins = static_cast<int>(std::ceil(o.horizontal_fov / (M_PI / 180)));
  s.bin_width = o.horizontal_fov / bins;
  s.bearing_min = pan - o.horizontal_fov / 2;
  s.bins.resize(bins);
  std::vector<float> range(bins);
  for (int i = 0; i < bins; ++i)
  {
    const double b = s.bearing_min + (i + 0.5) * s.bin_width;
    const double r = plan.range(pose.x, pose.y, pose.yaw + b, o.max_range);
    range[i] = std::isfinite(r) ? static_cast<float>(r) : ViewScan::kNone;
    s.bins[i].obstacle_range = range[i];
    s.bins[i].free_from = 0.3f;  // the floor in view starts in front of the base
    s.bins[i].free_to = std::min(range[i], static_cast<float>(o.max_range));
    if (std::isfinite(r))
      s.obstacle_points.emplace_back(r * std::cos(b), r * std::sin(b), 0.3);
  }
  for (int k = 0; k < 3; ++k)
  {
    ViewScan::Strip strip;
    strip.centre_bearing = s.bearing_min + (k + 0.5) * o.horizontal_fov / 3;
    strip.observed = true;
    for (int i = k * bins / 3; i < (k + 1) * bins / 3; ++i)
      if (range[i] < strip.nearest_range)
      {
        strip.nearest_range = range[i];
        const double b = s.bearing_min + (i + 0.5) * s.bin_width;
        strip.nearest_point = {range[i] * std::cos(b), range[i] * std::sin(b)};
      }
    s.strips.push_back(strip);
  }
  s.valid_pixels = bins;
  return s;
}

// The LTM as the task manager's map over the room (and a metre around it), strength scaled to 0..100.
OccupancyMap ltmMap(const biovision_memory::LongTermMemory& ltm, const biovision_sim::RoomWorldGenerator::Room& room)
{
  const double cell = ltm.parameters().cell_size;
  const double ox = -1.0, oy = -room.depth / 2 - 1.0;
  cv::Mat1b m(static_cast<int>(std::ceil((room.depth + 2) / cell)),
              static_cast<int>(std::ceil((room.width + 2) / cell)), uchar(0));
  const double max_strength = ltm.parameters().rules.max_strength;
  for (const auto& kv : ltm.cells())
  {
    const auto& c = kv.second;
    const int col = static_cast<int>(std::floor((ltm.cellCentre(c.ix) - ox) / cell));
    const int row = static_cast<int>(std::floor((ltm.cellCentre(c.iy) - oy) / cell));
    if (row >= 0 && col >= 0 && row < m.rows && col < m.cols)
      m(row, col) = static_cast<uchar>(std::clamp(100.0 * c.strength / max_strength, 0.0, 100.0));
  }
  return OccupancyMap(m, ox, oy, cell);
}

constexpr std::uintmax_t kMaxWorldBytes = 1 << 20;  // corridor.yaml: 4 KB
constexpr size_t kMaxWorldObjects = 100;            // corridor.yaml: 14
constexpr double kStartClearance = 0.3;             // [m] the Pioneer's 0.26 m radius and a little

// The demo's world as a room: the target object taken out (the trial puts its own there), the start at the
// origin facing +x, moved across and turned by up to o.start_jitter per seed.
biovision_sim::RoomWorldGenerator::Room roomFromWorld(unsigned seed, const MissionTrialOptions& o)
{
  // Bounded before parsing: the loader reads the whole file and builds a texture per object (1 MB each).
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::is_regular_file(o.world_file, ec) || fs::file_size(o.world_file, ec) > kMaxWorldBytes || ec)
    throw std::runtime_error("mission_eval: " + o.world_file + " is not a regular file of at most " +
                             std::to_string(kMaxWorldBytes) + " bytes");
  const biovision_sim::World loaded = biovision_sim::World::load(o.world_file);
  if (loaded.objects().size() > kMaxWorldObjects)
    throw std::runtime_error("mission_eval: " + o.world_file + " has " + std::to_string(loaded.objects().size()) +
                             " objects, more than " + std::to_string(kMaxWorldObjects));
  // Centres on the LTM map (x in [-1, 11] m, y in [-5, 5] m) or within 0.5 m of it (the corridor's back wall
  // stands at x = -1.05): an object off the map would be an obstacle the planner can never know.
  for (const auto& object : loaded.objects())
    if (!object.position.allFinite() || !std::isfinite(object.yaw) || !object.size.allFinite() ||
        !(object.position.x() >= -1.5 && object.position.x() <= 11.5 && std::abs(object.position.y()) <= 5.5) ||
        !(object.size.maxCoeff() <= 100.0))
      throw std::runtime_error("mission_eval: " + o.world_file + "'s '" + object.label +
                               "' is not finite or lies off the map (x in [-1, 11] m, y in [-5, 5] m)");
  biovision_sim::RoomWorldGenerator::Room room;
  room.seed = seed;
  room.width = 10.0;  // ltmMap's extent: x in [-1, 11], y in [-5, 5]
  room.depth = 8.0;
  bool found = false;
  for (const auto& object : loaded.objects())
    if (object.label == o.world_target)
    {
      if (found)
        throw std::runtime_error("mission_eval: " + o.world_file + " has two objects labelled '" + o.world_target +
                                 "'");
      if (object.size.head<2>().maxCoeff() > 1.0)
        throw std::runtime_error("mission_eval: " + o.world_file + "'s '" + o.world_target +
                                 "' is wider than 1 m: not a target to find");
      room.goal_x = object.position.x();
      room.goal_y = object.position.y();
      found = true;
    }
    else
      room.world.addObject(object);  // geometry only: the trial's FloorPlan reads no texture
  if (!found)
    throw std::runtime_error("mission_eval: " + o.world_file + " has no object labelled '" + o.world_target + "'");
  if (!(room.goal_x >= -1.0 && room.goal_x <= room.width + 1.0 && std::abs(room.goal_y) <= room.depth / 2 + 1.0))
    throw std::runtime_error("mission_eval: " + o.world_file + "'s '" + o.world_target +
                             "' lies outside the map's x in [-1, 11] m, y in [-5, 5] m");
  // A start the base fits at (any jitter) and a target standing free, away from it.
  if (!(o.start_jitter >= 0.0 && o.start_jitter <= 1.0))
    throw std::runtime_error("mission_eval: start_jitter outside [0, 1]");
  const biovision_sim::FloorPlan plan(room.world);
  for (const double y : {-o.start_jitter, 0.0, o.start_jitter})
    if (plan.clearance(0.0, y) < kStartClearance)
      throw std::runtime_error("mission_eval: " + o.world_file + ": the start (0, " + std::to_string(y) +
                               ") is closer than " + std::to_string(kStartClearance) + " m to an object");
  if (plan.clearance(room.goal_x, room.goal_y) <= 0.0 || std::hypot(room.goal_x, room.goal_y) < 1.0 + o.start_jitter)
    throw std::runtime_error("mission_eval: " + o.world_file + "'s '" + o.world_target +
                             "' stands inside another object or within 1 m of the start");
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> jitter(-o.start_jitter, o.start_jitter);
  room.start_y = jitter(rng);
  room.start_yaw = jitter(rng);
  return room;
}

// New obstacles on the straight way from `from` to home, each clear of the robot, home and (by 1 m) of
// every footprint, so that the way round stays open.
int placeNewObstacles(biovision_sim::World& world, const cv::Point2d& from, const cv::Point2d& home, int n)
{
  int placed = 0;
  for (int k = 1; k <= n; ++k)
  {
    const cv::Point2d q = from + (home - from) * (static_cast<double>(k) / (n + 1));
    const biovision_sim::FloorPlan plan(world);
    if (cv::norm(q - from) < 1.0 || cv::norm(q - home) < 1.0 || plan.clearance(q.x, q.y) < 1.0)
      continue;
    biovision_sim::World::Object box;
    box.label = "new_obstacle_" + std::to_string(k);
    box.shape = "box";
    box.position = Eigen::Vector3d(q.x, q.y, 0.25);
    box.size = Eigen::Vector3d(0.4, 0.4, 0.5);
    world.addObject(box);
    ++placed;
  }
  return placed;
}

// The demo's rule (mission_director's place_obstacle) for a world file: one obstacle of the demo's size
// halfway home on the straight line, else up to 0.4 of the way either side in steps of 0.05, else the
// point of the path driven nearest halfway home; 1 m from the robot and home, 1 m from every footprint
// but the target's. No check that the way round stays open (the director's way_round_open): a placement
// that closes it shows up as a trial that does not return.
int placeDemoObstacle(biovision_sim::World& world, const cv::Point2d& from, const cv::Point2d& home,
                      const std::vector<cv::Point2d>& driven)
{
  biovision_sim::World others;
  for (const auto& object : world.objects())
    if (object.label != kTarget)
      others.addObject(object);
  const biovision_sim::FloorPlan plan(others);
  const auto clear = [&](const cv::Point2d& q) {
    return cv::norm(q - from) >= 1.0 && cv::norm(q - home) >= 1.0 && plan.clearance(q.x, q.y) >= 1.0;
  };
  std::vector<double> fractions;
  for (int k = -8; k <= 8; ++k)
    fractions.push_back(0.5 + 0.05 * k);
  std::stable_sort(fractions.begin(), fractions.end(),
                   [](double a, double b) { return std::abs(a - 0.5) < std::abs(b - 0.5); });
  std::optional<cv::Point2d> where;
  for (const double f : fractions)
    if (clear(from + (home - from) * f))
    {
      where = from + (home - from) * f;
      break;
    }
  if (!where)
  {
    const double half = cv::norm(home - from) / 2;
    double best = HUGE_VAL;
    for (size_t i = 0; i < driven.size(); i += 5)
      if (clear(driven[i]) && std::abs(cv::norm(driven[i] - home) - half) < best)
      {
        best = std::abs(cv::norm(driven[i] - home) - half);
        where = driven[i];
      }
  }
  if (!where)
    return 0;
  biovision_sim::World::Object box;
  box.label = "new_obstacle_1";
  box.shape = "box";
  box.position = Eigen::Vector3d(where->x, where->y, 0.25);
  box.size = Eigen::Vector3d(0.45, 0.45, 0.5);  // mission.launch's new_crate
  world.addObject(box);
  return 1;
}
}  // namespace

void checkMissionWorld(const MissionTrialOptions& o)
{
  if (!o.world_file.empty())
    roomFromWorld(0, o);
}

MissionTrialResult runMissionTrial(unsigned seed, const TaskParameters& tasks,
                                   const biovision_attractor::BaseAttractorParameters& base,
                                   const biovision_attractor::HeadAttractorParameters& head,
                                   const MissionTrialOptions& o)
{
  MissionTrialResult result;
  result.seed = seed;
  biovision_sim::RoomWorldGenerator::Room room = o.world_file.empty()
                                                     ? biovision_sim::RoomWorldGenerator().generate(seed)
                                                     : roomFromWorld(seed, o);
  biovision_sim::World& world = room.world;
  // The target where the generator put the goal; the robot starts facing away from it.
  biovision_sim::World::Object target;
  target.label = kTarget;
  target.shape = "box";
  target.position = Eigen::Vector3d(room.goal_x, room.goal_y, 0.2);
  target.size = Eigen::Vector3d(0.3, 0.3, 0.4);
  world.addObject(target);
  const double start_yaw = o.world_file.empty()
                               ? std::atan2(room.goal_y - room.start_y, room.goal_x - room.start_x) + M_PI
                               : room.start_yaw;
  auto plan = std::make_unique<biovision_sim::FloorPlan>(world);

  biovision_sim::DifferentialDrive::Limits limits;
  limits.radius = base.robot_radius;
  biovision_sim::DifferentialDrive drive(limits, room.start_x, room.start_y, start_yaw);
  biovision_sim::Servo pan(head.pan_lower, head.pan_upper, o.servo_speed, 0.0);
  HeadAttractor head_controller(head);
  BaseAttractor base_controller(base);
  biovision_memory::ShortTermMemory stm(o.stm);
  biovision_memory::LongTermMemoryParameters ltm_parameters;
  ltm_parameters.min_points = 1;  // one range per degree, not thousands of disparity pixels
  biovision_memory::LongTermMemory ltm(ltm_parameters);
  TaskManager manager(tasks);
  for (const auto& t : TaskSpec::parseText(std::string("search ") + kTarget + "; return_home"))
    manager.add(t);
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, o.position_noise);

  const double dt = 1.0 / o.physics_rate;
  const int control_every = std::max(1, static_cast<int>(std::lround(o.physics_rate / o.control_rate)));
  const int perceive_every = std::max(1, static_cast<int>(std::lround(o.physics_rate / o.perception_rate)));
  MotorCommand command, last_sent;  // last_sent: the base command the controller last got as a new goal
  last_sent.base = MotorCommand::Base::Stop;
  bool trapped = false, in_contact = false;
  BaseAttractor::Output last_base;
  result.min_clearance = plan->clearance(drive.x(), drive.y()) - limits.radius;
  const long steps = static_cast<long>(std::ceil(o.timeout * o.physics_rate));
  long step = 0;
  for (; step <= steps && !manager.idle(); ++step)
  {
    const double t = step * dt;
    const Pose2D pose{drive.x(), drive.y(), drive.yaw()};
    if (step % perceive_every == 0)
    {
      const ViewScan scan = groundTruthScan(*plan, pose, pan.position(), o);
      stm.update(scan, pose, t);
      ltm.update(scan, pose, t);
      Percept p;
      p.time = t;
      p.pose = {pose.x, pose.y, pose.yaw};
      p.pose_valid = true;
      p.view_yaw = pose.yaw + pan.position();
      p.map = ltmMap(ltm, room);
      p.base_trapped = trapped;
      for (const auto& s :
           plan->visible(pose.x, pose.y, pose.yaw + pan.position(), o.horizontal_fov / 2, o.recognition_range))
        if (plan->footprints()[s.index].label == kTarget)
          p.seen.push_back({kTarget, s.distance * std::cos(s.bearing) + pose.x + noise(rng),
                            s.distance * std::sin(s.bearing) + pose.y + noise(rng), 0.9, t});
      const bool found_before = manager.record().found.count(kTarget) > 0;
      command = manager.step(p);
      if (!found_before && manager.record().found.count(kTarget))
      {
        result.found = true;
        result.found_time = t;
        const auto& f = manager.record().found.at(kTarget);
        result.found_error = std::hypot(f.x - room.goal_x, f.y - room.goal_y);
        result.target_found = {f.x, f.y};
        const cv::Point2d here(pose.x, pose.y), home(room.start_x, room.start_y);
        result.new_obstacles_placed = o.world_file.empty()  ? placeNewObstacles(world, here, home, o.new_obstacles)
                                      : o.new_obstacles > 0 ? placeDemoObstacle(world, here, home, result.path)
                                                            : 0;
        for (int k = 0; k < result.new_obstacles_placed; ++k)
        {
          const auto& added = world.objects()[world.objects().size() - result.new_obstacles_placed + k];
          result.new_obstacle_positions.emplace_back(added.position.x(), added.position.y());
        }
        plan = std::make_unique<biovision_sim::FloorPlan>(world);
      }
      head_controller.setBehaviour(command.head_mode == "explore" ? HeadAttractor::Behaviour::kExplore
                                                                  : HeadAttractor::Behaviour::kLookAhead);
    }
    if (step % control_every == 0)
    {
      const double control_dt = control_every * dt;
      // The head: the clutter in view is salient (walls are not), nearer is more salient.
      std::vector<biovision_attractor::SeenRegion> regions;
      for (const auto& s : plan->visible(pose.x, pose.y, pose.yaw + pan.position(), o.horizontal_fov / 2, 6.0))
        if (plan->footprints()[s.index].label.rfind("wall", 0) != 0)
          regions.push_back({wrap(s.bearing - pose.yaw), 0.3, std::clamp(1.0 - s.distance / 6.0, 0.05, 1.0), 1000.0});
      const HeadAttractor::Output h = head_controller.update(regions, pan.position(), t, control_dt,
                                                             o.horizontal_fov / 2);
      if (std::isfinite(h.command))
        pan.command(h.command);
      // The base: the task's goal, turn or stop.
      std::vector<BaseAttractor::Sector> sectors;
      for (const auto& s : stm.sectors(ltm, pose))
        sectors.push_back({s.centre, s.distance, s.confidence, stm.parameters().sector_width, s.offset});
      if (command.base == MotorCommand::Base::Stop)
      {
        base_controller.stop();
        drive.command(0, 0);
        last_sent = command;
      }
      else
      {
        const bool turn = command.base == MotorCommand::Base::Heading;
        // A new goal message (the task manager sends one only when the goal moves by 5 cm or the turn by 0.05 rad)
        // restarts the controller's progress and trap clock, as in the node.
        const bool moved = command.base != last_sent.base ||
                           (turn ? std::abs(wrap(command.heading - last_sent.heading)) > 0.05
                                 : std::hypot(command.goal_x - last_sent.goal_x, command.goal_y - last_sent.goal_y) >
                                       0.05);
        if (moved)
        {
          base_controller.newGoal();
          last_sent = command;
        }
        const double bearing = turn ? wrap(command.heading - pose.yaw)
                                    : wrap(std::atan2(command.goal_y - pose.y, command.goal_x - pose.x) - pose.yaw);
        const double distance = turn ? INFINITY : std::hypot(command.goal_x - pose.x, command.goal_y - pose.y);
        const BaseAttractor::Output out = base_controller.update(sectors, bearing, distance, t, control_dt);
        trapped = out.status == BaseAttractor::Status::kTrapped;
        drive.command(out.linear, out.angular);
        last_base = out;
      }
    }
    pan.step(dt);
    const double x0 = drive.x(), y0 = drive.y();
    const bool hit = drive.step(dt, world);
    if (hit && !in_contact)
    {
      ++result.collisions;
      result.collision_positions.emplace_back(drive.x(), drive.y());
      MissionCollision c;
      c.time = step * dt;
      c.position = {drive.x(), drive.y()};
      c.object = drive.collidedWith();
      c.task = manager.status().macro_task;
      c.base_status = command.base == MotorCommand::Base::Stop ? "stop" : BaseAttractor::name(last_base.status);
      c.linear = last_base.linear;
      c.angular = last_base.angular;
      c.front_clearance = last_base.front_clearance;
      c.pan = pan.position();
      // Where on the base's rim the contact is: the rim point nearest a footprint (2-degree steps).
      double nearest = INFINITY;
      for (int k = -90; k < 90; ++k)
      {
        const double a = k * M_PI / 90;
        const double d = plan->clearance(drive.x() + (limits.radius + 0.02) * std::cos(drive.yaw() + a),
                                         drive.y() + (limits.radius + 0.02) * std::sin(drive.yaw() + a));
        if (d < nearest)
          nearest = d, c.contact_bearing = a;
      }
      c.stm_distance = INFINITY;
      if (const int i = stm.sectorOf(c.contact_bearing); i >= 0)
      {
        const auto sector = stm.sectors(ltm, pose)[i];
        c.stm_distance = sector.distance;
        c.stm_confidence = sector.confidence;
      }
      result.collision_details.push_back(c);
    }
    if (result.path.empty() || std::hypot(drive.x() - result.path.back().x, drive.y() - result.path.back().y) > 0.05)
      result.path.emplace_back(drive.x(), drive.y());
    const double clearance = plan->clearance(drive.x(), drive.y()) - limits.radius;
    in_contact = hit || (in_contact && clearance <= 0.02);
    result.path_length += std::hypot(drive.x() - x0, drive.y() - y0);
    result.min_clearance = std::min(result.min_clearance, clearance);
  }
  result.time = step * dt;
  result.home = {room.start_x, room.start_y};
  result.target = {room.goal_x, room.goal_y};
  result.ltm = ltmMap(ltm, room);
  result.final_home_distance = std::hypot(drive.x() - room.start_x, drive.y() - room.start_y);
  std::ostringstream outcome;
  for (const auto& f : manager.finished())
  {
    outcome << (outcome.tellp() > 0 ? "; " : "") << f.name << ": " << toString(f.state);
    if (!f.reason.empty())
      outcome << " (" << f.reason << ")";
    if (f.name == "return_home")
      result.returned = f.state == TaskState::Succeeded;
  }
  if (!manager.idle())
    outcome << (outcome.tellp() > 0 ? "; " : "") << "mission time-out in '" << manager.status().macro_task << "'";
  result.outcome = outcome.str();
  result.completed = result.found && result.returned;
  int on_footprint = 0;
  for (const auto& kv : ltm.cells())
  {
    ++result.ltm_cells;
    on_footprint += plan->clearance(ltm.cellCentre(kv.second.ix), ltm.cellCentre(kv.second.iy)) <=
                    ltm.parameters().cell_size;
  }
  result.ltm_precision = result.ltm_cells ? static_cast<double>(on_footprint) / result.ltm_cells : 0.0;
  return result;
}
}  // namespace biovision_tasks
