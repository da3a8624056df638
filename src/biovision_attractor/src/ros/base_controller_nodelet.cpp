#include "biovision_attractor/ros/base_controller_nodelet.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <biovision_msgs/AttractorState.h>
#include <geometry_msgs/Twist.h>
#include <pluginlib/class_list_macros.hpp>

#include "biovision_attractor/forcelets.hpp"
#include "biovision_attractor/ros/base_controller_config.hpp"

namespace biovision_attractor
{
namespace
{
constexpr double kInf = std::numeric_limits<double>::infinity();

double wrap(double a)
{
  return std::atan2(std::sin(a), std::cos(a));
}

double yawOf(const geometry_msgs::Quaternion& q)
{
  return std::atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z));
}

bool finiteQuaternion(const geometry_msgs::Quaternion& q)
{
  return std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z) && std::isfinite(q.w) &&
         q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w > 1e-6;
}
}  // namespace

BaseControllerNodelet::~BaseControllerNodelet() = default;

void BaseControllerNodelet::onInit()
{
  ros::NodeHandle& nh = getNodeHandle();
  try
  {
    readSettings();
  }
  catch (const std::invalid_argument& e)
  {
    NODELET_FATAL("%s", e.what());
    throw;
  }
  {
    std::lock_guard<std::mutex> lock(mutex_);
    attractor_ = std::make_unique<BaseAttractor>(BaseAttractorParameters());
  }
  startDiagnostics();
  applied_config_ = BaseControllerConfig::__getDefault__();
  reconfigure_server_ = std::make_unique<dynamic_reconfigure::Server<BaseControllerConfig>>(reconfigure_mutex_,
                                                                                            getPrivateNodeHandle());
  reconfigure_server_->setCallback([this](BaseControllerConfig& c, uint32_t level) { reconfigure(c, level); });

  tf_buffer_ = std::make_unique<tf2_ros::Buffer>();
  tf_listener_ = std::make_unique<tf2_ros::TransformListener>(*tf_buffer_, nh);
  cmd_pub_ = nh.advertise<geometry_msgs::Twist>("cmd_vel", 10);
  state_pub_ = nh.advertise<biovision_msgs::AttractorState>("attractor/base", 10);
  stm_sub_ = nh.subscribe("memory/stm", 5, &BaseControllerNodelet::onStm, this);
  odom_sub_ = nh.subscribe("odom", 20, &BaseControllerNodelet::onOdom, this);
  goal_sub_ = nh.subscribe("goal", 5, &BaseControllerNodelet::onGoal, this);
  bearing_sub_ = nh.subscribe("goal_bearing", 5, &BaseControllerNodelet::onGoalBearing, this);
  pioneer_sub_ = nh.subscribe("pioneer_state", 5, &BaseControllerNodelet::onPioneerState, this);
  stop_srv_ = nh.advertiseService("base/stop", &BaseControllerNodelet::onStop, this);
  hold_srv_ = nh.advertiseService("base/hold", &BaseControllerNodelet::onHold, this);
  timer_ = nh.createTimer(ros::Duration(1.0 / settings_.control_rate), &BaseControllerNodelet::step, this);
}

void BaseControllerNodelet::readSettings()
{
  ros::NodeHandle& pnh = getPrivateNodeHandle();
  BaseControllerSettings s;
  pnh.param("odom_frame", s.odom_frame, s.odom_frame);
  pnh.param("control_rate", s.control_rate, s.control_rate);
  pnh.param("stm_timeout", s.stm_timeout, s.stm_timeout);
  pnh.param("odom_timeout", s.odom_timeout, s.odom_timeout);
  pnh.param("max_goal_distance", s.max_goal_distance, s.max_goal_distance);
  s.validate();
  settings_ = s;
}

