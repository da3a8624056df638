#pragma once

#include <memory>
#include <mutex>
#include <string>

#include <biovision_v1/V1CellsConfig.h>
#include <diagnostic_updater/diagnostic_updater.h>
#include <diagnostic_updater/publisher.h>
#include <dynamic_reconfigure/server.h>
#include <image_transport/image_transport.h>
#include <ros/ros.h>
#include <sensor_msgs/Image.h>

#include <boost/thread/recursive_mutex.hpp>

#include "biovision_ros_common/lazy_nodelet.hpp"
#include "biovision_ros_common/nodelet_diagnostics.hpp"
#include "biovision_v1/v1_pipeline.hpp"

namespace biovision_v1
{
/// ROS wrapper of V1Pipeline. Subscribes `image` only while someone listens to `keypoints` or
/// `debug_image` (biovision_ros_common::LazyNodelet); publishes biovision_msgs/KeypointArray on `keypoints` and, when subscribed, a
/// debug image (line/edge events of the finest scale and keypoints) on `debug_image`.
class V1CellsNodelet : public biovision_ros_common::LazyNodelet
{
public:
  ~V1CellsNodelet() override;

private:
  void onInitNodelet() override;
  void subscribe() override;
  void unsubscribe() override;
  void imageCallback(const sensor_msgs::ImageConstPtr& msg);
  void reconfigure(V1CellsConfig& config, uint32_t level);
  void details(diagnostic_updater::DiagnosticStatusWrapper& status);
  sensor_msgs::ImagePtr debugImage(const cv::Mat& bgr, const V1Result& result, const std_msgs::Header& header) const;

  std::unique_ptr<image_transport::ImageTransport> it_;
  image_transport::Subscriber image_sub_;
  std::string input_topic_;
  size_t max_input_pixels_ = 0;  // ~max_input_pixels: larger images are refused (bounded memory per frame)
  image_transport::Publisher debug_pub_;
  ros::Publisher keypoints_pub_;

  std::mutex pipeline_mutex_;
  std::unique_ptr<V1Pipeline> pipeline_;
  boost::recursive_mutex reconfigure_mutex_;  // dynamic_reconfigure::Server takes a boost mutex; outlives it
  std::unique_ptr<dynamic_reconfigure::Server<V1CellsConfig>> reconfigure_server_;

  biovision_ros_common::NodeletDiagnostics diagnostics_;
  double last_ms_ = 0.0;
  size_t last_keypoints_ = 0;
  int last_nonfinite_ = 0;
};
}  // namespace biovision_v1
