#pragma once

#include <atomic>
#include <memory>
#include <mutex>
#include <string>

#include <biovision_stereo/BioBinDisparityConfig.h>
#include <boost/thread/recursive_mutex.hpp>
#include <diagnostic_updater/diagnostic_updater.h>
#include <diagnostic_updater/publisher.h>
#include <dynamic_reconfigure/server.h>
#include <image_transport/image_transport.h>
#include <image_transport/subscriber_filter.h>
#include <message_filters/subscriber.h>
#include <message_filters/sync_policies/approximate_time.h>
#include <message_filters/sync_policies/exact_time.h>
#include <message_filters/synchronizer.h>
#include <nodelet/nodelet.h>
#include <ros/ros.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>

#include "biovision_common/parallel_arena.hpp"
#include "biovision_stereo/bio_bin_matcher.hpp"
#include "biovision_ros_common/lazy_nodelet.hpp"
#include "biovision_ros_common/nodelet_diagnostics.hpp"

namespace biovision_stereo
{
/// Drop-in for stereo_image_proc's `disparity` nodelet, computing BioBin stereo. Subscribes (only
/// while `disparity` or `obstacle_mask` has a subscriber) to left/right image_rect_color (or
/// image_rect with ~use_color false) and camera_info, synchronised exactly or approximately
/// (~approximate_sync); publishes stereo_msgs/DisparityImage on `disparity` with invalid pixels
/// below min_disparity as stereo_image_proc does, and a mono8 `obstacle_mask` of pixels nearer than
/// ~obstacle_distance.
/// Disparity as stereo_msgs/DisparityImage defines it: d = x_l - x_r - (cx_l - cx_r), so Z = f T / d holds
/// for every consumer (this repo's obstacle mask, saliency, memory, recognition) also when the rectified
/// principal points differ; pixels whose adjusted disparity would be negative are marked invalid.
/// Frames larger than ~max_input_pixels (width x height) are refused with an ERROR diagnostic, before any
/// pixel is copied (bounded memory per frame).
/// BioBin runs in a task arena of ~threads (biovision_common::ParallelArena) on TBB's worker pool, whatever
/// the process's OpenCV thread count: in one nodelet manager it is the frame's critical path (issue #21).
class BioBinDisparityNodelet : public biovision_ros_common::LazyNodelet
{
public:
  ~BioBinDisparityNodelet() override;

private:
  using ExactPolicy = message_filters::sync_policies::ExactTime<sensor_msgs::Image, sensor_msgs::CameraInfo,
                                                                sensor_msgs::Image, sensor_msgs::CameraInfo>;
  using ApproximatePolicy = message_filters::sync_policies::ApproximateTime<
      sensor_msgs::Image, sensor_msgs::CameraInfo, sensor_msgs::Image, sensor_msgs::CameraInfo>;

  void onInitNodelet() override;
  void subscribe() override;
  void unsubscribe() override;
  void pairCallback(const sensor_msgs::ImageConstPtr& left, const sensor_msgs::CameraInfoConstPtr& left_info,
                    const sensor_msgs::ImageConstPtr& right, const sensor_msgs::CameraInfoConstPtr& right_info);
  void reconfigure(BioBinDisparityConfig& config, uint32_t level);
  void details(diagnostic_updater::DiagnosticStatusWrapper& status);
  void watchSynchronisation();

  std::unique_ptr<image_transport::ImageTransport> it_;
  image_transport::SubscriberFilter left_sub_, right_sub_;
  message_filters::Subscriber<sensor_msgs::CameraInfo> left_info_sub_, right_info_sub_;
  std::unique_ptr<message_filters::Synchronizer<ExactPolicy>> exact_sync_;
  std::unique_ptr<message_filters::Synchronizer<ApproximatePolicy>> approximate_sync_;
  ros::Publisher disparity_pub_;
  image_transport::Publisher obstacle_pub_;
  bool use_color_ = true;
  int queue_size_ = 5;
  size_t max_input_pixels_ = 0;                             // ~max_input_pixels
  std::unique_ptr<biovision_common::ParallelArena> arena_;  // ~threads

  std::mutex matcher_mutex_;
  std::unique_ptr<BioBinMatcher> matcher_;
  double obstacle_distance_ = 1.0;
  boost::recursive_mutex reconfigure_mutex_;  // dynamic_reconfigure::Server takes a boost mutex; outlives it
  std::unique_ptr<dynamic_reconfigure::Server<BioBinDisparityConfig>> reconfigure_server_;

  biovision_ros_common::NodeletDiagnostics diagnostics_;
  double last_ms_ = 0.0, last_valid_fraction_ = 0.0;
  int last_area_ = 0;  ///< [px] of the last pair matched
  // Watchdog for pairs the synchroniser never matches (e.g. different stamps with exact sync).
  std::atomic<unsigned> left_images_{0}, pairs_{0};
  unsigned watched_left_ = 0, watched_pairs_ = 0;
  ros::WallTime last_pair_time_;
};
}  // namespace biovision_stereo
