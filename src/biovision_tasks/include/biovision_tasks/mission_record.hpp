#pragma once

#include <map>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "biovision_tasks/percept.hpp"

namespace biovision_tasks
{
/// What a mission has learned so far, shared by its tasks: where home is (the first localised pose),
/// where each searched object was found and the trail driven (map frame). Owned by the TaskManager.
struct MissionRecord
{
  bool home_known = false;
  Percept::Pose home;
  std::map<std::string, Percept::Object> found;  ///< by label
  double path_length = 0;                        ///< [m] driven since the mission record began
  /// Positions driven [m, map], oldest (home) first, one every kTrailSpacing: ground the base has crossed,
  /// the way back when the planned one is blocked (GoToTask). At most kMaxTrail points: when full, every
  /// other one is dropped (the spacing doubles), so memory stays bounded on a long mission.
  std::vector<cv::Point2d> trail;
  static constexpr double kTrailSpacing = 0.2;  ///< [m]: finer than the base's 0.52 m disc
  static constexpr size_t kMaxTrail = 4096;
  static constexpr double kLoopCut = 0.35;  ///< [m]: wayBack's jumps; the base's discs at both ends overlap them

  /// Appends (x, y) once it is kTrailSpacing from the last point; a non-finite position is ignored.
  void extendTrail(double x, double y);
  /// The trail back to home from its point nearest `from`, loops cut (a point within kLoopCut of an older
  /// one jumps to it): ground crossed before, so free of what the map did not know. Empty with no trail.
  std::vector<cv::Point2d> wayBack(const cv::Point2d& from) const;
};
}  // namespace biovision_tasks
