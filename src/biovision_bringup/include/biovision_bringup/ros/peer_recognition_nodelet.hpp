#pragma once

#include <memory>
#include <mutex>

#include <image_transport/image_transport.h>
#include <ros/ros.h>
#include <sensor_msgs/Image.h>

#include "biovision_bringup/peer_saliency_orb.hpp"
#include "biovision_ros_common/lazy_nodelet.hpp"
#include "biovision_ros_common/nodelet_diagnostics.hpp"

namespace biovision_bringup
{
/// loop_bench's peer of our saliency + recognition (PeerSaliencyOrb) as a nodelet, so that it runs in the
/// same manager as stereo_image_proc's SGBM disparity.
/// Subscribes `image` (sensor_msgs/Image, any 8/16-bit grey or colour encoding); publishes `objects`
/// (biovision_msgs/RecognizedObjectArray, the image's header) and `saliency/regions`
/// (biovision_msgs/SalientRegionArray). Parameters (start-up): ~views (string, required: the folder of
/// teach_from_bag --views), ~max_regions (int, 3), ~orb_features (int, 400), ~ratio (double, 0.8),
/// ~min_matches (int, 5), ~region_margin (int, 15 px), ~inlier_distance (double, 4 px).
class PeerRecognitionNodelet : public biovision_ros_common::LazyNodelet
{
private:
  void onInitNodelet() override;
  void subscribe() override;
  void unsubscribe() override;
  void imageCallback(const sensor_msgs::ImageConstPtr& msg);

  std::unique_ptr<image_transport::ImageTransport> it_;
  image_transport::Subscriber image_sub_;
  ros::Publisher objects_pub_, regions_pub_;
  std::mutex mutex_;
  std::unique_ptr<PeerSaliencyOrb> peer_;
  biovision_ros_common::NodeletDiagnostics diagnostics_;
};
}  // namespace biovision_bringup
