#include "biovision_hri/ros/hri_nodelet.hpp"

#include <chrono>

#include <biovision_msgs/DetectionArray.h>
#include <biovision_msgs/GestureArray.h>
#include <biovision_msgs/SetHeadMode.h>
#include <opencv2/imgproc.hpp>
#include <pluginlib/class_list_macros.hpp>
#include <ros/package.h>
#include <std_msgs/Float64.h>
#include <std_msgs/String.h>

#include "biovision_hri/hand_gesture_reader.hpp"
#include "biovision_hri/non_maximum_suppression.hpp"
#include "biovision_recognition/descriptor_model.hpp"
#include "biovision_ros_common/image_message_converter.hpp"
#include "biovision_v1/input_image.hpp"

namespace biovision_hri
{
namespace
{
sensor_msgs::RegionOfInterest toRoi(const cv::Rect2f& box, const cv::Size& image)
{
  const cv::Rect r = cv::Rect(cvRound(box.x), cvRound(box.y), cvRound(box.width), cvRound(box.height)) &
                     cv::Rect(0, 0, image.width, image.height);
  sensor_msgs::RegionOfInterest roi;
  roi.x_offset = r.x;
  roi.y_offset = r.y;
  roi.width = r.width;
  roi.height = r.height;
  return roi;
}

cv::Rect2f scaled(const cv::Rect2f& r, double s)
{
  return cv::Rect2f(static_cast<float>(r.x * s), static_cast<float>(r.y * s), static_cast<float>(r.width * s),
                    static_cast<float>(r.height * s));
}
}  // namespace

HriNodelet::~HriNodelet() = default;

void HriNodelet::onInitNodelet()
{
  ros::NodeHandle& nh = getNodeHandle();
  ros::NodeHandle& pnh = getPrivateNodeHandle();
  it_ = std::make_unique<image_transport::ImageTransport>(nh);

  // Models: a missing or corrupt detector model stops the nodelet at start (it cannot detect anything);
  // the gesture methods are optional.
  const std::string share = ros::package::getPath("biovision_hri");
  std::string face_model, hand_model, templates, posture_model, descriptor_model;
  pnh.param<std::string>("face_model", face_model, share + "/models/face_detector.bin");
  pnh.param<std::string>("hand_model", hand_model, share + "/models/hand_detector.bin");
  pnh.param<std::string>("gesture_templates", templates, share + "/models/gesture_templates.bin");  // "" = off
  pnh.param<std::string>("posture_model", posture_model, share + "/models/hand_posture.bin");       // "" = off
  pnh.param<std::string>("descriptor_model", descriptor_model,
                         ros::package::getPath("biovision_recognition") + "/models/" +
                             biovision_recognition::kDefaultModelFile);
  pnh.param("max_input_age", max_input_age_, 0.5);
  max_input_pixels_ = biovision_ros_common::ImageMessageConverter::maxInputPixels(pnh);  // throws: fatal at start
  pnh.param<std::string>("pan_joint", pan_joint_, "head_pan_joint");
  pnh.param<std::string>("tilt_joint", tilt_joint_, "head_tilt_joint");
  pnh.param("horizontal_fov", greet_base_.horizontal_fov, greet_base_.horizontal_fov);
  pnh.param("pan_min", greet_base_.pan_min, greet_base_.pan_min);
  pnh.param("pan_max", greet_base_.pan_max, greet_base_.pan_max);
  pnh.param("tilt_min", greet_base_.tilt_min, greet_base_.tilt_min);
  pnh.param("tilt_max", greet_base_.tilt_max, greet_base_.tilt_max);
  pnh.param("actions", greet_base_.actions, greet_base_.actions);
  try
  {
    const LinearDetectorModel face = LinearDetectorModel::load(face_model);
    const LinearDetectorModel hand = LinearDetectorModel::load(hand_model);
    if (face.kind != "face" || hand.kind != "hand")
      throw std::runtime_error("face_model/hand_model hold a '" + face.kind + "' and a '" + hand.kind + "' model");
    face_detector_ = std::make_unique<SlidingWindowDetector>(face, SlidingWindowDetector::Parameters());
    hand_detector_ = std::make_unique<SlidingWindowDetector>(hand, SlidingWindowDetector::Parameters());
    NODELET_INFO("hri: face model %s (%s)", face_model.c_str(), face.provenance.c_str());
    NODELET_INFO("hri: hand model %s (%s)", hand_model.c_str(), hand.provenance.c_str());
  }
  catch (const std::exception& e)
  {
    NODELET_FATAL("hri: cannot load the detector models: %s", e.what());
    throw;
  }
  if (!templates.empty())
  {
    try
    {
      auto descriptor = std::make_shared<const biovision_recognition::V1Descriptor>(
          biovision_recognition::DescriptorModel::load(descriptor_model));
      gestures_ = std::make_unique<GestureRecognizer>(descriptor, GestureRecognizer::Parameters());
      gestures_->loadTemplates(templates);
      NODELET_INFO("hri: %zu gesture templates from %s", gestures_->templates().views().size(), templates.c_str());
    }
    catch (const std::exception& e)
    {
      gestures_.reset();
      gestures_off_ = std::string("gesture templates off: ") + e.what();
      diagnostics_.health().reportError(getName(), gestures_off_);
    }
  }
  if (!posture_model.empty())
  {
    try
    {
      auto posture = std::make_unique<HandPostureClassifier>(FeatureLayout(), HandPostureClassifier::Parameters());
      posture->load(posture_model);
      posture_ = std::move(posture);
      NODELET_INFO("hri: hand posture SVMs for %zu classes from %s", posture_->labels().size(), posture_model.c_str());
    }
    catch (const std::exception& e)
    {
      posture_off_ = std::string("posture SVMs off: ") + e.what();
      diagnostics_.health().reportError(getName(), posture_off_);
    }
  }
  behaviour_ = std::make_unique<GreetBehaviour>(greet_base_);

  reconfigure_server_ = std::make_unique<dynamic_reconfigure::Server<HriConfig>>(reconfigure_mutex_, pnh);
  reconfigure_server_->setCallback([this](HriConfig& c, uint32_t level) { reconfigure(c, level); });

  biovision_ros_common::DiagnosticsOptions options;
  options.status_name = "HRI";
  options.rate_topic = "hri/faces";
  options.idle = [this] { return !isSubscribed(); };
  options.idle_message = "idle: nobody subscribes to hri/faces, hri/hands or hri/gestures";
  options.details = [this](diagnostic_updater::DiagnosticStatusWrapper& s) { details(s); };
  diagnostics_.init(nh, pnh, getName(), options);
  // Called from imageCallback with mutex_ held.
  image_clock_.onJumpBack([this] {
    if (behaviour_->state() != GreetBehaviour::State::Idle)
      last_reason_ = "time jumped back";
    behaviour_->stop();
    regions_.reset();
    last_image_t_ = -HUGE_VAL;
  });

  input_topic_ = nh.resolveName("image");
  faces_pub_ = advertise<biovision_msgs::DetectionArray>(nh, "hri/faces", 5);
  hands_pub_ = advertise<biovision_msgs::DetectionArray>(nh, "hri/hands", 5);
  gestures_pub_ = advertise<biovision_msgs::GestureArray>(nh, "hri/gestures", 5);
  // Not lazy outputs: consumers of commands must not keep the detectors running.
  action_pub_ = nh.advertise<std_msgs::String>("hri/action", 5);
  pan_pub_ = nh.advertise<std_msgs::Float64>(pan_joint_ + "/command", 5);
  tilt_pub_ = nh.advertise<std_msgs::Float64>(tilt_joint_ + "/command", 5);
  greet_srv_ = nh.advertiseService("hri/greet", &HriNodelet::greet, this);
  stop_srv_ = nh.advertiseService("hri/stop_greet", &HriNodelet::stopGreet, this);
  // Off the callbacks' threads: a head controller that never answers must not stall detection.
  head_mode_client_ = std::make_unique<biovision_ros_common::AsyncServiceClient<biovision_msgs::SetHeadMode>>(
      nh, "head/set_mode", 2.0);
  // Sends what images did not (a mode asked for while no image comes, a retry after a failed call).
  // Also lets the images go when a greeting has ended and nobody listens (not from imageCallback: unsubscribing
  // there would wait for that very callback).
  head_mode_timer_ = nh.createWallTimer(ros::WallDuration(0.5), [this](const ros::WallTimerEvent&) {
    sendHeadMode();
    updateBusy();
  });
}

void HriNodelet::subscribe()
{
  ros::NodeHandle& nh = getNodeHandle();
  image_sub_ = it_->subscribe("image", 1, &HriNodelet::imageCallback, this, imageHints());
  regions_sub_ = nh.subscribe("saliency/regions", 2, &HriNodelet::regionsCallback, this);
  joint_sub_ = nh.subscribe("joint_states", 20, &HriNodelet::jointCallback, this);
}

void HriNodelet::unsubscribe()
{
  image_sub_.shutdown();
  regions_sub_.shutdown();
  joint_sub_.shutdown();
}

void HriNodelet::reconfigure(HriConfig& config, uint32_t /*level*/)
{
  try
  {
    HriParameters p = toHriParameters(config, greet_base_);
    if (config.detection_width > 0 && config.detection_width < 64)
      throw std::invalid_argument("detection_width must be 0 or >= 64 px, got " +
                                  std::to_string(config.detection_width));
    std::lock_guard<std::mutex> lock(mutex_);
    // Validate everything before changing anything: a rejected set keeps the previous one whole.
    p.face.validate();
    p.hand.validate();
    p.gestures.validate();
    p.greet.validate();
    face_detector_->setParameters(p.face);
    hand_detector_->setParameters(p.hand);
    if (gestures_)
      gestures_->setParameters(p.gestures);
    behaviour_->setParameters(p.greet);
    parameters_ = p;
  }
  catch (const std::invalid_argument& e)
  {
    diagnostics_.health().reportError(getName(),
                                      std::string("rejected parameters (keeping the previous ones): ") + e.what());
  }
}

void HriNodelet::regionsCallback(const biovision_msgs::SalientRegionArrayConstPtr& msg)
{
  std::lock_guard<std::mutex> lock(mutex_);
  regions_ = msg;
}

void HriNodelet::jointCallback(const sensor_msgs::JointStateConstPtr& msg)
{
  std::lock_guard<std::mutex> lock(mutex_);
  for (size_t i = 0; i < msg->name.size() && i < msg->position.size(); ++i)
  {
    if (msg->name[i] == pan_joint_)
      pan_ = msg->position[i];
    else if (msg->name[i] == tilt_joint_)
      tilt_ = msg->position[i];
    else
      continue;
    have_joints_ = true;
  }
}

bool HriNodelet::greet(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res)
{
  {
    std::lock_guard<std::mutex> lock(mutex_);
    start_requested_ = true;
    image_time_moved_ = ros::WallTime::now();
  }
  setBusy(true);  // the greeting needs the images though nobody may listen to hri/* (mutex_ released first)
  res.success = true;
  res.message = "greeting: looking up for a face";
  return true;
}

void HriNodelet::updateBusy()
{
  bool greeting, given_up = false;
  double timeout;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    timeout = parameters_.greet.search_timeout;
    greeting = start_requested_ || behaviour_->state() != GreetBehaviour::State::Idle;
    // The behaviour runs on image time: with no images, or stamps that do not advance (0 from some
    // drivers), it would hold the head and the images for good. Give up after search_timeout of wall time
    // without image time moving, as the behaviour gives up without a face.
    const double still = (ros::WallTime::now() - image_time_moved_).toSec();
    if (greeting && still > timeout)
    {
      given_up = behaviour_->state() != GreetBehaviour::State::Idle;
      behaviour_->stop();
      start_requested_ = false;
      last_reason_ = "image time stood still for " + std::to_string(static_cast<int>(still)) + " s";
      greeting = false;
    }
  }
  if (given_up)
  {
    NODELET_WARN("hri: greeting given up: no image with a newer stamp for %.0f s", timeout);
    setHeadMode("explore");
  }
  setBusy(greeting);
}

