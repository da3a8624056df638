#include "navigation_trial.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "biovision_attractor/base_attractor.hpp"
#include "biovision_attractor/head_attractor.hpp"
#include "biovision_sim/differential_drive.hpp"
#include "biovision_sim/floor_plan.hpp"
#include "biovision_sim/servo.hpp"

namespace biovision_attractor
{
namespace
{
double wrap(double a)
{
  return std::atan2(std::sin(a), std::cos(a));
}

// Clutter in the camera's view as salient regions (the stand-in for the saliency pipeline).
std::vector<SeenRegion> visibleClutter(const biovision_sim::FloorPlan& plan, double x, double y, double yaw, double pan,
                                       double half_fov)
{
  std::vector<SeenRegion> regions;
  for (const auto& f : plan.footprints())
  {
    if (f.label.rfind("wall", 0) == 0 || f.label == "partition")
      continue;
    const double d = std::hypot(f.x - x, f.y - y);
    const double bearing = wrap(std::atan2(f.y - y, f.x - x) - yaw);
    if (d > 6.0 || std::abs(wrap(bearing - pan)) > half_fov)
      continue;
    // Visible only when nothing nearer is on the line of sight.
    if (plan.range(x, y, yaw + bearing, d) < d - std::max(f.half_x, f.half_y) - 0.05)
      continue;
    SeenRegion r;
    r.pan = bearing;
    r.tilt = 0.3;
    r.peak = std::clamp(1.0 - d / 6.0, 0.05, 1.0);
    r.area = 1000.0;
    regions.push_back(r);
  }
  return regions;
}
}  // namespace

NavigationTrialResult runNavigationTrial(const biovision_sim::World& world, double start_x, double start_y,
                                         double start_yaw, double goal_x, double goal_y,
                                         const BaseAttractorParameters& base, const HeadAttractorParameters& head,
                                         const NavigationTrialOptions& options,
                                         const std::function<std::unique_ptr<StmSource>()>& make_stm)
{
  const biovision_sim::FloorPlan plan(world);
  biovision_sim::DifferentialDrive::Limits limits;
  limits.radius = base.robot_radius;
  biovision_sim::DifferentialDrive drive(limits, start_x, start_y, start_yaw);
  HeadAttractorParameters head_parameters = head;
  biovision_sim::Servo pan_servo(head_parameters.pan_lower, head_parameters.pan_upper, options.servo_speed, 0.0);
  HeadAttractor head_controller(head_parameters);
  head_controller.setBehaviour(HeadAttractor::Behaviour::kLookAhead);
  BaseAttractor controller(base);
  std::unique_ptr<StmSource> stm_source = make_stm();

  NavigationTrialResult result;
  result.straight_line = std::hypot(goal_x - start_x, goal_y - start_y);
  result.min_clearance = plan.clearance(start_x, start_y) - limits.radius;
  result.path.emplace_back(start_x, start_y);
  const double physics_dt = 1.0 / options.physics_rate;
  const int control_every = std::max(1, static_cast<int>(std::lround(options.physics_rate / options.control_rate)));
  const int stm_every = std::max(1, static_cast<int>(std::lround(options.physics_rate / options.stm_rate)));
  std::vector<BaseAttractor::Sector> stm;
  double stm_time = -std::numeric_limits<double>::infinity();
  bool was_trapped = false, in_contact = false;
  double pan_sum = 0.0;
  long pan_count = 0;
  // Active head: one sweep across the field before the goal is given, the base standing.
  if (options.active_head && options.initial_scan > 0)
  {
    const long scan_steps = static_cast<long>(std::ceil(options.initial_scan * options.physics_rate));
    for (long step = 0; step < scan_steps; ++step)
    {
      const double t = -options.initial_scan + step * physics_dt;
      const double phase = static_cast<double>(step) / scan_steps;
      pan_servo.command(phase < 0.25 ? -1.4 : phase < 0.75 ? 1.4 : 0.0);
      if (step % stm_every == 0)
        stm_source->update(start_x, start_y, start_yaw, pan_servo.position(), t);
      pan_servo.step(physics_dt);
    }
  }
  const long steps = static_cast<long>(std::ceil(options.timeout * options.physics_rate));
  for (long step = 0; step <= steps; ++step)
  {
    const double t = step * physics_dt;
    const double x = drive.x(), y = drive.y(), yaw = drive.yaw();
    if (step % stm_every == 0)
    {
      stm = stm_source->update(x, y, yaw, pan_servo.position(), t);
      stm_time = t;
    }
    if (step % control_every == 0)
    {
      const double control_dt = control_every * physics_dt;
      if (options.active_head)
      {
        const auto regions = visibleClutter(plan, x, y, yaw, pan_servo.position(), options.horizontal_fov / 2);
        const HeadAttractor::Output h = head_controller.update(regions, pan_servo.position(), t, control_dt,
                                                               options.horizontal_fov / 2);
        if (std::isfinite(h.command))
          pan_servo.command(h.command);
      }
      const double dx = goal_x - x, dy = goal_y - y;
      const double distance = std::hypot(dx, dy);
      if (t - stm_time > options.watchdog_timeout)
      {
        controller.stop();
        drive.command(0, 0);
        ++result.watchdog_stops;
      }
      else
      {
        const BaseAttractor::Output out = controller.update(stm, wrap(std::atan2(dy, dx) - yaw), distance, t,
                                                            control_dt);
        drive.command(out.linear, out.angular);
        const bool trapped = out.status == BaseAttractor::Status::kTrapped;
        if (trapped && !was_trapped)
          ++result.trapped_events;
        was_trapped = trapped;
        if (out.status == BaseAttractor::Status::kReached && drive.linear() == 0.0 && distance <= options.reach_radius)
        {
          result.reached = true;
          result.time = t;
          break;
        }
      }
      pan_sum += std::abs(pan_servo.position());
      ++pan_count;
      if (step > 0)
        result.path.emplace_back(x, y);
    }
    pan_servo.step(physics_dt);
    // A collision is a contact after the base had been clear (2 cm) since the last one: pushing on against
    // the same obstacle is one collision, not one per physics step.
    const bool hit = drive.step(physics_dt, world);
    if (hit && !in_contact)
    {
      ++result.collisions;
      result.collisions_at.emplace_back(drive.x(), drive.y());
    }
    if (hit)
      in_contact = true;
    else if (plan.clearance(drive.x(), drive.y()) - limits.radius > 0.02)
      in_contact = false;
    result.path_length += std::hypot(drive.x() - x, drive.y() - y);
    result.min_clearance = std::min(result.min_clearance, plan.clearance(drive.x(), drive.y()) - limits.radius);
    result.time = t;
  }
  result.final_distance = std::hypot(goal_x - drive.x(), goal_y - drive.y());
  result.path.emplace_back(drive.x(), drive.y());
  result.mean_pan_abs = pan_count > 0 ? pan_sum / pan_count : 0.0;
  return result;
}
}  // namespace biovision_attractor
