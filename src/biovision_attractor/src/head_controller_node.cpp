// head_controller: attractor-dynamics control of the head's pan (thesis 4.7) from salient regions.
#include <cmath>
#include <memory>
#include <mutex>
#include <sstream>

#include <biovision_msgs/AttractorState.h>
#include <biovision_msgs/SalientRegionArray.h>
#include <biovision_msgs/SetHeadMode.h>
#include <ros/ros.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/JointState.h>
#include <std_msgs/Float64.h>
#include <urdf/model.h>

#include "biovision_attractor/head_attractor.hpp"

using namespace biovision_attractor;

class HeadController
{
public:
  HeadController() : pnh_("~")
  {
    HeadAttractorParameters p;
    pnh_.param("alpha_attraction", p.alpha_attraction, p.alpha_attraction);
    pnh_.param("alpha_repulsion", p.alpha_repulsion, p.alpha_repulsion);
    pnh_.param("beta_attraction", p.beta_attraction, p.beta_attraction);
    pnh_.param("beta_repulsion", p.beta_repulsion, p.beta_repulsion);
    pnh_.param("epsilon_attraction", p.epsilon_attraction, p.epsilon_attraction);
    pnh_.param("epsilon_repulsion", p.epsilon_repulsion, p.epsilon_repulsion);
    pnh_.param("repulsion_step", p.repulsion_step, p.repulsion_step);
    pnh_.param("gain", p.gain, p.gain);
    pnh_.param("max_rate", p.max_rate, p.max_rate);
    pnh_.param("memory_decay", p.memory_decay, p.memory_decay);
    pnh_.param("min_saliency", p.min_saliency, p.min_saliency);
    pnh_.param("saccade_angle", p.saccade_angle, p.saccade_angle);
    pnh_.param("habituation_time", p.habituation_time, p.habituation_time);
    pnh_.param("recovery_time", p.recovery_time, p.recovery_time);
    pnh_.param("idle_timeout", p.idle_timeout, p.idle_timeout);
    pnh_.param("look_ahead_period", p.look_ahead_period, p.look_ahead_period);
    pnh_.param("look_ahead_duration", p.look_ahead_duration, p.look_ahead_duration);
    pnh_.param("min_region_area", min_area_, 200.0);
    pnh_.param("control_rate", control_rate_, 10.0);
    pnh_.param("joint_state_timeout", joint_timeout_, 0.5);
    pnh_.param("tilt", p.default_tilt, p.default_tilt);
    pnh_.param("tilt_dynamics", p.tilt_dynamics, p.tilt_dynamics);
    pnh_.param("horizontal_fov", half_fov_, 0.7505);
    half_fov_ /= 2;
    std::string mode;
    pnh_.param<std::string>("mode", mode, "explore");
    // Never command beyond the robot's limits: take them from the description when there is one.
    urdf::Model model;
    if (model.initParam("robot_description"))
    {
      if (auto j = model.getJoint("head_pan_joint"); j && j->limits)
      {
        p.pan_lower = j->limits->lower;
        p.pan_upper = j->limits->upper;
      }
      if (auto j = model.getJoint("head_tilt_joint"); j && j->limits)
      {
        p.tilt_lower = j->limits->lower;
        p.tilt_upper = j->limits->upper;
        p.default_tilt = std::clamp(p.default_tilt, p.tilt_lower, p.tilt_upper);
      }
    }
    attractor_ = std::make_unique<HeadAttractor>(p);  // throws on bad parameters: fatal at start-up
    HeadAttractor::Behaviour b;
    if (!HeadAttractor::parseBehaviour(mode, b))
      throw std::invalid_argument("~mode '" + mode + "' is not explore, track, look_ahead or hold");
    attractor_->setBehaviour(b);

    pan_pub_ = nh_.advertise<std_msgs::Float64>("head_pan_joint/command", 10);
    tilt_pub_ = nh_.advertise<std_msgs::Float64>("head_tilt_joint/command", 10);
    state_pub_ = nh_.advertise<biovision_msgs::AttractorState>("attractor/head", 10);
    regions_sub_ = nh_.subscribe("saliency/regions", 5, &HeadController::onRegions, this);
    joints_sub_ = nh_.subscribe("joint_states", 20, &HeadController::onJoints, this);
    info_sub_ = nh_.subscribe("camera_info", 1, &HeadController::onInfo, this);
    mode_srv_ = nh_.advertiseService("head/set_mode", &HeadController::onSetMode, this);
    timer_ = nh_.createTimer(ros::Duration(1.0 / control_rate_), &HeadController::step, this);
  }

private:
  void onRegions(const biovision_msgs::SalientRegionArrayConstPtr& m)
  {
    std::lock_guard<std::mutex> lock(mutex_);
    regions_.clear();
    for (const auto& r : m->regions)
      if (r.area >= min_area_)
        regions_.push_back({r.pan, r.tilt, r.peak_saliency, static_cast<double>(r.area)});
    latest_regions_ = m;
  }

