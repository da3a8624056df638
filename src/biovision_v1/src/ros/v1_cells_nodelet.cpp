#include "biovision_v1/ros/v1_cells_nodelet.hpp"

#include <chrono>
#include <sstream>

#include <biovision_msgs/KeypointArray.h>
#include <cv_bridge/cv_bridge.h>
#include <opencv2/imgproc.hpp>
#include <pluginlib/class_list_macros.hpp>
#include <sensor_msgs/image_encodings.h>

#include "biovision_ros_common/image_message_converter.hpp"
#include "biovision_ros_common/processing_times.hpp"
#include "biovision_v1/ros/v1_cells_config.hpp"
#include "biovision_v1/input_image.hpp"
#include "biovision_v1/wavelength_list.hpp"

namespace biovision_v1
{
namespace enc = sensor_msgs::image_encodings;

V1CellsNodelet::~V1CellsNodelet() = default;

void V1CellsNodelet::onInitNodelet()
{
  ros::NodeHandle& nh = getNodeHandle();
  ros::NodeHandle& pnh = getPrivateNodeHandle();
  it_ = std::make_unique<image_transport::ImageTransport>(nh);
  try
  {
    max_input_pixels_ = biovision_ros_common::ImageMessageConverter::maxInputPixels(pnh);
  }
  catch (const std::invalid_argument& e)
  {
    NODELET_FATAL("%s", e.what());  // start-up configuration: fail loudly rather than run misconfigured
    throw;
  }

  // Parameters from YAML arrive through dynamic_reconfigure's server (it reads the private namespace).
  reconfigure_server_ = std::make_unique<dynamic_reconfigure::Server<V1CellsConfig>>(reconfigure_mutex_, pnh);
  reconfigure_server_->setCallback([this](V1CellsConfig& c, uint32_t level) { reconfigure(c, level); });

  biovision_ros_common::DiagnosticsOptions options;
  options.status_name = "V1 cells";
  options.rate_topic = "keypoints";
  options.idle = [this] { return !isSubscribed(); };
  options.idle_message = "idle: nobody subscribes to keypoints or debug_image";
  options.details = [this](diagnostic_updater::DiagnosticStatusWrapper& s) { details(s); };
  diagnostics_.init(nh, pnh, getName(), options);

  input_topic_ = nh.resolveName("image");  // not image_sub_.getTopic(): (un)subscribe() reassigns it on another thread
  keypoints_pub_ = advertise<biovision_msgs::KeypointArray>(nh, "keypoints", 5);
  debug_pub_ = advertiseImage(*it_, "debug_image", 1);
}

void V1CellsNodelet::subscribe()
{
  image_sub_ = it_->subscribe("image", 1, &V1CellsNodelet::imageCallback, this, imageHints());
}

void V1CellsNodelet::unsubscribe()
{
  image_sub_.shutdown();
}

void V1CellsNodelet::reconfigure(V1CellsConfig& config, uint32_t /*level*/)
{
  try
  {
    const V1Pipeline::Parameters p = toV1Parameters(config);
    auto pipeline = std::make_unique<V1Pipeline>(p);
    std::lock_guard<std::mutex> lock(pipeline_mutex_);
    pipeline_ = std::move(pipeline);
    NODELET_INFO("V1 cells: wavelengths [%s], %d orientations", config.wavelengths.c_str(), config.orientations);
  }
  catch (const std::invalid_argument& e)
  {
    // Keep the previous, valid pipeline; a rejected value never gets used.
    diagnostics_.health().reportError(getName(),
                                      std::string("rejected parameters (keeping the previous ones): ") + e.what());
    std::lock_guard<std::mutex> lock(pipeline_mutex_);
    if (!pipeline_)
      pipeline_ = std::make_unique<V1Pipeline>(V1Pipeline::Parameters());
  }
}

void V1CellsNodelet::imageCallback(const sensor_msgs::ImageConstPtr& msg)
{
  const biovision_ros_common::ScopedProcessingTimer timer(getName());  // loop_bench's CPU per stage
  const auto start = std::chrono::steady_clock::now();
  V1Result result;
  cv::Mat input;
  const bool want_debug = debug_pub_.getNumSubscribers() > 0;
  {
    std::lock_guard<std::mutex> lock(pipeline_mutex_);
    try
    {
      input = biovision_ros_common::ImageMessageConverter::toCv(
          *msg, biovision_ros_common::ImageMessageConverter::Depth::Keep, max_input_pixels_);
      result = pipeline_->process(input, want_debug);
    }
    catch (const std::exception& e)  // ImageConversionError, invalid_argument, cv::Exception
    {
      diagnostics_.health().reportError(getName(), "dropping image " + std::to_string(msg->width) + "x" +
                                                       std::to_string(msg->height) + " '" + msg->encoding + "' from " +
                                                       input_topic_ + ": " + e.what());
      return;
    }
    last_ms_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    last_keypoints_ = result.keypoints.size();
    last_nonfinite_ = result.nonfinite_pixels;
  }
  if (result.nonfinite_pixels > 0)
    NODELET_WARN_THROTTLE(5.0, "V1 cells: %d NaN/Inf pixels replaced by 0", result.nonfinite_pixels);

  auto out = boost::make_shared<biovision_msgs::KeypointArray>();
  out->header = msg->header;
  out->image_width = msg->width;
  out->image_height = msg->height;
  out->keypoints.reserve(result.keypoints.size());
  for (const Keypoint& k : result.keypoints)
  {
    biovision_msgs::Keypoint m;
    m.x = k.x;
    m.y = k.y;
    m.wavelength = k.wavelength;
    m.strength = k.strength;
    m.orientation = k.orientation;
    out->keypoints.push_back(m);
  }
  keypoints_pub_.publish(out);
  diagnostics_.tick();
  if (want_debug)
    debug_pub_.publish(debugImage(input, result, msg->header));
}

sensor_msgs::ImagePtr V1CellsNodelet::debugImage(const cv::Mat& input, const V1Result& result,
                                                 const std_msgs::Header& header) const
{
  // Dimmed grey image, line/edge events of the finest scale, keypoints as circles of radius lambda/2.
  cv::Mat gray = InputImage(input).gray(), canvas;
  cv::Mat gray8;
  gray.convertTo(gray8, CV_8U, 255.0 * 0.5);
  cv::cvtColor(gray8, canvas, cv::COLOR_GRAY2BGR);
  static const cv::Vec3b kEventColour[5] = {{0, 0, 0}, {255, 255, 255}, {255, 80, 0}, {0, 220, 0}, {0, 0, 255}};
  if (!result.line_edges.empty())
  {
    const LineEdgeMap& le = result.line_edges.front();
    const int d = le.decimation;
    for (int y = 0; y < le.events.rows; ++y)
      for (int x = 0; x < le.events.cols; ++x)
      {
        const uchar e = le.events.at<uchar>(y, x);
        if (e != LineEdgeMap::kNone)
          canvas(cv::Rect(x * d, y * d, d, d) & cv::Rect(0, 0, canvas.cols, canvas.rows)).setTo(kEventColour[e]);
      }
  }
  for (const Keypoint& k : result.keypoints)
    cv::circle(canvas, cv::Point(cvRound(k.x), cvRound(k.y)), std::max(2, cvRound(k.wavelength / 2)),
               cv::Scalar(0, 255, 255), 1, cv::LINE_AA);
  return cv_bridge::CvImage(header, enc::BGR8, canvas).toImageMsg();
}

void V1CellsNodelet::details(diagnostic_updater::DiagnosticStatusWrapper& status)
{
  std::lock_guard<std::mutex> lock(pipeline_mutex_);
  status.add("last processing time [ms]", last_ms_);
  status.add("last keypoints", last_keypoints_);
  status.add("last NaN/Inf pixels", last_nonfinite_);
}
}  // namespace biovision_v1

PLUGINLIB_EXPORT_CLASS(biovision_v1::V1CellsNodelet, nodelet::Nodelet)
