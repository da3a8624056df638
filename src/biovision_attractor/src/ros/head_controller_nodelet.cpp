#include "biovision_attractor/ros/head_controller_nodelet.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <stdexcept>

#include <biovision_msgs/AttractorState.h>
#include <dynamic_reconfigure/Config.h>
#include <pluginlib/class_list_macros.hpp>
#include <std_msgs/Float64.h>
#include <urdf/model.h>

#include "biovision_ros_common/input_check.hpp"

namespace biovision_attractor
{
namespace
{
template <typename Field>
Field fieldNamed(const std::vector<std::pair<std::string, Field>>& fields, const std::string& name)
{
  for (const auto& [field_name, field] : fields)
    if (field_name == name)
      return field;
  throw std::logic_error("cfg/HeadController.cfg parameter '" + name + "' has no HeadAttractorParameters field");
}

// A diagnostic value: the number, or "none" for NaN.
std::string valueOrNone(double x)
{
  return std::isnan(x) ? "none" : std::to_string(x);
}

std::string interval(double lower, double upper)
{
  std::ostringstream s;
  s << "[" << lower << ", " << upper << "]";
  return s.str();
}
}  // namespace

HeadControllerNodelet::~HeadControllerNodelet() = default;

HeadAttractorParameters HeadControllerNodelet::parametersFromConfig(const HeadControllerConfig& config,
                                                                    HeadAttractorParameters base)
{
  dynamic_reconfigure::Config values;
  config.__toMessage__(values);
  for (const auto& d : values.doubles)
    base.*fieldNamed(HeadAttractorParameters::namedDoubles(), d.name) = d.value;
  for (const auto& b : values.bools)
    base.*fieldNamed(HeadAttractorParameters::namedBools(), b.name) = b.value;
  if (!values.ints.empty() || !values.strs.empty())
    throw std::logic_error("cfg/HeadController.cfg has int or string parameters, which have no field");
  return base;
}

void HeadControllerNodelet::onInit()
{
  ros::NodeHandle& nh = getNodeHandle();
  try
  {
    readSettings();
    readJointLimits();
  }
  catch (const std::invalid_argument& e)
  {
    NODELET_FATAL("%s", e.what());  // start-up configuration: fail loudly rather than run misconfigured
    throw;
  }
  {
    std::lock_guard<std::mutex> lock(mutex_);
    attractor_ = std::make_unique<HeadAttractor>(base_);
    HeadAttractor::Behaviour behaviour;
    HeadAttractor::parseBehaviour(settings_.mode, behaviour);  // validated in readSettings()
    attractor_->setBehaviour(behaviour);
    half_fov_ = settings_.horizontal_fov / 2;
    tilt_ = base_.default_tilt;
    last_output_.command = last_output_.tilt_command = last_output_.target = std::nan("");  // no step yet
  }
  startDiagnostics();
  // The attractor parameters from YAML arrive through dynamic_reconfigure's server (it reads ~).
  applied_config_ = HeadControllerConfig::__getDefault__();
  reconfigure_server_ = std::make_unique<dynamic_reconfigure::Server<HeadControllerConfig>>(reconfigure_mutex_,
                                                                                            getPrivateNodeHandle());
  reconfigure_server_->setCallback([this](HeadControllerConfig& c, uint32_t level) { reconfigure(c, level); });

  pan_pub_ = nh.advertise<std_msgs::Float64>(settings_.pan_joint + "/command", 10);
  tilt_pub_ = nh.advertise<std_msgs::Float64>(settings_.tilt_joint + "/command", 10);
  state_pub_ = nh.advertise<biovision_msgs::AttractorState>("attractor/head", 10);
  regions_sub_ = nh.subscribe("saliency/regions", 5, &HeadControllerNodelet::onRegions, this);
  joints_sub_ = nh.subscribe("joint_states", 20, &HeadControllerNodelet::onJointStates, this);
  info_sub_ = nh.subscribe("camera_info", 1, &HeadControllerNodelet::onCameraInfo, this);
  mode_srv_ = nh.advertiseService("head/set_mode", &HeadControllerNodelet::onSetMode, this);
  timer_ = nh.createTimer(ros::Duration(1.0 / settings_.control_rate), &HeadControllerNodelet::step, this);
}

void HeadControllerNodelet::readSettings()
{
  ros::NodeHandle& pnh = getPrivateNodeHandle();
  HeadControllerSettings s;
  pnh.param("mode", s.mode, s.mode);
  pnh.param("pan_joint", s.pan_joint, s.pan_joint);
  pnh.param("tilt_joint", s.tilt_joint, s.tilt_joint);
  pnh.param("control_rate", s.control_rate, s.control_rate);
  pnh.param("joint_state_timeout", s.joint_state_timeout, s.joint_state_timeout);
  pnh.param("min_region_area", s.min_region_area, s.min_region_area);
  pnh.param("horizontal_fov", s.horizontal_fov, s.horizontal_fov);
  s.validate();
  settings_ = s;
}

void HeadControllerNodelet::readJointLimits()
{
  // Never command beyond the robot's limits: take them from the description when there is one.
  urdf::Model model;
  if (!model.initParam("robot_description"))
  {
    NODELET_WARN("no robot_description: pan limits %s, tilt limits %s rad (defaults)",
                 interval(base_.pan_lower, base_.pan_upper).c_str(),
                 interval(base_.tilt_lower, base_.tilt_upper).c_str());
    return;
  }
  if (auto j = model.getJoint(settings_.pan_joint); j && j->limits)
  {
    base_.pan_lower = j->limits->lower;
    base_.pan_upper = j->limits->upper;
  }
  else
    NODELET_WARN("robot_description has no limits for %s: using the defaults", settings_.pan_joint.c_str());
  if (auto j = model.getJoint(settings_.tilt_joint); j && j->limits)
  {
    base_.tilt_lower = j->limits->lower;
    base_.tilt_upper = j->limits->upper;
    base_.default_tilt = std::clamp(base_.default_tilt, base_.tilt_lower, base_.tilt_upper);
  }
  else
    NODELET_WARN("robot_description has no limits for %s: using the defaults", settings_.tilt_joint.c_str());
  base_.validate();  // a URDF with lower >= upper
}

void HeadControllerNodelet::startDiagnostics()
{
  biovision_ros_common::DiagnosticsOptions options;
  options.status_name = "head controller";
  options.rate_topic = settings_.pan_joint + "/command";
  options.default_max_rate = 2 * settings_.control_rate;
  options.idle = [this] { return holding_.load(); };
  options.idle_message = "holding";
  options.working_message = "controlling";
  options.details = [this](diagnostic_updater::DiagnosticStatusWrapper& s) { details(s); };
  diagnostics_.init(getNodeHandle(), getPrivateNodeHandle(), getName(), options);
  diagnostics_.clockJumps().onJumpBack([this] { onTimeJumpBack(); });
}

void HeadControllerNodelet::reconfigure(HeadControllerConfig& config, uint32_t /*level*/)
{
  try
  {
    HeadAttractorParameters p = parametersFromConfig(config, base_);
    p.default_tilt = std::clamp(p.default_tilt, base_.tilt_lower, base_.tilt_upper);
    std::lock_guard<std::mutex> lock(mutex_);
    attractor_->setParameters(p);  // throws, keeping the previous parameters
    applied_config_ = config;
  }
  catch (const std::invalid_argument& e)
  {
    diagnostics_.health().reportError(getName(),
                                      std::string("rejected parameters (keeping the previous ones): ") + e.what());
    config = applied_config_;  // the server then reports the parameters in use
  }
}

void HeadControllerNodelet::onRegions(const biovision_msgs::SalientRegionArrayConstPtr& msg)
{
  // A region's direction must be a finite angle within ±pi and its saliency finite, else it is a damaged
  // message; more than kMaxRegions regions are a flood: only the first (the most salient) are looked at.
  std::vector<SeenRegion> regions;
  size_t dropped = 0;
  const size_t looked_at = std::min(msg->regions.size(), kMaxRegions);
  for (size_t i = 0; i < looked_at; ++i)
  {
    const auto& r = msg->regions[i];
    if (!(std::isfinite(r.pan) && std::isfinite(r.tilt) && std::isfinite(r.peak_saliency) && std::abs(r.pan) <= M_PI &&
          std::abs(r.tilt) <= M_PI))
      ++dropped;
    else if (r.area >= settings_.min_region_area)
      regions.push_back({r.pan, r.tilt, r.peak_saliency, static_cast<double>(r.area)});
  }
  {
    std::lock_guard<std::mutex> lock(mutex_);
    regions_ = std::move(regions);
    latest_regions_ = msg;
    dropped_regions_ += dropped;
  }
  if (dropped > 0)
    diagnostics_.health().reportError(getName(), "dropped " + std::to_string(dropped) + " of " +
                                                     std::to_string(msg->regions.size()) +
                                                     " salient regions with a NaN/Inf or beyond-pi pan/tilt, or a "
                                                     "NaN/Inf peak saliency");
  if (msg->regions.size() > kMaxRegions)
    diagnostics_.health().reportError(getName(), "a message of " + std::to_string(msg->regions.size()) +
                                                     " salient regions: only the first " + std::to_string(kMaxRegions) +
                                                     " are used");
}

void HeadControllerNodelet::onJointStates(const sensor_msgs::JointStateConstPtr& msg)
{
  std::map<std::string, double> found;
  try
  {
    found = biovision_ros_common::InputCheck::jointPositions(*msg, {settings_.pan_joint, settings_.tilt_joint});
  }
  catch (const biovision_ros_common::InputError& e)
  {
    diagnostics_.health().reportError(getName(), std::string("ignoring ") + e.what());
    return;
  }
  std::lock_guard<std::mutex> lock(mutex_);
  if (auto it = found.find(settings_.pan_joint); it != found.end())
  {
    pan_ = it->second;
    joints_received_ = ros::Time::now();
  }
  if (auto it = found.find(settings_.tilt_joint); it != found.end())
    tilt_ = it->second;
}

void HeadControllerNodelet::onCameraInfo(const sensor_msgs::CameraInfoConstPtr& msg)
{
  try
  {
    biovision_ros_common::InputCheck::cameraInfo(*msg);
  }
  catch (const biovision_ros_common::InputError& e)
  {
    diagnostics_.health().reportError(getName(),
                                      std::string("ignoring ") + e.what() + " (keeping the current field of view)");
    return;
  }
  std::lock_guard<std::mutex> lock(mutex_);
  half_fov_ = std::atan(0.5 * msg->width / msg->P[0]);
}

bool HeadControllerNodelet::onSetMode(biovision_msgs::SetHeadMode::Request& req,
                                      biovision_msgs::SetHeadMode::Response& res)
{
  std::lock_guard<std::mutex> lock(mutex_);
  HeadAttractor::Behaviour behaviour;
  if (!HeadAttractor::parseBehaviour(req.mode, behaviour))
  {
    res.success = false;
    res.message = "unknown mode '" + req.mode + "' (explore, track, look_ahead, hold)";
    return true;
  }
  double angle = 0.0;
  if (behaviour == HeadAttractor::Behaviour::kTrack)
  {
    // "region:<rank>" tracks the direction of that salient region; labels need recognition.
    unsigned rank = 0;
    if (req.target.rfind("region:", 0) != 0 || !(std::istringstream(req.target.substr(7)) >> rank) ||
        !latest_regions_ || rank >= latest_regions_->regions.size() ||
        !std::isfinite(latest_regions_->regions[rank].pan) || std::abs(latest_regions_->regions[rank].pan) > M_PI)
    {
      res.success = false;
      res.message = "track needs target 'region:<rank>' of a current salient region with a finite pan within +-pi";
      return true;
    }
    angle = latest_regions_->regions[rank].pan;
  }
  try
  {
    attractor_->setBehaviour(behaviour, angle);
  }
  catch (const std::invalid_argument& e)
  {
    res.success = false;
    res.message = e.what();
    return true;
  }
  res.success = true;
  res.message = std::string("head mode ") + HeadAttractor::name(behaviour);
  return true;
}

void HeadControllerNodelet::onTimeJumpBack()
{
  {
    std::lock_guard<std::mutex> lock(mutex_);
    attractor_->reset();
    regions_.clear();
    joints_received_ = ros::Time();  // its age is meaningless now: hold until the next joint state
    last_step_ = ros::Time();
  }
  diagnostics_.health().reportError(getName(), "ROS time jumped back: attractor memory and timers reset");
}

void HeadControllerNodelet::step(const ros::TimerEvent& /*event*/)
{
  const ros::Time now = ros::Time::now();
  diagnostics_.clockJumps().observe(now);  // before taking mutex_: a jump runs onTimeJumpBack(), which takes it
  HeadAttractor::Output out;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    const double dt = last_step_.isZero() ? 1.0 / settings_.control_rate : (now - last_step_).toSec();
    last_step_ = now;
    holding_ = joints_received_.isZero() || (now - joints_received_).toSec() > settings_.joint_state_timeout;
    if (holding_)
    {
      // Without knowing where the head is, do not move it.
      NODELET_WARN_THROTTLE(5.0, "no joint_states for %s in %.1f s; holding", settings_.pan_joint.c_str(),
                            settings_.joint_state_timeout);
      return;
    }
    out = attractor_->update(regions_, pan_, now.toSec(), dt, half_fov_, tilt_);
    regions_.clear();  // each frame's regions are used once
    last_output_ = out;
  }
  publishCommands(out);
  publishState(out, now);
}