void BaseControllerNodelet::startDiagnostics()
{
  biovision_ros_common::DiagnosticsOptions options;
  options.status_name = "base controller";
  options.rate_topic = "cmd_vel";
  options.default_max_rate = 2 * settings_.control_rate;
  options.idle = [this] {
    std::lock_guard<std::mutex> lock(mutex_);
    return mode_ == Mode::kIdle;
  };
  options.idle_message = "idle: no goal";
  options.working_message = "driving";
  options.details = [this](diagnostic_updater::DiagnosticStatusWrapper& s) { details(s); };
  diagnostics_.init(getNodeHandle(), getPrivateNodeHandle(), getName(), options);
  diagnostics_.clockJumps().onJumpBack([this] { onTimeJumpBack(); });
}

void BaseControllerNodelet::reconfigure(BaseControllerConfig& config, uint32_t /*level*/)
{
  try
  {
    const BaseAttractorParameters p = toBaseAttractorParameters(config);
    std::lock_guard<std::mutex> lock(mutex_);
    attractor_->setParameters(p);  // throws, keeping the previous parameters
    applied_config_ = config;
  }
  catch (const std::invalid_argument& e)
  {
    diagnostics_.health().reportError(getName(),
                                      std::string("rejected parameters (keeping the previous ones): ") + e.what());
    config = applied_config_;
  }
}

void BaseControllerNodelet::onStm(const biovision_msgs::EgoMapConstPtr& msg)
{
  const ros::Time now = ros::Time::now();
  std::string problem;
  const size_t n = msg->section_angles.size();
  if (n == 0 || msg->obstacle_distance.size() != n || (!msg->confidence.empty() && msg->confidence.size() != n) ||
      (!msg->obstacle_offset.empty() && msg->obstacle_offset.size() != n))
    problem = "unequal or empty section_angles/obstacle_distance/obstacle_offset/confidence arrays";
  else if (msg->header.stamp.isZero())
    problem = "an unstamped map";
  else if (msg->header.stamp > now + ros::Duration(settings_.stm_timeout))
    problem = "a stamp " + std::to_string((msg->header.stamp - now).toSec()) + " s in the future";
  std::vector<BaseAttractor::Sector> sectors(n);
  const double width = std::isfinite(msg->section_width) && msg->section_width > 0
                           ? msg->section_width
                           : BaseAttractorParameters::kSectorWidth;
  for (size_t i = 0; problem.empty() && i < n; ++i)
  {
    BaseAttractor::Sector& s = sectors[i];
    s.angle = msg->section_angles[i];
    s.distance = msg->obstacle_distance[i];
    s.confidence = msg->confidence.empty() ? 1.0 : msg->confidence[i];
    s.width = width;
    // Absent, NaN or negative: BaseAttractor puts the sector's obstacle at the sector's edge.
    s.offset = msg->obstacle_offset.empty() ? std::numeric_limits<double>::quiet_NaN() : msg->obstacle_offset[i];
    if (!std::isfinite(s.angle) || std::abs(s.angle) > M_PI || std::isnan(s.distance) || std::isnan(s.confidence))
      problem = "a NaN/Inf or beyond-pi section angle or a NaN distance or confidence in sector " + std::to_string(i);
  }
  if (!problem.empty())
  {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      ++rejected_stm_;
    }
    // Not used: the last good map ages and the watchdog stops the base.
    diagnostics_.health().reportError(getName(), "rejected memory/stm with " + problem);
    return;
  }
  std::lock_guard<std::mutex> lock(mutex_);
  stm_ = std::move(sectors);
  stm_received_ = now;
  stm_stamp_ = msg->header.stamp;
}

void BaseControllerNodelet::onOdom(const nav_msgs::OdometryConstPtr& msg)
{
  const auto& p = msg->pose.pose;
  if (!std::isfinite(p.position.x) || !std::isfinite(p.position.y) || !finiteQuaternion(p.orientation))
  {
    diagnostics_.health().reportError(getName(), "rejected odom with a NaN/Inf pose");
    return;
  }
  if (!msg->header.frame_id.empty() && msg->header.frame_id != settings_.odom_frame)
  {
    diagnostics_.health().reportError(getName(), "rejected odom in frame '" + msg->header.frame_id + "' (expected '" +
                                                     settings_.odom_frame + "')");
    return;
  }
  std::lock_guard<std::mutex> lock(mutex_);
  pose_ = {p.position.x, p.position.y, yawOf(p.orientation)};
  odom_received_ = ros::Time::now();
  odom_stamp_ = msg->header.stamp.isZero() ? odom_received_ : msg->header.stamp;
}

