#pragma once

#include <vector>

#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include "biovision_memory/disparity_camera.hpp"
#include "biovision_memory/pose2d.hpp"
#include "biovision_memory/short_term_memory_parameters.hpp"
#include "biovision_memory/view_scan.hpp"
#include "biovision_memory/view_scanner.hpp"

namespace biovision_memory
{
class LongTermMemory;

/// The egocentric short-term memory of thesis §5.3.1: 9 sectors of 20° over −90°…+90° around the base
/// (base_link, + = left), each holding the nearest obstacle seen there.
///
/// Per disparity frame, each of the 3 image strips gives its nearest obstacle (ViewScanner). A strip's
/// obstacle overwrites the sector of its own bearing (a refinement: the thesis used the strip's centre
/// bearing, "according to the current head pan"); a strip that saw no obstacle within range marks the
/// sector holding its centre bearing free; a blind strip (too few valid disparities) changes nothing. Out of view a sector keeps its content, moved by odometry — every remembered obstacle point
/// is rotated and translated by the base's motion and re-binned; what leaves ±90° is dropped, and so is
/// what is older than its horizon (time) or was seen before the base travelled horizon_distance.
///
/// Confidence falls linearly from 1 (just seen) to 0 at the horizon; at 0 a sector is unknown
/// (distance +Inf, confidence 0). Free space fades faster than obstacles. Not thread-safe.
class ShortTermMemory
{
public:
  /// One sector as the base controller reads it.
  struct Sector
  {
    double centre = 0.0;                ///< bearing of the sector's centre in base_link [rad]
    double distance = ViewScan::kNone;  ///< nearest obstacle from base_link's origin [m]; +Inf: free or unknown
    /// A lower bound [m] on how near the line ahead (base_link x) the sector's obstacles come: the STM's one
    /// point is taken to reach the sector's edge nearest the heading, a completing map cell is taken as itself
    /// (the map holds every face cell it saw). +Inf when the sector holds no obstacle.
    double offset = ViewScan::kNone;
    double confidence = 0.0;  ///< [0, 1]; 0 = unknown (never seen, or aged out)
    bool obstacle = false;    ///< distance is an obstacle's
    double age = 0.0;         ///< time since the sector was last seen [s] (0 when unknown)
  };

  /// Throws std::invalid_argument (ShortTermMemoryParameters::validate) on bad parameters.
  explicit ShortTermMemory(const ShortTermMemoryParameters& parameters = {});

  /// Replaces the parameters (validated first; on a throw the old ones stay). Keeps the memory.
  void setParameters(const ShortTermMemoryParameters& parameters);
  const ShortTermMemoryParameters& parameters() const { return parameters_; }

  /// Forgets everything (time jumped back, odometry reset).
  void reset();

  /// Moves the remembered obstacles by the base's motion since the last call (odom_from_base: the base's
  /// pose in `odom`), drops what leaves ±90° or passes a horizon, and ages every sector to `stamp` [s].
  /// The first call only records the pose. A non-finite pose is ignored (the memory only ages). A stamp
  /// earlier than the last one first resets the memory (time went backwards, e.g. a looped bag) and the
  /// call returns false; the pose and stamp are then the new start.
  bool moveTo(const Pose2D& odom_from_base, double stamp);

  /// One disparity frame: moveTo(odom_from_base, stamp), then ViewScanner::scan() and update(scan).
  /// Throws std::invalid_argument on an empty/non-CV_32FC1 disparity or an invalid camera (the memory is
  /// unchanged then). Returns false when the stamp went backwards (the memory was reset before the frame
  /// was used).
  bool update(const cv::Mat& disparity, const DisparityCamera& camera, const Eigen::Isometry3d& base_from_camera,
              const Pose2D& odom_from_base, double stamp);
  /// The same from a scan the caller made (base_link at odom_from_base at `stamp`).
  bool update(const ViewScan& scan, const Pose2D& odom_from_base, double stamp);

  /// The sectors at the time of the last moveTo()/update(), right-most (−90°) first.
  std::vector<Sector> sectors() const;
  /// The same, completed by the long-term map (beyond the thesis; what memory/stm publishes): every LTM cell
  /// of at least the initial strength whose centre lies within parameters().map_completion_radius [m] of the
  /// base is an obstacle of the sector holding its bearing, at its distance less half a cell, where the
  /// sector is unknown or holds nothing nearer (confidence 1, age 0); every such cell (less half a cell)
  /// and the STM's own point bound the sector's offset. `map_from_base`: base_link in the
  /// LTM's frame. A non-finite pose or a radius of 0 gives sectors().
  std::vector<Sector> sectors(const LongTermMemory& ltm, const Pose2D& map_from_base) const;
  /// The scan of the last update(disparity, …) (empty before one).
  const ViewScan& lastScan() const { return last_scan_; }
  /// Sector index of a bearing [rad] in base_link, −1 outside the sectors.
  int sectorOf(double bearing) const;
  /// Centre bearing of sector i [rad].
  double sectorCentre(int i) const;

private:
  struct Cell
  {
    bool known = false;
    bool obstacle = false;
    Eigen::Vector2d point{0.0, 0.0};  ///< obstacle: its position; free: a point on the sector's centre ray
    double seen = 0.0;                ///< stamp it was last seen [s]
    double travelled = 0.0;           ///< base travel since then [m]
  };

  void age();
  void clearCell(Cell& c) const { c = Cell{}; }

  ShortTermMemoryParameters parameters_;
  ViewScanner scanner_;
  std::vector<Cell> cells_;
  ViewScan last_scan_;
  bool has_pose_ = false;
  Pose2D pose_;
  double stamp_ = 0.0;
};
}  // namespace biovision_memory