  void onJoints(const sensor_msgs::JointStateConstPtr& m)
  {
    std::lock_guard<std::mutex> lock(mutex_);
    for (size_t i = 0; i < m->name.size() && i < m->position.size(); ++i)
    {
      if (!std::isfinite(m->position[i]))
        continue;
      if (m->name[i] == "head_pan_joint")
      {
        pan_ = m->position[i];
        joints_stamp_ = ros::Time::now();
      }
      else if (m->name[i] == "head_tilt_joint")
        tilt_ = m->position[i];
    }
  }

  void onInfo(const sensor_msgs::CameraInfoConstPtr& m)
  {
    if (m->P[0] > 0 && m->width > 0)
    {
      std::lock_guard<std::mutex> lock(mutex_);
      half_fov_ = std::atan(0.5 * m->width / m->P[0]);
    }
  }

  bool onSetMode(biovision_msgs::SetHeadMode::Request& req, biovision_msgs::SetHeadMode::Response& res)
  {
    std::lock_guard<std::mutex> lock(mutex_);
    HeadAttractor::Behaviour b;
    if (!HeadAttractor::parseBehaviour(req.mode, b))
    {
      res.success = false;
      res.message = "unknown mode '" + req.mode + "' (explore, track, look_ahead, hold)";
      return true;
    }
    double angle = 0.0;
    if (b == HeadAttractor::Behaviour::kTrack)
    {
      // "region:<rank>" tracks the direction of that salient region; labels need recognition.
      unsigned rank = 0;
      if (req.target.rfind("region:", 0) != 0 || !(std::istringstream(req.target.substr(7)) >> rank) ||
          !latest_regions_ || rank >= latest_regions_->regions.size())
      {
        res.success = false;
        res.message = "track needs target 'region:<rank>' of a current salient region";
        return true;
      }
      angle = latest_regions_->regions[rank].pan;
    }
    attractor_->setBehaviour(b, angle);
    res.success = true;
    res.message = std::string("head mode ") + HeadAttractor::name(b);
    return true;
  }

  void step(const ros::TimerEvent& e)
  {
    std::lock_guard<std::mutex> lock(mutex_);
    const ros::Time now = ros::Time::now();
    if (joints_stamp_.isZero() || (now - joints_stamp_).toSec() > joint_timeout_)
    {
      // Without knowing where the head is, do not move it.
      ROS_WARN_THROTTLE(5.0, "head_controller: no joint_states for head_pan_joint in %.1f s; holding", joint_timeout_);
      return;
    }
    const double dt = e.last_real.isZero() ? 1.0 / control_rate_ : (e.current_real - e.last_real).toSec();
    const auto out = attractor_->update(regions_, pan_, now.toSec(), dt, half_fov_, tilt_);
    regions_.clear();  // each frame's regions are used once
    std_msgs::Float64 pan_cmd, tilt_cmd;
    pan_cmd.data = out.command;
    tilt_cmd.data = out.tilt_command;
    pan_pub_.publish(pan_cmd);
    tilt_pub_.publish(tilt_cmd);
    biovision_msgs::AttractorState s;
    s.header.stamp = now;
    s.controller = "head_pan";
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

  ros::NodeHandle nh_, pnh_;
  ros::Publisher pan_pub_, tilt_pub_, state_pub_;
  ros::Subscriber regions_sub_, joints_sub_, info_sub_;
  ros::ServiceServer mode_srv_;
  ros::Timer timer_;
  std::mutex mutex_;
  std::unique_ptr<HeadAttractor> attractor_;
  std::vector<SeenRegion> regions_;
  biovision_msgs::SalientRegionArrayConstPtr latest_regions_;
  double pan_ = 0.0, tilt_ = 0.3, min_area_ = 200.0, control_rate_ = 10.0, joint_timeout_ = 0.5, half_fov_ = 0.375;
  ros::Time joints_stamp_;
};

int main(int argc, char** argv)
{
  ros::init(argc, argv, "head_controller");
  try
  {
    HeadController controller;
    ros::spin();
  }
  catch (const std::exception& e)
  {
    ROS_FATAL("head_controller: %s", e.what());
    return 1;
  }
  return 0;
}
