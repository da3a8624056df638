#include "biovision_bringup/ros/peer_recognition_nodelet.hpp"

#include <biovision_msgs/RecognizedObjectArray.h>
#include <biovision_msgs/SalientRegionArray.h>
#include <opencv2/imgproc.hpp>
#include <pluginlib/class_list_macros.hpp>

#include "biovision_ros_common/image_message_converter.hpp"
#include "biovision_ros_common/processing_times.hpp"

namespace biovision_bringup
{
void PeerRecognitionNodelet::onInitNodelet()
{
  ros::NodeHandle& nh = getNodeHandle();
  ros::NodeHandle& pnh = getPrivateNodeHandle();
  it_ = std::make_unique<image_transport::ImageTransport>(nh);
  biovision_ros_common::DiagnosticsOptions options;
  options.status_name = "Peer recognition";
  options.rate_topic = "objects";
  options.idle = [this] { return !isSubscribed(); };
  diagnostics_.init(nh, pnh, getName(), options);

  PeerSaliencyOrb::Parameters p;
  pnh.param("max_regions", p.max_regions, p.max_regions);
  pnh.param("orb_features", p.orb_features, p.orb_features);
  pnh.param("ratio", p.ratio, p.ratio);
  pnh.param("min_matches", p.min_matches, p.min_matches);
  pnh.param("region_margin", p.region_margin, p.region_margin);
  pnh.param("inlier_distance", p.inlier_distance, p.inlier_distance);
  const std::string views = pnh.param<std::string>("views", "");
  try
  {
    peer_ = std::make_unique<PeerSaliencyOrb>(PeerSaliencyOrb::loadViews(views), p);
  }
  catch (const std::exception& e)
  {
    diagnostics_.health().reportError(getName(), std::string("no recogniser: ") + e.what());
  }
  objects_pub_ = advertise<biovision_msgs::RecognizedObjectArray>(nh, "objects", 5);
  regions_pub_ = advertise<biovision_msgs::SalientRegionArray>(nh, "saliency/regions", 5);
}

void PeerRecognitionNodelet::subscribe()
{
  image_sub_ = it_->subscribe("image", 2, &PeerRecognitionNodelet::imageCallback, this, imageHints());
}

void PeerRecognitionNodelet::unsubscribe()
{
  image_sub_.shutdown();
}

void PeerRecognitionNodelet::imageCallback(const sensor_msgs::ImageConstPtr& msg)
{
  const biovision_ros_common::ScopedProcessingTimer timer(getName());
  std::lock_guard<std::mutex> lock(mutex_);
  if (!peer_)
    return;
  std::vector<cv::Rect> boxes;
  std::vector<PeerSaliencyOrb::Detection> found;
  try
  {
    cv::Mat image = biovision_ros_common::ImageMessageConverter::toCv(*msg), gray;
    if (image.channels() == 3)
      cv::cvtColor(image, gray, cv::COLOR_BGR2GRAY);
    else
      gray = image;
    found = peer_->process(gray, &boxes);
  }
  catch (const std::exception& e)
  {
    diagnostics_.health().reportError(getName(), std::string("dropping image: ") + e.what());
    return;
  }
  auto regions = boost::make_shared<biovision_msgs::SalientRegionArray>();
  regions->header = msg->header;
  regions->image_width = msg->width;
  regions->image_height = msg->height;
  for (size_t i = 0; i < boxes.size(); ++i)
  {
    biovision_msgs::SalientRegion r;
    r.rank = static_cast<uint32_t>(i);
    r.box.x_offset = boxes[i].x;
    r.box.y_offset = boxes[i].y;
    r.box.width = boxes[i].width;
    r.box.height = boxes[i].height;
    regions->regions.push_back(r);
  }
  regions_pub_.publish(regions);
  auto objects = boost::make_shared<biovision_msgs::RecognizedObjectArray>();
  objects->header = msg->header;
  for (const auto& f : found)
  {
    biovision_msgs::RecognizedObject o;
    o.label = f.label;
    o.matches = static_cast<uint32_t>(f.matches);
    o.score = static_cast<float>(f.matches);
    o.box.x_offset = f.box.x;
    o.box.y_offset = f.box.y;
    o.box.width = f.box.width;
    o.box.height = f.box.height;
    o.region_rank = f.region_rank;
    objects->objects.push_back(o);
  }
  objects_pub_.publish(objects);
  diagnostics_.tick();
}
}  // namespace biovision_bringup

PLUGINLIB_EXPORT_CLASS(biovision_bringup::PeerRecognitionNodelet, nodelet::Nodelet)