void BaseControllerNodelet::refuseGoal(const std::string& why)
{
  {
    std::lock_guard<std::mutex> lock(mutex_);
    mode_ = Mode::kIdle;
    ++refused_goals_;
  }
  diagnostics_.health().reportError(getName(), "refused goal: " + why + " (stopping)");
}

void BaseControllerNodelet::onGoal(const geometry_msgs::PoseStampedConstPtr& msg)
{
  const auto& p = msg->pose.position;
  if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
    return refuseGoal("a NaN/Inf position");
  double x = p.x, y = p.y;
  if (!msg->header.frame_id.empty() && msg->header.frame_id != settings_.odom_frame)
  {
    geometry_msgs::TransformStamped t;
    try
    {
      t = tf_buffer_->lookupTransform(settings_.odom_frame, msg->header.frame_id, ros::Time(0), ros::Duration(0.2));
    }
    catch (const tf2::TransformException& e)
    {
      return refuseGoal("no transform " + msg->header.frame_id + " -> " + settings_.odom_frame + ": " + e.what());
    }
    // Rotate by the transform's quaternion, then translate: x' = q p q* + t.
    const auto& q = t.transform.rotation;
    const double px = p.x, py = p.y, pz = p.z;
    const double tx = 2 * (q.y * pz - q.z * py), ty = 2 * (q.z * px - q.x * pz), tz = 2 * (q.x * py - q.y * px);
    x = px + q.w * tx + (q.y * tz - q.z * ty) + t.transform.translation.x;
    y = py + q.w * ty + (q.z * tx - q.x * tz) + t.transform.translation.y;
  }
  bool too_far = false;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    too_far = !odom_received_.isZero() && std::hypot(x - pose_.x, y - pose_.y) > settings_.max_goal_distance;
    if (!too_far)
    {
      goal_x_ = x;
      goal_y_ = y;
      mode_ = Mode::kPose;
      zero_sent_ = false;
      attractor_->newGoal();
    }
  }
  if (too_far)
    refuseGoal("farther than max_goal_distance = " + std::to_string(settings_.max_goal_distance) + " m");
}

void BaseControllerNodelet::onGoalBearing(const std_msgs::Float64ConstPtr& msg)
{
  if (!std::isfinite(msg->data) || std::abs(msg->data) > 2 * M_PI)
    return refuseGoal("a bearing of " + std::to_string(msg->data) + " rad (expected a finite angle within +-2 pi)");
  bool no_odom = false;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    no_odom = odom_received_.isZero();
    if (!no_odom)
    {
      goal_heading_ = wrap(pose_.yaw + msg->data);
      mode_ = Mode::kBearing;
      zero_sent_ = false;
      attractor_->newGoal();
    }
  }
  if (no_odom)
    refuseGoal("a bearing before any odometry");
}

void BaseControllerNodelet::onPioneerState(const biovision_msgs::PioneerStateConstPtr& msg)
{
  const std::string what = msg->front_bumpers != 0 || msg->rear_bumpers != 0 ? "bumper"
                           : msg->left_stall || msg->right_stall             ? "stall"
                                                                             : "";
  std::lock_guard<std::mutex> lock(mutex_);
  if (!what.empty())
  {
    if (stopped_by_.empty())
      NODELET_WARN("pioneer_state reports a %s: stopping the base and forgetting the goal", what.c_str());
    stopped_by_ = what;
    mode_ = Mode::kIdle;
    attractor_->stop();
  }
  else
    stopped_by_.clear();
}