bool HriNodelet::stopGreet(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res)
{
  bool was_active;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    was_active = behaviour_->state() != GreetBehaviour::State::Idle;
    behaviour_->stop();
    start_requested_ = false;
    last_reason_ = "stopped";
  }
  if (was_active)
    setHeadMode("explore");
  updateBusy();
  res.success = true;
  res.message = was_active ? "stopped" : "was idle";
  return true;
}

void HriNodelet::setHeadMode(const std::string& mode)
{
  {
    std::lock_guard<std::mutex> lock(head_mode_mutex_);
    head_mode_wanted_ = mode;
    head_mode_retry_at_ = ros::WallTime();
  }
  sendHeadMode();
}

void HriNodelet::sendHeadMode()
{
  std::lock_guard<std::mutex> lock(head_mode_mutex_);
  const ros::WallTime now = ros::WallTime::now();
  if (const auto r = head_mode_client_->take())
  {
    head_mode_answer_ = head_mode_sent_ + ": " +
                        (r->answered && r->response.success ? std::string("accepted")
                         : r->timed_out                     ? std::string("no answer")
                         : r->answered                      ? "refused: " + r->response.message
                                                            : std::string("no head controller"));
    if (!(r->answered && r->response.success))
    {
      NODELET_WARN_THROTTLE(5.0, "hri: head/set_mode %s", head_mode_answer_.c_str());
      // Not answered: sent again a second later unless another mode was asked for meanwhile (a refused
      // mode would be refused again).
      if (!r->answered && head_mode_wanted_.empty())
      {
        head_mode_wanted_ = head_mode_sent_;
        head_mode_retry_at_ = now + ros::WallDuration(1.0);
      }
    }
  }
  if (head_mode_wanted_.empty() || now < head_mode_retry_at_)
    return;
  biovision_msgs::SetHeadMode::Request request;
  request.mode = head_mode_wanted_;
  if (head_mode_client_->start(request))  // else a call is under way: the next image or tick sends it
  {
    head_mode_sent_ = head_mode_wanted_;
    head_mode_wanted_.clear();
  }
}

