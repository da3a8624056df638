#pragma once

#include <deque>

#include <Eigen/Core>

#include "biovision_memory/pose2d.hpp"

namespace biovision_memory
{
/// Parameters of the landmark pose correction (beyond the thesis, whose pose is raw odometry).
struct LandmarkCorrectorParameters
{
  int window = 40;  ///< landmark sightings kept for the fit, [1, 10000]
  double window_time =
      20.0;           ///< sightings older than this are dropped [s], (0, 1e6]: odometry drifts (tuned: memory_eval)
  double gain = 0.6;  ///< fraction of the fitted correction applied per sighting, (0, 1] (tuned: memory_eval)
  double min_spread =
      0.3;  ///< the heading is fitted only when the sightings lie this far from their centroid [m], (0, 100]
  double max_jump = 1.5;  ///< a sighting implying a correction larger than this is an outlier [m], (0, 100]
  /// Sightings deeper than this in the camera (optical z) are not used [m], (0, 100]: the correction moves
  /// the whole map, so it takes only the nearer, precise ones. In mission.test (perfect odometry: every
  /// correction is error) sightings at 4.3-4.9 m were 0.7-1.6 m off and left the robot believing itself
  /// 0.28 m from where it was; those at 2.3-3.5 m were 0.09-0.25 m off.
  double max_depth = 3.5;

  /// Throws std::invalid_argument naming the offending field and its range.
  void validate() const;
};

/// Keeps the map consistent on a long drive with odometry drift: estimates `map → odom` from re-sightings
/// of fixed landmarks (ObjectMemory objects at M_R, whose map position no longer moves).
///
/// Each sighting pairs a landmark's remembered map position m_i with where odometry puts it now,
/// o_i = odom_from_base · (its position in base_link). Over a sliding window (count and time) the 2-D
/// rigid transform T minimising Σ |T·o_i − m_i|² is fitted in closed form (Procrustes/Umeyama in 2-D:
/// centroids, then the heading from the cross-covariance); when the window's sightings are closer together
/// than min_spread — in odometry or in the map: one landmark seen from many places is spread in odometry by
/// its noise alone, and gives no heading —, only the translation is fitted (the heading is not observable) and the current heading
/// kept. The estimate moves by `gain` towards the fit per sighting (a first-order filter that smooths the
/// stereo noise of single sightings). Sightings implying a jump larger than max_jump are ignored.
/// Not thread-safe.
class LandmarkCorrector
{
public:
  explicit LandmarkCorrector(const LandmarkCorrectorParameters& parameters = {});
  void setParameters(const LandmarkCorrectorParameters& parameters);
  const LandmarkCorrectorParameters& parameters() const { return parameters_; }

  /// One sighting at `stamp` [s], `depth` [m] in the camera (0: unknown, used). Returns false when it
  /// was ignored (non-finite, negative depth, deeper than max_depth, outlier).
  bool observe(const Eigen::Vector2d& map_position, const Eigen::Vector2d& odom_position, double stamp,
               double depth = 0.0);
  /// The current map → odom (the identity before any sighting).
  const Pose2D& mapFromOdom() const { return map_from_odom_; }
  /// Starts from a known map → odom (e.g. loaded) and forgets the sightings.
  void reset(const Pose2D& map_from_odom = {});
  size_t sightings() const { return window_.size(); }

private:
  struct Pair
  {
    Eigen::Vector2d map, odom;
    double stamp;
  };
  LandmarkCorrectorParameters parameters_;
  std::deque<Pair> window_;
  Pose2D map_from_odom_;
};
}  // namespace biovision_memory
