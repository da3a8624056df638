#include "biovision_stereo/ros/bio_bin_disparity_nodelet.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <malloc.h>
#include <sstream>

#include <cv_bridge/cv_bridge.h>
#include <image_geometry/stereo_camera_model.h>
#include <opencv2/imgproc.hpp>
#include <pluginlib/class_list_macros.hpp>
#include <sensor_msgs/image_encodings.h>
#include <stereo_msgs/DisparityImage.h>

#include "biovision_ros_common/image_message_converter.hpp"
#include "biovision_ros_common/input_check.hpp"
#include "biovision_ros_common/processing_times.hpp"
#include "biovision_ros_common/typed_parameter.hpp"
#include "biovision_stereo/ros/bio_bin_config.hpp"
#include "biovision_v1/wavelength_list.hpp"

namespace biovision_stereo
{
namespace enc = sensor_msgs::image_encodings;

namespace
{
// What BioBinMatcher reads (8-bit BGR or grey), naming the image in any conversion error.
cv::Mat toMatcherInput(const sensor_msgs::Image& image, const char* which, size_t max_pixels)
{
  try
  {
    return biovision_ros_common::ImageMessageConverter::toCv(
        image, biovision_ros_common::ImageMessageConverter::Depth::Eight, max_pixels);
  }
  catch (const biovision_ros_common::ImageConversionError& e)
  {
    throw std::invalid_argument(std::string(which) + " image: " + e.what());
  }
}

void checkInfo(const sensor_msgs::CameraInfo& info, const sensor_msgs::Image& image, const char* which)
{
  try
  {
    biovision_ros_common::InputCheck::cameraInfo(info, image.width, image.height);
  }
  catch (const biovision_ros_common::InputError& e)
  {
    throw std::invalid_argument(std::string(which) + " " + e.what());
  }
}
}  // namespace

BioBinDisparityNodelet::~BioBinDisparityNodelet() = default;

void BioBinDisparityNodelet::onInitNodelet()
{
  ros::NodeHandle& nh = getNodeHandle();
  ros::NodeHandle& pnh = getPrivateNodeHandle();
  it_ = std::make_unique<image_transport::ImageTransport>(nh);
  bool approximate = false;
  pnh.param("approximate_sync", approximate, false);
  pnh.param("use_color", use_color_, true);
  pnh.param("queue_size", queue_size_, 5);
  int threads = 0;  // ~threads: 0 = every CPU
  try
  {
    biovision_ros_common::readTypedParameter(pnh, "threads", threads);  // a double or string is refused
    max_input_pixels_ = biovision_ros_common::ImageMessageConverter::maxInputPixels(pnh);
    if (queue_size_ < 1)
      throw std::invalid_argument("~queue_size = " + std::to_string(queue_size_) + " must be >= 1");
    if (threads < 0)
      throw std::invalid_argument("~threads = " + std::to_string(threads) + " must be >= 0 (0: every CPU)");
    arena_ = std::make_unique<biovision_common::ParallelArena>(threads);
    if (threads > 0 && arena_->threads() != threads)
      NODELET_WARN("~threads = %d: this process may use %d CPUs; BioBin runs on %d threads", threads, arena_->threads(),
                   arena_->threads());
  }
  catch (const std::invalid_argument& e)
  {
    NODELET_FATAL("%s", e.what());  // start-up configuration: fail loudly rather than run misconfigured
    throw;
  }
  if (approximate)
  {
    approximate_sync_ = std::make_unique<message_filters::Synchronizer<ApproximatePolicy>>(
        ApproximatePolicy(queue_size_), left_sub_, left_info_sub_, right_sub_, right_info_sub_);
    approximate_sync_->registerCallback(&BioBinDisparityNodelet::pairCallback, this);
  }
  else
  {
    exact_sync_ = std::make_unique<message_filters::Synchronizer<ExactPolicy>>(
        ExactPolicy(queue_size_), left_sub_, left_info_sub_, right_sub_, right_info_sub_);
    exact_sync_->registerCallback(&BioBinDisparityNodelet::pairCallback, this);
  }

  reconfigure_server_ = std::make_unique<dynamic_reconfigure::Server<BioBinDisparityConfig>>(reconfigure_mutex_, pnh);
  reconfigure_server_->setCallback([this](BioBinDisparityConfig& c, uint32_t level) { reconfigure(c, level); });

  left_sub_.registerCallback(boost::function<void(const sensor_msgs::ImageConstPtr&)>(
      [this](const sensor_msgs::ImageConstPtr&) { ++left_images_; }));
  last_pair_time_ = ros::WallTime::now();
  biovision_ros_common::DiagnosticsOptions options;
  options.status_name = "BioBin disparity";
  options.rate_topic = "disparity";
  options.default_max_rate = 60.0;
  options.idle = [this] { return !isSubscribed(); };
  options.idle_message = "idle: nobody subscribes to disparity or obstacle_mask";
  options.working_message = "matching";
  options.details = [this](diagnostic_updater::DiagnosticStatusWrapper& s) { details(s); };
  options.on_tick = [this] { watchSynchronisation(); };
  diagnostics_.init(nh, pnh, getName(), options);

  disparity_pub_ = advertise<stereo_msgs::DisparityImage>(nh, "disparity", 1);
  obstacle_pub_ = advertiseImage(*it_, "obstacle_mask", 1);
}

void BioBinDisparityNodelet::subscribe()
{
  ros::NodeHandle& nh = getNodeHandle();
  const std::string image = use_color_ ? "image_rect_color" : "image_rect";
  left_sub_.subscribe(*it_, "left/" + image, 1, imageHints());
  left_info_sub_.subscribe(nh, "left/camera_info", 1);
  right_sub_.subscribe(*it_, "right/" + image, 1, imageHints());
  right_info_sub_.subscribe(nh, "right/camera_info", 1);
}

void BioBinDisparityNodelet::unsubscribe()
{
  left_sub_.unsubscribe();
  left_info_sub_.unsubscribe();
  right_sub_.unsubscribe();
  right_info_sub_.unsubscribe();
}

void BioBinDisparityNodelet::reconfigure(BioBinDisparityConfig& config, uint32_t /*level*/)
{
  try
  {
    const BioBinParameters p = toBioBinParameters(config);
    auto matcher = std::make_unique<BioBinMatcher>(p);
    std::lock_guard<std::mutex> lock(matcher_mutex_);
    matcher_ = std::move(matcher);
    obstacle_distance_ = config.obstacle_distance;
    NODELET_INFO("BioBin: wavelengths [%s], max disparity %d", config.wavelengths.c_str(), config.max_disparity);
  }
  catch (const std::invalid_argument& e)
  {
    diagnostics_.health().reportError(getName(),
                                      std::string("rejected parameters (keeping the previous ones): ") + e.what());
    std::lock_guard<std::mutex> lock(matcher_mutex_);
    if (!matcher_)
      matcher_ = std::make_unique<BioBinMatcher>(BioBinParameters());
  }
}

void BioBinDisparityNodelet::pairCallback(const sensor_msgs::ImageConstPtr& left,
                                          const sensor_msgs::CameraInfoConstPtr& left_info,
                                          const sensor_msgs::ImageConstPtr& right,
                                          const sensor_msgs::CameraInfoConstPtr& right_info)
{
  biovision_ros_common::ScopedProcessingTimer timer(getName());  // loop_bench's CPU per stage
  ++pairs_;
  std::lock_guard<std::mutex> lock(matcher_mutex_);
  image_geometry::StereoCameraModel model;
  DisparityMap result;
  try
  {
    checkInfo(*left_info, *left, "left");
    checkInfo(*right_info, *right, "right");
    if (left->width != right->width || left->height != right->height || left->encoding != right->encoding)
      throw std::invalid_argument("left " + std::to_string(left->width) + "x" + std::to_string(left->height) + " " +
                                  left->encoding + " and right " + std::to_string(right->width) + "x" +
                                  std::to_string(right->height) + " " + right->encoding + " differ");
    // image_geometry also asserts (aborts the whole process) unless the two projections share fx, fy and cy,
    // as a rectified pair does: refuse any other pair here.
    if (left_info->P[0] != right_info->P[0] || left_info->P[5] != right_info->P[5] ||
        left_info->P[6] != right_info->P[6])
      throw std::invalid_argument("left and right camera_info are not a rectified pair: fx " +
                                  std::to_string(left_info->P[0]) + "/" + std::to_string(right_info->P[0]) + ", fy " +
                                  std::to_string(left_info->P[5]) + "/" + std::to_string(right_info->P[5]) + ", cy " +
                                  std::to_string(left_info->P[6]) + "/" + std::to_string(right_info->P[6]) +
                                  " (left/right P) must be equal");
    // image_geometry asserts (aborts) when the two frame ids differ; drivers disagree on that
    // convention, and only fx and the baseline are used here, so give the right info the left frame.
    if (right_info->header.frame_id != left_info->header.frame_id)
    {
      sensor_msgs::CameraInfo right_in_left = *right_info;
      right_in_left.header.frame_id = left_info->header.frame_id;
      model.fromCameraInfo(*left_info, right_in_left);
      NODELET_WARN_THROTTLE(30.0, "BioBin: right camera_info frame '%s' differs from the left's '%s'; using the left's",
                            right_info->header.frame_id.c_str(), left_info->header.frame_id.c_str());
    }
    else
      model.fromCameraInfo(left_info, right_info);
    if (!(model.baseline() > 0.0) || !std::isfinite(model.baseline()))
      throw std::invalid_argument("camera_info gives no positive baseline (right P[3] must be -fx * T)");
    const auto start = std::chrono::steady_clock::now();
    // Size first: an oversized pair is refused before either image is converted.
    const cv::Mat left_image = toMatcherInput(*left, "left", max_input_pixels_);
    const cv::Mat right_image = toMatcherInput(*right, "right", max_input_pixels_);
    const double helper_cpu = arena_->helperCpuSeconds();
    try
    {
      arena_->run([&] { result = matcher_->compute(left_image, right_image); });
    }
    catch (...)
    {
      timer.addCpuSeconds(arena_->helperCpuSeconds() - helper_cpu);  // a refused pair's CPU counts too
      throw;
    }
    timer.addCpuSeconds(arena_->helperCpuSeconds() - helper_cpu);  // the arena's other threads
    last_ms_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    // A smaller frame after a larger one: the matcher has freed the larger one's buffers; hand glibc's
    // freed heap back too (after one 1920x1080 pair the node kept ~590 MB more while matching 320x240).
    const int area = left_image.cols * left_image.rows;
    if (area < last_area_)
      malloc_trim(0);
    last_area_ = area;
  }
  catch (const std::exception& e)  // invalid_argument, cv::Exception
  {
    diagnostics_.health().reportError(getName(), std::string("dropping stereo pair: ") + e.what());
    return;
  }

  // BioBin matches x_l - x_r; DisparityImage holds d = x_l - x_r - (cx_l - cx_r) (its definition, and what
  // Z = f T / d needs). Where the adjusted value would be negative the point lies beyond infinity: invalid.
  const double principal_offset = model.left().cx() - model.right().cx();
  if (principal_offset != 0.0)
  {
    const cv::Mat invalid = result.disparity < std::max(0.f, static_cast<float>(principal_offset));
    result.disparity -= static_cast<float>(principal_offset);
    result.disparity.setTo(-1.f, invalid);
  }

  auto msg = boost::make_shared<stereo_msgs::DisparityImage>();
  msg->header = left->header;
  msg->f = static_cast<float>(model.right().fx());
  msg->T = static_cast<float>(model.baseline());
  msg->min_disparity = 0.0f;
  msg->max_disparity = static_cast<float>(result.max_disparity - principal_offset);
  msg->delta_d = matcher_->parameters().subpixel ? 1.0f / 16.0f : 1.0f;
  msg->valid_window.x_offset = 0;
  msg->valid_window.y_offset = 0;
  msg->valid_window.width = left->width;
  msg->valid_window.height = left->height;
  // Invalid pixels are below min_disparity (-1), as stereo_image_proc marks them.
  cv_bridge::CvImage image(left->header, enc::TYPE_32FC1, result.disparity);
  image.toImageMsg(msg->image);
  const int valid = cv::countNonZero(result.disparity >= 0.f);
  last_valid_fraction_ = double(valid) / std::max(1, result.disparity.rows * result.disparity.cols);
  disparity_pub_.publish(msg);
  diagnostics_.tick();

  if (obstacle_pub_.getNumSubscribers() > 0)
  {
    const float near = static_cast<float>(msg->f * msg->T / obstacle_distance_);
    cv::Mat mask = result.disparity >= near;
    obstacle_pub_.publish(cv_bridge::CvImage(left->header, enc::MONO8, mask).toImageMsg());
  }
}

void BioBinDisparityNodelet::watchSynchronisation()
{
  // Left images keep coming but no pair for 3 s: the streams are not synchronised.
  const unsigned left = left_images_, pairs = pairs_;
  if (pairs != watched_pairs_)
    last_pair_time_ = ros::WallTime::now();
  else if (left > watched_left_ + 2 && (ros::WallTime::now() - last_pair_time_).toSec() > 3.0)
    diagnostics_.health().reportError(getName(),
                                      "left images arrive but no left/right/camera_info set is synchronised for 3 s (" +
                                          std::string(approximate_sync_ ? "approximate" : "exact") +
                                          " sync; check stamps or set ~approximate_sync)");
  watched_left_ = left;
  watched_pairs_ = pairs;
}

void BioBinDisparityNodelet::details(diagnostic_updater::DiagnosticStatusWrapper& status)
{
  std::lock_guard<std::mutex> lock(matcher_mutex_);
  status.add("last processing time [ms]", last_ms_);
  status.add("last valid fraction", last_valid_fraction_);
  status.add("threads", arena_ ? arena_->threads() : 0);
  if (matcher_)
  {
    const auto& t = matcher_->lastTimes();
    status.add("stage ms: cells/costs+dog/fusion/spatial/wta",
               std::to_string(t.cells) + "/" + std::to_string(t.costs) + "/" + std::to_string(t.fusion) + "/" +
                   std::to_string(t.spatial) + "/" + std::to_string(t.wta));
  }
}
}  // namespace biovision_stereo

PLUGINLIB_EXPORT_CLASS(biovision_stereo::BioBinDisparityNodelet, nodelet::Nodelet)
