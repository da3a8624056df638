#include "biovision_saliency/ros/saliency_nodelet.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <stdexcept>

#include <biovision_msgs/SalientRegionArray.h>
#include <cv_bridge/cv_bridge.h>
#include <opencv2/imgproc.hpp>
#include <pluginlib/class_list_macros.hpp>
#include <sensor_msgs/image_encodings.h>

#include "biovision_ros_common/image_message_converter.hpp"
#include "biovision_ros_common/input_check.hpp"
#include "biovision_ros_common/processing_times.hpp"
#include "biovision_saliency/ros/saliency_config.hpp"

namespace biovision_saliency
{
namespace enc = sensor_msgs::image_encodings;

void SaliencyNodelet::onInitNodelet()
{
  ros::NodeHandle& nh = getNodeHandle();
  ros::NodeHandle& pnh = getPrivateNodeHandle();
  it_ = std::make_unique<image_transport::ImageTransport>(nh);
  pnh.param("pan_joint", pan_joint_, pan_joint_);
  pnh.param("tilt_joint", tilt_joint_, tilt_joint_);
  pnh.param("max_input_age", max_input_age_, 0.5);
  try
  {
    max_input_pixels_ = biovision_ros_common::ImageMessageConverter::maxInputPixels(pnh);
    if (!(max_input_age_ > 0.0))
      throw std::invalid_argument("~max_input_age = " + std::to_string(max_input_age_) + " must be > 0 [s]");
  }
  catch (const std::invalid_argument& e)
  {
    NODELET_FATAL("%s", e.what());  // start-up configuration: fail loudly rather than run misconfigured
    throw;
  }

  reconfigure_server_ = std::make_unique<dynamic_reconfigure::Server<SaliencyConfig>>(reconfigure_mutex_, pnh);
  reconfigure_server_->setCallback([this](SaliencyConfig& c, uint32_t level) { reconfigure(c, level); });

  biovision_ros_common::DiagnosticsOptions options;
  options.status_name = "Saliency";
  options.rate_topic = "saliency/regions";
  options.idle = [this] { return !isSubscribed(); };
  options.idle_message = "idle: nobody subscribes to saliency outputs";
  options.details = [this](diagnostic_updater::DiagnosticStatusWrapper& s) { details(s); };
  diagnostics_.init(nh, pnh, getName(), options);
  // Called from imageCallback with state_mutex_ held.
  image_clock_.onJumpBack([this] {
    pipeline_->reset();
    NODELET_WARN_THROTTLE(5.0, "saliency: image stamps went backwards; restarting motion and IoR");
  });
  reset_srv_ = nh.advertiseService("saliency/reset_inhibition", &SaliencyNodelet::resetInhibition, this);

  regions_pub_ = advertise<biovision_msgs::SalientRegionArray>(nh, "saliency/regions", 5);
  map_pub_ = advertiseImage(*it_, "saliency/map", 1);
  thresholded_pub_ = advertiseImage(*it_, "saliency/thresholded", 1);
}

void SaliencyNodelet::subscribe()
{
  ros::NodeHandle& nh = getNodeHandle();
  image_sub_ = it_->subscribe("image", 2, &SaliencyNodelet::imageCallback, this, imageHints());
  disparity_sub_ = nh.subscribe("disparity", 2, &SaliencyNodelet::disparityCallback, this);
  joint_sub_ = nh.subscribe("joint_states", 20, &SaliencyNodelet::jointCallback, this);
  info_sub_ = nh.subscribe("camera_info", 2, &SaliencyNodelet::infoCallback, this);
}

void SaliencyNodelet::unsubscribe()
{
  image_sub_.shutdown();
  disparity_sub_.shutdown();
  joint_sub_.shutdown();
  info_sub_.shutdown();
}

void SaliencyNodelet::reconfigure(SaliencyConfig& c, uint32_t /*level*/)
{
  const SaliencyParameters p = toSaliencyParameters(c);
  try
  {
    auto pipeline = std::make_unique<SaliencyPipeline>(p);
    std::lock_guard<std::mutex> lock(state_mutex_);
    pipeline_ = std::move(pipeline);
  }
  catch (const std::invalid_argument& e)
  {
    diagnostics_.health().reportError(getName(),
                                      std::string("rejected parameters (keeping the previous ones): ") + e.what());
    std::lock_guard<std::mutex> lock(state_mutex_);
    if (!pipeline_)
      pipeline_ = std::make_unique<SaliencyPipeline>(SaliencyParameters());
  }
}

void SaliencyNodelet::disparityCallback(const stereo_msgs::DisparityImageConstPtr& msg)
{
  std::lock_guard<std::mutex> lock(state_mutex_);
  disparity_ = msg;
}

void SaliencyNodelet::infoCallback(const sensor_msgs::CameraInfoConstPtr& msg)
{
  try
  {
    biovision_ros_common::InputCheck::cameraInfo(*msg);
  }
  catch (const biovision_ros_common::InputError& e)
  {
    diagnostics_.health().reportError(getName(), std::string("ignoring ") + e.what());
    return;
  }
  std::lock_guard<std::mutex> lock(state_mutex_);
  info_ = msg;
}

void SaliencyNodelet::jointCallback(const sensor_msgs::JointStateConstPtr& msg)
{
  std::map<std::string, double> found;
  try
  {
    found = biovision_ros_common::InputCheck::jointPositions(*msg, {pan_joint_, tilt_joint_});
  }
  catch (const biovision_ros_common::InputError& e)
  {
    diagnostics_.health().reportError(getName(), std::string("ignoring ") + e.what());
    return;
  }
  if (found.empty())
    return;
  std::lock_guard<std::mutex> lock(state_mutex_);
  if (auto it = found.find(pan_joint_); it != found.end())
    pan_ = it->second;
  if (auto it = found.find(tilt_joint_); it != found.end())
    tilt_ = it->second;
  joints_stamp_ = msg->header.stamp;
}

bool SaliencyNodelet::resetInhibition(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res)
{
  std::lock_guard<std::mutex> lock(state_mutex_);
  pipeline_->inhibitionOfReturn().reset();
  res.success = true;
  res.message = "inhibition-of-return memory cleared";
  return true;
}

void SaliencyNodelet::imageCallback(const sensor_msgs::ImageConstPtr& msg)
{
  const biovision_ros_common::ScopedProcessingTimer timer(getName());  // loop_bench's CPU per stage
  const auto start = std::chrono::steady_clock::now();
  std::lock_guard<std::mutex> lock(state_mutex_);
  SaliencyResult result;
  try
  {
    image_clock_.observe(msg->header.stamp);
    const cv::Mat image = biovision_ros_common::ImageMessageConverter::toCv(
        *msg, biovision_ros_common::ImageMessageConverter::Depth::Eight, max_input_pixels_);

    // Optional inputs: used only when they are recent relative to this image.
    cv::Mat disparity;
    std::string channels = "colour";
    if (disparity_)
    {
      const double age = std::abs((msg->header.stamp - disparity_->header.stamp).toSec());
      if (age <= max_input_age_)
      {
        disparity =
            biovision_ros_common::ImageMessageConverter::toFloat32(disparity_->image, max_input_pixels_).clone();
        disparity.setTo(-1.f, disparity < disparity_->min_disparity);  // stereo_image_proc's invalid marking
        channels += "+disparity";
      }
      else
        NODELET_WARN_THROTTLE(5.0, "saliency: disparity is %.2f s away from the image; colour and motion only", age);
    }
    HeadDirection head;
    if (!joints_stamp_.isZero())
    {
      head.pan = pan_;
      head.tilt = tilt_;
    }
    if (info_ && info_->width == msg->width && info_->height == msg->height)  // checked in infoCallback
    {
      head.focal = info_->P[0];
      head.principal = cv::Point2d(info_->P[2], info_->P[6]);
    }
    result = pipeline_->process(image, disparity, head, msg->header.stamp.toSec());
    if (!result.motion.empty())
      channels += "+motion";
    last_channels_ = channels;
  }
  catch (const std::exception& ex)
  {
    diagnostics_.health().reportError(getName(), "dropping image " + std::to_string(msg->width) + "x" +
                                                     std::to_string(msg->height) + " '" + msg->encoding +
                                                     "': " + ex.what());
    return;
  }
  last_ms_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  last_regions_ = result.regions.size();

  // No non-finite or out-of-range angle leaves the node, whatever went into the pipeline.
  size_t bad_angles = 0;
  for (const SalientRegion& r : result.regions)
    bad_angles += !(std::isfinite(r.pan) && std::isfinite(r.tilt) && std::abs(r.pan) <= M_PI &&
                    std::abs(r.tilt) <= M_PI && std::isfinite(r.peak) && std::isfinite(r.mean));
  if (bad_angles > 0)
  {
    diagnostics_.health().reportError(getName(), "dropping a frame: " + std::to_string(bad_angles) +
                                                     " salient regions have a NaN/Inf or beyond-pi pan/tilt");
    return;
  }

  auto regions = boost::make_shared<biovision_msgs::SalientRegionArray>();
  regions->header = msg->header;
  regions->image_width = msg->width;
  regions->image_height = msg->height;
  for (size_t i = 0; i < result.regions.size(); ++i)
  {
    const SalientRegion& r = result.regions[i];
    biovision_msgs::SalientRegion m;
    m.rank = static_cast<uint32_t>(i);
    m.box.x_offset = r.box.x;
    m.box.y_offset = r.box.y;
    m.box.width = r.box.width;
    m.box.height = r.box.height;
    m.peak_saliency = r.peak;
    m.mean_saliency = r.mean;
    m.area = static_cast<uint32_t>(r.area);
    m.pan = r.pan;
    m.tilt = r.tilt;
    m.inhibition = r.inhibition;
    regions->regions.push_back(m);
  }
  regions_pub_.publish(regions);
  diagnostics_.tick();
  if (map_pub_.getNumSubscribers() > 0)
    map_pub_.publish(cv_bridge::CvImage(msg->header, enc::TYPE_32FC1, result.map).toImageMsg());
  if (thresholded_pub_.getNumSubscribers() > 0)
    thresholded_pub_.publish(cv_bridge::CvImage(msg->header, enc::MONO8, result.thresholded).toImageMsg());
}

void SaliencyNodelet::details(diagnostic_updater::DiagnosticStatusWrapper& status)
{
  std::lock_guard<std::mutex> lock(state_mutex_);
  status.add("last processing time [ms]", last_ms_);
  status.add("last regions", last_regions_);
  status.add("channels in use", last_channels_);
}
}  // namespace biovision_saliency

PLUGINLIB_EXPORT_CLASS(biovision_saliency::SaliencyNodelet, nodelet::Nodelet)