void HeadControllerNodelet::publishCommands(const HeadAttractor::Output& out)
{
  if (!std::isfinite(out.command) || !std::isfinite(out.tilt_command))
  {
    diagnostics_.health().reportError(getName(), "the attractor gave a NaN/Inf command: not sent");
    return;
  }
  // HeadAttractor clamps already; this is the last line before the motors.
  std_msgs::Float64 pan, tilt;
  pan.data = std::clamp(out.command, base_.pan_lower, base_.pan_upper);
  tilt.data = std::clamp(out.tilt_command, base_.tilt_lower, base_.tilt_upper);
  pan_pub_.publish(pan);
  tilt_pub_.publish(tilt);
  diagnostics_.tick();
}

void HeadControllerNodelet::publishState(const HeadAttractor::Output& out, const ros::Time& now)
{
  biovision_msgs::AttractorState s;
  s.header.stamp = now;
  s.controller = "head_pan";
  std::lock_guard<std::mutex> lock(mutex_);
  s.behaviour = HeadAttractor::name(attractor_->behaviour());
  for (double a : attractor_->sectionAngles())
    s.section_angles.push_back(static_cast<float>(a));
  for (size_t i = 0; i < out.attraction.size(); ++i)
  {
    s.attraction.push_back(static_cast<float>(out.attraction[i]));
    s.repulsion.push_back(static_cast<float>(out.repulsion[i]));
    s.forcelet.push_back(static_cast<float>(out.forcelet[i]));
  }
  s.rate = static_cast<float>(out.rate);
  s.angle = static_cast<float>(pan_);
  s.target = static_cast<float>(out.target);
  state_pub_.publish(s);
}