bool BaseControllerNodelet::onStop(std_srvs::Trigger::Request& /*req*/, std_srvs::Trigger::Response& res)
{
  {
    std::lock_guard<std::mutex> lock(mutex_);
    mode_ = Mode::kIdle;
    hold_ = false;
    attractor_->stop();
  }
  publishZero();
  res.success = true;
  res.message = "stopped; goal forgotten";
  return true;
}

bool BaseControllerNodelet::onHold(std_srvs::SetBool::Request& req, std_srvs::SetBool::Response& res)
{
  {
    std::lock_guard<std::mutex> lock(mutex_);
    hold_ = req.data;
    attractor_->stop();
  }
  if (req.data)
    publishZero();
  res.success = true;
  res.message = req.data ? "holding (goal kept)" : "resumed";
  return true;
}

void BaseControllerNodelet::onTimeJumpBack()
{
  {
    std::lock_guard<std::mutex> lock(mutex_);
    attractor_->reset();
    stm_received_ = stm_stamp_ = odom_received_ = odom_stamp_ = last_step_ = ros::Time();
  }
  diagnostics_.health().reportError(getName(), "ROS time jumped back: waiting for fresh STM and odometry");
}

void BaseControllerNodelet::publishZero()
{
  cmd_pub_.publish(geometry_msgs::Twist());
  diagnostics_.tick();
}

void BaseControllerNodelet::step(const ros::TimerEvent& /*event*/)
{
  const ros::Time now = ros::Time::now();
  diagnostics_.clockJumps().observe(now);  // before mutex_: a jump runs onTimeJumpBack(), which takes it
  BaseAttractor::Output out;
  BaseAttractorParameters p;
  std::string behaviour;
  double goal_bearing = std::nan("");
  enum
  {
    kNothing,
    kZero,
    kCommand
  } action = kNothing;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    p = attractor_->parameters();
    const double dt = last_step_.isZero() ? 1.0 / settings_.control_rate : (now - last_step_).toSec();
    last_step_ = now;
    auto stale = [&](const ros::Time& received, const ros::Time& stamp, double timeout) {
      return received.isZero() || (now - received).toSec() > timeout || (now - stamp).toSec() > timeout;
    };
    if (!stopped_by_.empty())
    {
      behaviour_ = stopped_by_;
      action = kZero;
    }
    else if (mode_ == Mode::kIdle)
    {
      behaviour_ = "idle";
      action = zero_sent_ ? kNothing : kZero;
      zero_sent_ = true;
    }
    else if (hold_)
    {
      behaviour_ = "hold";
      action = kZero;
    }
    else if (stale(stm_received_, stm_stamp_, settings_.stm_timeout) ||
             stale(odom_received_, odom_stamp_, settings_.odom_timeout))
    {
      behaviour_ = "watchdog";
      attractor_->stop();
      ++watchdog_stops_;
      NODELET_WARN_THROTTLE(2.0, "no fresh memory/stm or odom within %.2f s: base stopped", settings_.stm_timeout);
      action = kZero;
    }
    else
    {
      double distance = kInf;
      if (mode_ == Mode::kPose)
      {
        goal_bearing = wrap(std::atan2(goal_y_ - pose_.y, goal_x_ - pose_.x) - pose_.yaw);
        distance = std::hypot(goal_x_ - pose_.x, goal_y_ - pose_.y);
      }
      else
        goal_bearing = wrap(goal_heading_ - pose_.yaw);
      out = attractor_->update(stm_, goal_bearing, distance, now.toSec(), dt);
      behaviour_ = BaseAttractor::name(out.status);
      last_output_ = out;
      action = kCommand;
    }
    behaviour = behaviour_;
  }
  if (action == kZero)
  {
    publishZero();
    // The behaviour (hold, watchdog, bumper, idle) for the task manager and plots; no forcelets.
    publishState(BaseAttractor::Output(), behaviour, goal_bearing, now);
  }
  if (action != kCommand)
    return;
  geometry_msgs::Twist cmd;
  // BaseAttractor keeps its commands inside the limits already; this is the last line before the motors.
  cmd.linear.x = std::isfinite(out.linear) ? std::clamp(out.linear, 0.0, p.max_linear) : 0.0;
  cmd.angular.z = std::isfinite(out.angular) ? std::clamp(out.angular, -p.max_angular, p.max_angular) : 0.0;
  cmd_pub_.publish(cmd);
  diagnostics_.tick();
  publishState(out, behaviour, goal_bearing, now);
}

