#include "biovision_recognition/ros/recognition_nodelet.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <biovision_msgs/RecognizedObjectArray.h>
#include <cv_bridge/cv_bridge.h>
#include <opencv2/imgproc.hpp>
#include <pluginlib/class_list_macros.hpp>
#include <ros/package.h>
#include <sensor_msgs/image_encodings.h>

#include "biovision_common/atomic_file.hpp"
#include "biovision_common/stored_file.hpp"
#include "biovision_recognition/descriptor_model.hpp"
#include "biovision_recognition/object_locator.hpp"
#include "biovision_ros_common/image_message_converter.hpp"
#include "biovision_ros_common/processing_times.hpp"
#include "biovision_v1/input_image.hpp"

using biovision_common::StoredFileError;

namespace biovision_recognition
{
namespace enc = sensor_msgs::image_encodings;

void RecognitionNodelet::onInitNodelet()
{
  ros::NodeHandle& nh = getNodeHandle();
  ros::NodeHandle& pnh = getPrivateNodeHandle();
  it_ = std::make_unique<image_transport::ImageTransport>(nh);
  std::string model_file;
  pnh.param<std::string>("model_file", model_file,
                         ros::package::getPath("biovision_recognition") + "/models/" + kDefaultModelFile);
  pnh.param<std::string>("memory_file", memory_file_, "");
  pnh.param("max_input_age", max_input_age_, 0.5);
  pnh.param("max_disparity_wait", max_disparity_wait_, max_disparity_wait_);
  if (!(max_disparity_wait_ >= 0.0 && max_disparity_wait_ <= 5.0))
    throw std::invalid_argument("~max_disparity_wait = " + std::to_string(max_disparity_wait_) +
                                " is outside [0, 5] s");
  max_input_pixels_ = biovision_ros_common::ImageMessageConverter::maxInputPixels(pnh);  // throws: fatal at start

  // Without a descriptor model the node cannot do anything: refuse to start rather than run blind
  // (LazyNodelet logs the reason as FATAL; the nodelet loader alone would exit 1 without a word).
  std::shared_ptr<const V1Descriptor> descriptor;
  try
  {
    descriptor = std::make_shared<const V1Descriptor>(DescriptorModel::load(model_file));
  }
  catch (const std::exception& e)
  {
    throw std::runtime_error(std::string("descriptor model (~model_file) refused: ") + e.what());
  }
  model_id_ = descriptor->model().id();
  ObjectRecognizer::Parameters parameters;
  pnh.param("coarse_dft_sizes", parameters.coarse_dft_sizes, parameters.coarse_dft_sizes);  // loop_bench's A/B
  recognizer_ = std::make_unique<ObjectRecognizer>(descriptor, parameters);
  memory_ = std::make_unique<ObjectMemory>(descriptor->model().bits(), model_id_);
  if (!memory_file_.empty())
    loadMemory();

  reconfigure_server_ = std::make_unique<dynamic_reconfigure::Server<RecognitionConfig>>(reconfigure_mutex_, pnh);
  reconfigure_server_->setCallback([this](RecognitionConfig& c, uint32_t level) { reconfigure(c, level); });
  biovision_ros_common::DiagnosticsOptions options;
  options.status_name = "Recognition";
  options.rate_topic = "objects";
  options.idle = [this] { return !isSubscribed(); };
  options.idle_message = "idle: nobody subscribes to objects";
  options.working_message = "recognising";
  options.details = [this](diagnostic_updater::DiagnosticStatusWrapper& s) { details(s); };
  diagnostics_.init(nh, pnh, getName(), options);

  learn_srv_ = nh.advertiseService("recognition/learn_object", &RecognitionNodelet::learn, this);
  forget_srv_ = nh.advertiseService("recognition/forget_object", &RecognitionNodelet::forget, this);
  list_srv_ = nh.advertiseService("recognition/list_objects", &RecognitionNodelet::list, this);

  // ~lazy false (LazyNodelet) subscribes at once: learning needs images even without a consumer.
  objects_pub_ = advertise<biovision_msgs::RecognizedObjectArray>(nh, "objects", 5);
  debug_pub_ = advertiseImage(*it_, "recognition/debug_image", 1);
  pending_timer_ = nh.createWallTimer(ros::WallDuration(0.05), [this](const ros::WallTimerEvent&) {
    std::lock_guard<std::mutex> lock(state_mutex_);
    releasePending(false);
  });
}

void RecognitionNodelet::subscribe()
{
  ros::NodeHandle& nh = getNodeHandle();
  image_sub_ = it_->subscribe("image", 2, &RecognitionNodelet::imageCallback, this, imageHints());
  regions_sub_ = nh.subscribe("saliency/regions", 5, &RecognitionNodelet::regionsCallback, this);
  // As deep as the history: maps queue up while an image is recognised, and the oldest is often the one an
  // image waits for.
  disparity_sub_ = nh.subscribe("disparity", 4, &RecognitionNodelet::disparityCallback, this);
  info_sub_ = nh.subscribe("camera_info", 2, &RecognitionNodelet::infoCallback, this);
}

void RecognitionNodelet::unsubscribe()
{
  image_sub_.shutdown();
  regions_sub_.shutdown();
  disparity_sub_.shutdown();
  info_sub_.shutdown();
  std::lock_guard<std::mutex> lock(state_mutex_);
  releasePending(true);
  disparities_.clear();
}

void RecognitionNodelet::reconfigure(RecognitionConfig& c, uint32_t /*level*/)
{
  std::lock_guard<std::mutex> lock(state_mutex_);
  ObjectRecognizer::Parameters p = recognizer_->parameters();
  p.max_distance = c.max_distance;
  p.verifier.min_inliers = c.min_matches;
  p.verifier.inlier_distance = c.inlier_distance;
  p.verifier.max_rotation_degrees = c.max_rotation;
  p.max_keypoints = c.max_keypoints;
  p.min_view_keypoints = c.min_view_keypoints;
  p.time_budget_ms = c.time_budget_ms;
  p.region_margin = c.region_margin;
  recognizer_->setParameters(p);
  max_regions_ = c.max_regions;
}

void RecognitionNodelet::regionsCallback(const biovision_msgs::SalientRegionArrayConstPtr& msg)
{
  std::lock_guard<std::mutex> lock(state_mutex_);
  regions_ = msg;
}

void RecognitionNodelet::disparityCallback(const stereo_msgs::DisparityImageConstPtr& msg)
{
  std::lock_guard<std::mutex> lock(state_mutex_);
  disparities_.add(msg);
  releasePending(false);
}

void RecognitionNodelet::infoCallback(const sensor_msgs::CameraInfoConstPtr& msg)
{
  std::lock_guard<std::mutex> lock(state_mutex_);
  info_ = msg;
}

void RecognitionNodelet::locate(const stereo_msgs::DisparityImage& disparity, PendingObjects& pending)
{
  if (!info_ || !(disparity.f > 0) || !(std::abs(disparity.T) > 0) || !(info_->P[0] > 0) || !(info_->P[5] > 0) ||
      info_->width == 0 || info_->height == 0)
    return;
  cv::Mat d;  // once per image: a 16UC1 map is converted, a 32FC1 one only wrapped
  try
  {
    d = biovision_ros_common::ImageMessageConverter::toFloat32(disparity.image, max_input_pixels_);
  }
  catch (const std::exception&)
  {
    return;
  }
  // Principal point and focal lengths at the disparity's resolution (it may differ from the image's).
  ObjectLocator::Camera camera;
  camera.focal_length = disparity.f;
  camera.baseline = std::abs(disparity.T);
  camera.fx = info_->P[0] * double(d.cols) / info_->width;
  camera.fy = info_->P[5] * double(d.rows) / info_->height;
  camera.cx = info_->P[2] * double(d.cols) / info_->width;
  camera.cy = info_->P[6] * double(d.rows) / info_->height;
  camera.min_disparity = disparity.min_disparity;
  for (size_t i = 0; i < pending.found.size(); ++i)
  {
    const RecognizedObject& object = pending.found[i];
    cv::Point3d p;
    const ObjectLocator::Source source = ObjectLocator::locate(d, camera, pending.image_size, object.box,
                                                               object.match_points, p);
    if (source == ObjectLocator::Source::None)
      continue;
    ++(source == ObjectLocator::Source::Matches ? located_at_matches_ : located_by_box_);
    auto& o = pending.message.objects[i];
    o.has_position = true;
    o.position.x = p.x;
    o.position.y = p.y;
    o.position.z = p.z;
  }
}

void RecognitionNodelet::imageCallback(const sensor_msgs::ImageConstPtr& msg)
{
  const biovision_ros_common::ScopedProcessingTimer timer(getName());  // loop_bench's CPU per stage
  cv::Mat bgr, gray;
  try
  {
    bgr = biovision_ros_common::ImageMessageConverter::toCv(
        *msg, biovision_ros_common::ImageMessageConverter::Depth::Keep, max_input_pixels_);
    gray = biovision_v1::InputImage(bgr).gray();
  }
  catch (const std::exception& ex)
  {
    diagnostics_.health().reportError(getName(), "dropping image " + std::to_string(msg->width) + "x" +
                                                     std::to_string(msg->height) + " '" + msg->encoding +
                                                     "': " + ex.what());
    return;
  }

  biovision_msgs::RecognizedObjectArray out;
  out.header = msg->header;
  std::vector<RecognizedObject> found;
  std::vector<SearchRegion> regions;
  {
    std::lock_guard<std::mutex> lock(state_mutex_);
    // Newest last; a stamp before the newest (a looped bag, a restarted simulator) starts the history again.
    if (!recent_gray_.empty() && msg->header.stamp < recent_gray_.back().first)
    {
      recent_gray_.clear();
      releasePending(true);  // their disparities belong to the history that ended
    }
    recent_gray_.emplace_back(msg->header.stamp, gray);
    while (recent_gray_.size() > kRecentImages)
      recent_gray_.pop_front();
    if (regions_ && std::abs((regions_->header.stamp - msg->header.stamp).toSec()) <= max_input_age_)
    {
      // Region boxes are in full-resolution pixels of the region message; map them onto this image.
      const double sx = regions_->image_width ? double(gray.cols) / regions_->image_width : 1.0;
      const double sy = regions_->image_height ? double(gray.rows) / regions_->image_height : 1.0;
      for (const auto& r : regions_->regions)
      {
        if (static_cast<int>(regions.size()) >= max_regions_)
          break;
        regions.push_back({cv::Rect(cvRound(r.box.x_offset * sx), cvRound(r.box.y_offset * sy),
                                    cvRound(r.box.width * sx), cvRound(r.box.height * sy)),
                           r.rank});
      }
    }
    try
    {
      found = recognizer_->recognize(gray, regions, *memory_, &last_stats_);
      regions_total_ += last_stats_.regions_processed;
      spectra_built_total_ += last_stats_.kernel_spectra_built;
    }
    catch (const std::exception& ex)
    {
      diagnostics_.health().reportError(getName(), std::string("recognition failed: ") + ex.what());
      return;
    }
    for (const auto& f : found)
    {
      biovision_msgs::RecognizedObject o;
      o.label = f.label;
      o.score = static_cast<float>(f.score);
      o.matches = static_cast<uint32_t>(f.matches);
      o.box.x_offset = static_cast<uint32_t>(f.box.x);
      o.box.y_offset = static_cast<uint32_t>(f.box.y);
      o.box.width = static_cast<uint32_t>(f.box.width);
      o.box.height = static_cast<uint32_t>(f.box.height);
      o.region_rank = f.region_rank;
      out.objects.push_back(o);  // has_position and position: releasePending
    }
    last_objects_ = out.objects.size();  // details() reads it under the same lock
    pending_.push_back({std::move(out), found, gray.size(), ros::WallTime::now()});
    releasePending(false);
  }

  if (debug_pub_.getNumSubscribers() > 0)
  {
    cv::Mat canvas;
    if (bgr.depth() != CV_8U)
      bgr.convertTo(canvas, CV_8U, 1.0 / 256);
    else
      canvas = bgr.clone();
    if (canvas.channels() == 1)
      cv::cvtColor(canvas, canvas, cv::COLOR_GRAY2BGR);
    for (const auto& r : regions)
      cv::rectangle(canvas, r.box, cv::Scalar(255, 128, 0), 1);
    for (const auto& f : found)
    {
      cv::rectangle(canvas, f.box, cv::Scalar(0, 255, 0), 2);
      cv::putText(canvas, f.label + " " + std::to_string(f.matches), f.box.tl() + cv::Point(2, 14),
                  cv::FONT_HERSHEY_SIMPLEX, 0.45, cv::Scalar(0, 255, 0), 1);
    }
    debug_pub_.publish(cv_bridge::CvImage(msg->header, enc::BGR8, canvas).toImageMsg());
  }
}

void RecognitionNodelet::releasePending(bool flush)
{
  while (!pending_.empty())
  {
    PendingObjects& p = pending_.front();
    const ros::Time stamp = p.message.header.stamp;
    stereo_msgs::DisparityImageConstPtr disparity;
    if (!p.found.empty())
    {
      disparity = disparities_.exact(stamp);
      if (disparity)
        ++own_disparity_;
      else
      {
        // Stereo running: its latest map is from about this instant, so this image's map is on its way.
        const auto latest = disparities_.latest();
        const bool stereo_running = latest && std::abs((latest->header.stamp - stamp).toSec()) <= max_input_age_;
        const bool settled = flush || !stereo_running || disparities_.passed(stamp) || pending_.size() > kMaxPending ||
                             (ros::WallTime::now() - p.since).toSec() >= max_disparity_wait_;
        if (!settled)
          return;  // the rest wait behind it: objects go out in image order
        disparity = disparities_.nearest(stamp, max_input_age_);
        if (disparity)
          ++other_disparity_;
      }
    }
    if (disparity && !p.found.empty())
      locate(*disparity, p);
    objects_pub_.publish(p.message);
    diagnostics_.tick();
    pending_.pop_front();
  }
}

void RecognitionNodelet::loadMemory()
{
  // Saves killed mid-write (kill -9, power cut) leave their temporaries: remove those of dead processes.
  for (const auto& stale : biovision_common::removeStaleTemporaries(memory_file_))
    NODELET_WARN("recognition: removed %s, left by an interrupted save", stale.c_str());
  if (!std::ifstream(memory_file_).good())
    return;
  try
  {
    *memory_ = ObjectMemory::load(memory_file_, model_id_);
    NODELET_INFO("recognition: loaded %zu views of %zu objects from %s", memory_->views().size(),
                 memory_->labels().size(), memory_file_.c_str());
    return;
  }
  catch (const StoredFileError& e)
  {
    refusal_ = e.what();
  }
  // Refused, not half-loaded: keep the file for inspection under a name no later refusal overwrites, and
  // start empty at the usual path, so what is learned from now on survives a restart.
  try
  {
    refused_copy_ = biovision_common::keepAside(memory_file_);
  }
  catch (const std::exception& e)
  {
    // It cannot be moved: leave it untouched and save nothing over it (learning then says "not saved").
    refused_copy_ = memory_file_ + " (left in place: " + e.what() + ")";
    save_blocked_ = "the refused memory file could not be moved aside, so it is not overwritten";
  }
  diagnostics_.health().reportError(getName(),
                                    "object memory refused, starting with an empty one; the refused file "
                                    "is kept as " +
                                        refused_copy_ + ": " + refusal_);
}

bool RecognitionNodelet::saveMemory(std::string& error)
{
  if (memory_file_.empty())
    return true;
  if (!save_blocked_.empty())
  {
    error = save_blocked_;
    return false;
  }
  try
  {
    memory_->save(memory_file_);
    return true;
  }
  catch (const std::exception& e)
  {
    error = e.what();
    diagnostics_.health().reportError(getName(), "cannot save the object memory: " + error);
    return false;
  }
}

bool RecognitionNodelet::learn(biovision_msgs::LearnObject::Request& req, biovision_msgs::LearnObject::Response& res)
{
  std::lock_guard<std::mutex> lock(state_mutex_);
  try
  {
    ObjectMemory::validateLabel(req.label);  // the memory's own rule: what is learned can be loaded again
  }
  catch (const std::invalid_argument& e)
  {
    res.message = std::string("refused: ") + e.what();
    return true;
  }
  if (recent_gray_.empty())
  {
    res.message =
        "no image received yet (the node subscribes to images while `objects` has a subscriber, or with ~lazy false)";
    return true;
  }
  cv::Mat gray = recent_gray_.back().second;
  if (!req.stamp.isZero())
  {
    const auto held = std::find_if(recent_gray_.begin(), recent_gray_.end(),
                                   [&req](const auto& image) { return image.first == req.stamp; });
    if (held == recent_gray_.end())
    {
      std::ostringstream why;
      why << "refused: no image stamped " << req.stamp << " is held (the last " << recent_gray_.size()
          << " recognised span " << recent_gray_.front().first << " to " << recent_gray_.back().first << ")";
      res.message = why.str();
      return true;
    }
    gray = held->second;
  }
  try
  {
    // The box must be a region of the image: an empty or zero-width box would be taken as the whole image,
    // and every later scene would then be labelled with this object.
    const cv::Rect box(req.box.x_offset, req.box.y_offset, req.box.width, req.box.height);
    const std::string why = boxProblem(req.box, gray.size());
    if (!why.empty())
    {
      res.message = "refused: " + why;
      return true;
    }
    ObjectView view = recognizer_->describe(gray, box, req.label);
    res.keypoints = static_cast<uint32_t>(view.keypoints.size());
    const std::string problem = recognizer_->learnProblem(view);
    if (!problem.empty())
    {
      res.message = "refused: " + problem;
      return true;
    }
    memory_->addView(std::move(view));
    std::string error;
    res.success = saveMemory(error);
    res.message = res.success
                      ? "learned view " + std::to_string(memory_->viewCount(req.label)) + " of '" + req.label + "'"
                      : "learned, but not saved: " + error;
  }
  catch (const std::exception& e)
  {
    res.message = e.what();
  }
  return true;
}

std::string RecognitionNodelet::boxProblem(const sensor_msgs::RegionOfInterest& box, const cv::Size& image)
{
  const std::string text = "box (x " + std::to_string(box.x_offset) + ", y " + std::to_string(box.y_offset) + ", " +
                           std::to_string(box.width) + " x " + std::to_string(box.height) + " px)";
  if (box.width == 0 || box.height == 0)
    return "empty " + text +
           ": give the object's region in the image, width and height >= " + std::to_string(kMinBoxSide) + " px";
  if (box.width < kMinBoxSide || box.height < kMinBoxSide)
    return text + " is under " + std::to_string(kMinBoxSide) + " px wide or high";
  if (uint64_t(box.x_offset) + box.width > uint64_t(image.width) ||
      uint64_t(box.y_offset) + box.height > uint64_t(image.height))
    return text + " reaches outside the latest image (" + std::to_string(image.width) + " x " +
           std::to_string(image.height) + " px)";
  return "";
}

bool RecognitionNodelet::forget(biovision_msgs::ForgetObject::Request& req, biovision_msgs::ForgetObject::Response& res)
{
  std::lock_guard<std::mutex> lock(state_mutex_);
  const size_t removed = memory_->remove(req.label);
  if (removed == 0)
  {
    res.message = "no object '" + req.label + "'";
    return true;
  }
  std::string error;
  res.success = saveMemory(error);
  res.message = "forgot " + std::to_string(removed) + " views of '" + req.label + "'" +
                (res.success ? "" : "; not saved: " + error);
  return true;
}

bool RecognitionNodelet::list(biovision_msgs::ListObjects::Request&, biovision_msgs::ListObjects::Response& res)
{
  std::lock_guard<std::mutex> lock(state_mutex_);
  for (const auto& label : memory_->labels())
  {
    res.labels.push_back(label);
    res.views.push_back(static_cast<uint32_t>(memory_->viewCount(label)));
    res.keypoints.push_back(static_cast<uint32_t>(memory_->keypointCount(label)));
  }
  return true;
}

void RecognitionNodelet::details(diagnostic_updater::DiagnosticStatusWrapper& s)
{
  std::lock_guard<std::mutex> lock(state_mutex_);
  s.add("descriptor model", model_id_);
  s.add("objects in memory", memory_->labels().size());
  s.add("library codes", memory_->codeCount());
  s.add("memory file", memory_file_.empty() ? std::string("(none: edits are not saved)") : memory_file_);
  if (!refused_copy_.empty())
  {
    // Stays visible (WARN) until the next start: somebody should look at the kept file.
    s.add("refused memory kept as", refused_copy_);
    s.add("refused because", refusal_);
    s.mergeSummary(diagnostic_msgs::DiagnosticStatus::WARN, "object memory refused at start, kept as " + refused_copy_);
  }
  s.add("last regions processed", last_stats_.regions_processed);
  s.add("last regions skipped", last_stats_.regions_skipped);
  s.add("last keypoints", last_stats_.keypoints);
  s.add("positions from the matches' disparity", located_at_matches_);
  s.add("positions from the box median (too few matches with a disparity)", located_by_box_);
  s.add("images located with their own disparity map", own_disparity_);
  s.add("images located with a nearby disparity map (their own skipped or late)", other_disparity_);
  s.add("images waiting for their disparity map", pending_.size());
  s.add("last kernel spectra built", last_stats_.kernel_spectra_built);
  s.add("kernel spectra built per region", regions_total_ ? double(spectra_built_total_) / regions_total_ : 0.0);
  s.add("last recognition time [ms]", last_stats_.milliseconds);
  s.add("last objects", last_objects_);
}
}  // namespace biovision_recognition

PLUGINLIB_EXPORT_CLASS(biovision_recognition::RecognitionNodelet, nodelet::Nodelet)