void HeadControllerNodelet::details(diagnostic_updater::DiagnosticStatusWrapper& status)
{
  std::lock_guard<std::mutex> lock(mutex_);
  const ros::Time now = ros::Time::now();
  status.add("mode", HeadAttractor::name(attractor_->behaviour()));
  status.add("target [rad]", valueOrNone(last_output_.target));
  status.add("pan [rad]", pan_);
  status.add("tilt [rad]", tilt_);
  status.add("pan command [rad]", valueOrNone(last_output_.command));
  status.add("tilt command [rad]", valueOrNone(last_output_.tilt_command));
  status.add("pan limits [rad]", interval(base_.pan_lower, base_.pan_upper));
  status.add("tilt limits [rad]", interval(base_.tilt_lower, base_.tilt_upper));
  status.add("horizontal field of view [rad]", 2 * half_fov_);
  status.add("regions dropped (NaN/Inf)", dropped_regions_);
  if (joints_received_.isZero())
  {
    status.add("joint state age [s]", "none yet");
    status.mergeSummary(diagnostic_msgs::DiagnosticStatus::WARN,
                        "holding: no joint_states of " + settings_.pan_joint + " yet");
    return;
  }
  const double age = (now - joints_received_).toSec();
  status.add("joint state age [s]", age);
  if (holding_)
    status.mergeSummary(diagnostic_msgs::DiagnosticStatus::WARN,
                        "holding: " + settings_.pan_joint + " state " + std::to_string(age) + " s old");
}
}  // namespace biovision_attractor

PLUGINLIB_EXPORT_CLASS(biovision_attractor::HeadControllerNodelet, nodelet::Nodelet)