void HriNodelet::imageCallback(const sensor_msgs::ImageConstPtr& msg)
{
  const auto start = std::chrono::steady_clock::now();
  sendHeadMode();
  auto faces_msg = boost::make_shared<biovision_msgs::DetectionArray>();
  auto hands_msg = boost::make_shared<biovision_msgs::DetectionArray>();
  auto gestures_msg = boost::make_shared<biovision_msgs::GestureArray>();
  faces_msg->header = hands_msg->header = gestures_msg->header = msg->header;
  GreetBehaviour::Output behaviour;
  bool started = false;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    image_clock_.observe(msg->header.stamp);
    try
    {
      const cv::Mat input = biovision_ros_common::ImageMessageConverter::toCv(
          *msg, biovision_ros_common::ImageMessageConverter::Depth::Keep, max_input_pixels_);
      const cv::Mat gray = biovision_v1::InputImage(input).gray();
      const cv::Size size = gray.size();
      // Detection on a smaller copy: the thesis' detectors ran on salient regions of a 1024x768 capture;
      // our default 320 px width keeps a full frame within the rate goal. Boxes are mapped back.
      cv::Mat small = gray;
      double s = 1.0;  // detection px per image px
      if (parameters_.detection_width > 0 && gray.cols != parameters_.detection_width)
      {
        s = static_cast<double>(parameters_.detection_width) / gray.cols;
        cv::resize(gray, small, cv::Size(), s, s, s < 1 ? cv::INTER_AREA : cv::INTER_LINEAR);
        if (small.empty())
          throw std::invalid_argument("image too small to resize to detection_width");
      }
      std::vector<Detection> faces = face_detector_->detect(small);
      std::vector<Detection> hands;
      if (parameters_.detect_hands)
      {
        std::vector<cv::Rect> regions;
        const bool fresh = regions_ && std::abs((regions_->header.stamp - msg->header.stamp).toSec()) <= max_input_age_;
        if (parameters_.hands_in_salient_regions && fresh)
        {
          const int m = parameters_.region_margin;
          for (const auto& r : regions_->regions)
          {
            const cv::Rect2f box(r.box.x_offset - m, r.box.y_offset - m, r.box.width + 2 * m, r.box.height + 2 * m);
            regions.push_back(cv::Rect(scaled(box, s)) & cv::Rect(0, 0, small.cols, small.rows));
          }
        }
        else if (!parameters_.hands_in_salient_regions)
          regions.push_back(cv::Rect());  // the whole frame
        for (const cv::Rect& r : regions)
          if (r.area() > 0 || regions.size() == 1)
          {
            const auto found = hand_detector_->detect(small, r);
            hands.insert(hands.end(), found.begin(), found.end());
          }
        hands = nonMaximumSuppression(std::move(hands), parameters_.hand.nms_overlap);
        if (static_cast<int>(hands.size()) > parameters_.hand.max_detections)
          hands.resize(parameters_.hand.max_detections);
      }
      std::vector<cv::Rect2f> face_boxes;
      for (const Detection& d : faces)
      {
        biovision_msgs::Detection m;
        m.kind = "face";
        m.box = toRoi(scaled(d.box, 1.0 / s), size);
        m.score = d.score;
        m.scale = static_cast<float>(d.scale * s);
        faces_msg->detections.push_back(m);
        face_boxes.push_back(scaled(d.box, 1.0 / s));
      }
      std::vector<cv::Rect> hand_boxes, detected_boxes;  // enlarged for the keypoints / as detected
      for (const Detection& d : hands)
      {
        biovision_msgs::Detection m;
        m.kind = "hand";
        const cv::Rect2f box = scaled(d.box, 1.0 / s);
        m.box = toRoi(box, size);
        m.score = d.score;
        m.scale = static_cast<float>(d.scale * s);
        hands_msg->detections.push_back(m);
        detected_boxes.push_back(cv::Rect(box));
        const float g = static_cast<float>(parameters_.gesture_box_scale);
        const cv::Point2f c(box.x + box.width / 2, box.y + box.height / 2);
        hand_boxes.push_back(
            cv::Rect(cv::Rect2f(c.x - box.width * g / 2, c.y - box.height * g / 2, box.width * g, box.height * g)));
      }
      std::vector<std::string> labels;
      // The keypoint boxes are enlarged (templates were cut with context); the posture SVMs were trained
      // on hand boxes as annotated, so they get the box as detected.
      const HandGestureReader reader(gestures_.get(), posture_.get());
      for (const GestureReading& r : reader.read(gray, hand_boxes, detected_boxes))
        if (const GestureResult& g = r.result; !g.label.empty())
        {
          biovision_msgs::Gesture m;
          m.label = g.label;
          m.method = r.method;
          m.score = static_cast<float>(g.score);
          m.box = toRoi(cv::Rect2f(g.box), size);
          gestures_msg->gestures.push_back(m);
          labels.push_back(g.label);
        }

      const double t = msg->header.stamp.toSec();
      if (t > last_image_t_)
      {
        last_image_t_ = t;
        image_time_moved_ = ros::WallTime::now();
      }
      if (start_requested_)
      {
        start_requested_ = false;
        behaviour_->start(t, pan_, tilt_);
        started = true;
      }
      behaviour = behaviour_->update(t, size, face_boxes, labels, pan_, tilt_);
      if (behaviour.finished)
      {
        last_reason_ = behaviour.reason;
        last_action_ = behaviour.action;
      }
      last_faces_ = faces.size();
      last_hands_ = hands.size();
      last_gestures_ = labels.size();
      last_ms_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    }
    catch (const std::exception& e)  // ImageConversionError, invalid_argument, cv::Exception
    {
      diagnostics_.health().reportError(getName(), "dropping image " + std::to_string(msg->width) + "x" +
                                                       std::to_string(msg->height) + " '" + msg->encoding + "' from " +
                                                       input_topic_ + ": " + e.what());
      return;
    }
  }
  faces_pub_.publish(faces_msg);
  hands_pub_.publish(hands_msg);
  gestures_pub_.publish(gestures_msg);
  diagnostics_.tick();

  if (started)
    setHeadMode("hold");
  if (behaviour.head_active)
  {
    std_msgs::Float64 pan, tilt;
    pan.data = behaviour.pan;
    tilt.data = behaviour.tilt;
    pan_pub_.publish(pan);
    tilt_pub_.publish(tilt);
  }
  if (!behaviour.action.empty())
  {
    std_msgs::String action;
    action.data = behaviour.action;
    action_pub_.publish(action);
    NODELET_INFO("hri: gesture '%s' -> action '%s'", behaviour.gesture.c_str(), behaviour.action.c_str());
  }
  if (behaviour.finished)
  {
    NODELET_INFO("hri: greeting finished: %s", behaviour.reason.c_str());
    setHeadMode("explore");
  }
}

