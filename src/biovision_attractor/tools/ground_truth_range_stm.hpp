#pragma once

#include <string>
#include <vector>

#include "biovision_sim/floor_plan.hpp"
#include "stm_source.hpp"

namespace biovision_attractor
{
/// A short-term memory filled from the simulator's ground truth (FloorPlan::range), not from vision: the
/// stand-in for biovision_memory's disparity STM in navigation_eval until that plugs in. It follows the
/// thesis' STM (§5.3, notes §3.1) in everything but the sensor: the camera's view (head pan +- half the
/// horizontal field of view) is split into `strips` vertical strips; each strip's nearest obstacle (rays
/// every ray_step across it, up to max_range) is one observation (the thesis' maximum disparity per strip).
/// The memory accumulates observations as points fixed in the world (the simulator's pose stands for
/// odometry, which is exact there), so that they move with the base's motion: each strip's observation
/// replaces the remembered points in its span nearer than what it sees now (they are gone); points that
/// leave +-90 deg or get older than 3 memory_time are dropped; at most max_points, the oldest go first.
/// Sector i reports its nearest point: distance, confidence = exp(-age / memory_time); a sector that only
/// ever saw free space reports +Inf with the confidence of that look; a sector never seen, +Inf with 0.
class GroundTruthRangeStm : public StmSource
{
public:
  struct Options
  {
    double horizontal_fov = 0.7505;  ///< [rad] 43 deg, the Bumblebee-2 (thesis L948)
    int strips = 3;                  ///< vertical strips of the view (thesis)
    double max_range = 3.0;          ///< [m] farther is free
    double ray_step = 0.0175;        ///< [rad] between rays across a strip (1 deg)
    double memory_time = 10.0;       ///< [s] out-of-view confidence decays with this time constant
    int max_points = 400;            ///< remembered obstacle points
  };

  GroundTruthRangeStm(const biovision_sim::FloorPlan& plan, const Options& options);
  std::string name() const override { return "ground_truth_range"; }
  std::vector<BaseAttractor::Sector> update(double x, double y, double yaw, double pan, double t) override;

private:
  struct Point
  {
    double x = 0, y = 0;  // world frame [m]
    double seen = 0;      // time [s]
  };
  const biovision_sim::FloorPlan& plan_;
  Options options_;
  std::vector<Point> points_;
  std::vector<double> looked_;  // per sector: when a strip last looked there [s]; -Inf = never
};
}  // namespace biovision_attractor