void BaseControllerNodelet::publishState(const BaseAttractor::Output& out, const std::string& behaviour,
                                         double goal_bearing, const ros::Time& now)
{
  biovision_msgs::AttractorState s;
  s.header.stamp = now;
  s.header.frame_id = "base_link";
  s.controller = "base";
  s.behaviour = behaviour;
  std::vector<BaseAttractor::Sector> stm;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stm = stm_;
  }
  // The goal's attraction is shown in the sector of its bearing, so that the forcelets sum to the rate.
  int goal_sector = -1;
  double nearest = kInf;
  for (size_t i = 0; i < stm.size(); ++i)
    if (std::abs(wrap(stm[i].angle - goal_bearing)) < nearest)
    {
      nearest = std::abs(wrap(stm[i].angle - goal_bearing));
      goal_sector = static_cast<int>(i);
    }
  for (size_t i = 0; i < stm.size() && i < out.forcelet.size(); ++i)
  {
    const bool goal_here = static_cast<int>(i) == goal_sector;
    s.section_angles.push_back(static_cast<float>(stm[i].angle));
    s.attraction.push_back(goal_here ? 1.0f : 0.0f);
    s.repulsion.push_back(static_cast<float>(out.strength[i]));
    s.forcelet.push_back(static_cast<float>(out.forcelet[i] + (goal_here ? out.goal_forcelet : 0.0)));
  }
  s.rate = static_cast<float>(out.angular);
  s.angle = 0.0f;
  s.target = static_cast<float>(goal_bearing);
  state_pub_.publish(s);
}

void BaseControllerNodelet::details(diagnostic_updater::DiagnosticStatusWrapper& status)
{
  std::lock_guard<std::mutex> lock(mutex_);
  const ros::Time now = ros::Time::now();
  status.add("behaviour", behaviour_);
  status.add("mode", mode_ == Mode::kIdle ? "no goal" : mode_ == Mode::kPose ? "pose goal" : "bearing goal");
  if (mode_ == Mode::kPose)
    status.add("goal [m] (" + settings_.odom_frame + ")", std::to_string(goal_x_) + ", " + std::to_string(goal_y_));
  status.add("linear command [m/s]", last_output_.linear);
  status.add("angular command [rad/s]", last_output_.angular);
  status.add("front clearance [m]", last_output_.front_clearance);
  status.add("STM age [s]", stm_received_.isZero() ? "none yet" : std::to_string((now - stm_received_).toSec()));
  status.add("odom age [s]", odom_received_.isZero() ? "none yet" : std::to_string((now - odom_received_).toSec()));
  status.add("watchdog stops (control steps)", watchdog_stops_);
  status.add("rejected STM maps", rejected_stm_);
  status.add("refused goals", refused_goals_);
  if (behaviour_ == "watchdog")
    status.mergeSummary(diagnostic_msgs::DiagnosticStatus::WARN, "watchdog: STM or odometry stale, base stopped");
  else if (behaviour_ == "trapped")
    status.mergeSummary(diagnostic_msgs::DiagnosticStatus::WARN, "trapped: no progress, turning to the freer side");
  else if (behaviour_ == "bumper" || behaviour_ == "stall")
    status.mergeSummary(diagnostic_msgs::DiagnosticStatus::WARN, behaviour_ + ": base stopped");
}
}  // namespace biovision_attractor

PLUGINLIB_EXPORT_CLASS(biovision_attractor::BaseControllerNodelet, nodelet::Nodelet)