void HriNodelet::details(diagnostic_updater::DiagnosticStatusWrapper& status)
{
  std::lock_guard<std::mutex> lock(mutex_);
  status.add("last processing time [ms]", last_ms_);
  status.add("last faces", last_faces_);
  status.add("last hands", last_hands_);
  status.add("last gestures", last_gestures_);
  status.add("gesture templates", gestures_ ? gestures_->templates().views().size() : 0);
  status.add("posture classes", posture_ ? posture_->labels().size() : 0);
  status.add("greet state", GreetBehaviour::name(behaviour_->state()));
  status.add("joint states received", have_joints_);
  status.add("last greeting result", last_reason_);
  status.add("last action", last_action_);
  std::lock_guard<std::mutex> head_lock(head_mode_mutex_);
  status.add("head/set_mode", head_mode_answer_.empty() ? "not called" : head_mode_answer_);
  // A configured gesture method that could not be loaded stays a warning (the ERROR at start passes).
  for (const std::string* off : {&gestures_off_, &posture_off_})
    if (!off->empty())
      status.mergeSummary(diagnostic_msgs::DiagnosticStatus::WARN, *off);
}
}  // namespace biovision_hri

PLUGINLIB_EXPORT_CLASS(biovision_hri::HriNodelet, nodelet::Nodelet)
