#include "phantomx_driver/ros/phantomx_driver_nodelet.hpp"

#include <chrono>

#include <pluginlib/class_list_macros.hpp>
#include <sensor_msgs/JointState.h>
#include <urdf/model.h>

#include "biovision_common/steady_seconds.hpp"
#include "biovision_ros_common/typed_parameter.hpp"

namespace phantomx_driver
{
PhantomXDriverNodelet::~PhantomXDriverNodelet()
{
  running_ = false;
  if (thread_.joinable())
    thread_.join();
}

void PhantomXDriverNodelet::onInit()
{
  ros::NodeHandle& nh = getNodeHandle();
  ros::NodeHandle& pnh = getPrivateNodeHandle();
  try
  {
    // A value of the wrong type is refused, not replaced by the default (a driver told `_port:=123` opened
    // /dev/ttyUSB0).
    visitParameters(parameters_, [&](const std::string& name, auto& value) {
      biovision_ros_common::readTypedParameter(pnh, name, value);
    });
    bus_ = std::make_unique<PanTiltBus>(parameters_);
    // Never command beyond the robot's limits: the URDF's, narrowed by the servo's range.
    urdf::Model model;
    if (model.initParam("robot_description"))
    {
      for (size_t i = 0; i < 2; ++i)
      {
        const std::string& name = bus_->joint(i).name;
        if (auto j = model.getJoint(name); j && j->limits)
          bus_->setLimits(i, j->limits->lower, j->limits->upper);
        else
          NODELET_WARN("robot_description has no limits for %s: [%.3f, %.3f] rad from the parameters", name.c_str(),
                       bus_->joint(i).lower, bus_->joint(i).upper);
      }
    }
    else
      NODELET_WARN("no robot_description: joint limits from the parameters");
  }
  catch (const std::invalid_argument& e)
  {
    NODELET_FATAL("%s", e.what());
    throw;
  }
  joint_pub_ = nh.advertise<sensor_msgs::JointState>("joint_states", 10);
  biovision_ros_common::DiagnosticsOptions options;
  options.status_name = "PhantomX head";
  options.rate_topic = "joint_states";
  options.default_max_rate = 2.0 * parameters_.poll_rate;
  options.working_message = "both servos answer";
  options.details = [this](diagnostic_updater::DiagnosticStatusWrapper& s) {
    std::lock_guard<std::mutex> lock(mutex_);
    std::string problem;
    if (!port_open_)
      problem = "port down: " + last_error_;
    for (size_t i = 0; i < 2 && problem.empty(); ++i)
      if (states_[i].torque_off)
        problem = bus_->joint(i).name + " overloaded, torque off (restart the driver after fixing the cause)";
      else if (!states_[i].alive)
        problem = bus_->joint(i).name + " servo lost: " + last_error_;
    if (!problem.empty())
      s.summary(diagnostic_msgs::DiagnosticStatus::ERROR, problem);
    s.add("port", parameters_.port);
    s.add("rejected packets", rejected_);
    for (size_t i = 0; i < 2; ++i)
    {
      const std::string n = bus_->joint(i).name + " ";
      s.add(n + "id", static_cast<int>(bus_->joint(i).id));
      s.add(n + "answers", states_[i].alive);
      s.add(n + "position [rad]", states_[i].position);
      s.add(n + "limits [rad]", std::to_string(bus_->joint(i).lower) + " " + std::to_string(bus_->joint(i).upper));
      s.add(n + "error bits", describeErrorBits(states_[i].error));
      s.add(n + "voltage [V]", states_[i].voltage);
      s.add(n + "temperature [C]", states_[i].temperature);
      s.add(n + "load", states_[i].load);
      s.add(n + "torque off (overload)", states_[i].torque_off);
      s.add(n + "unanswered polls", states_[i].misses);
      s.add(n + "goals written again (read back differed)", states_[i].goal_rewrites);
    }
    s.add("last error", last_error_);
  };
  diagnostics_.init(nh, pnh, getName(), options);
  command_subs_[PanTiltBus::kPan] = nh.subscribe<std_msgs::Float64>(parameters_.pan_joint + "/command", 10,
                                                                    [this](const std_msgs::Float64ConstPtr& m) {
                                                                      onCommand(PanTiltBus::kPan, m);
                                                                    });
  command_subs_[PanTiltBus::kTilt] = nh.subscribe<std_msgs::Float64>(parameters_.tilt_joint + "/command", 10,
                                                                     [this](const std_msgs::Float64ConstPtr& m) {
                                                                       onCommand(PanTiltBus::kTilt, m);
                                                                     });
  running_ = true;
  thread_ = std::thread([this] { run(); });
  NODELET_INFO("PhantomX driver on %s at %d bit/s: %s id %d [%.3f, %.3f] rad, %s id %d [%.3f, %.3f] rad",
               parameters_.port.c_str(), parameters_.baud, bus_->joint(0).name.c_str(), bus_->joint(0).id,
               bus_->joint(0).lower, bus_->joint(0).upper, bus_->joint(1).name.c_str(), bus_->joint(1).id,
               bus_->joint(1).lower, bus_->joint(1).upper);
}

void PhantomXDriverNodelet::onCommand(size_t index, const std_msgs::Float64ConstPtr& msg)
{
  if (!std::isfinite(msg->data))
  {
    diagnostics_.health().reportError(getName(), bus_->joint(index).name + "/command is not finite: ignored");
    return;
  }
  const Ax12Joint& j = bus_->joint(index);
  if (!j.withinLimits(msg->data))
    NODELET_WARN_THROTTLE(5.0, "%s/command %.3f rad outside [%.3f, %.3f]: clamped", j.name.c_str(), msg->data, j.lower,
                          j.upper);
  std::lock_guard<std::mutex> lock(mutex_);
  goals_[index] = msg->data;
  goal_new_[index] = true;
}

void PhantomXDriverNodelet::run()
{
  const double period = 1.0 / parameters_.poll_rate;
  double next = biovision_common::steadySeconds();
  std::array<bool, 2> alive{true, true}, torque_off{false, false};
  bool port_open = true;
  unsigned long rejected = 0;
  std::string previous_error;
  while (running_ && ros::ok())
  {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      for (size_t i = 0; i < 2; ++i)
        if (goal_new_[i])
        {
          bus_->setGoal(i, goals_[i]);
          goal_new_[i] = false;
        }
    }
    bus_->step(biovision_common::steadySeconds());
    sensor_msgs::JointState js;
    js.header.stamp = ros::Time::now();
    for (size_t i = 0; i < 2; ++i)
    {
      const ServoState& s = bus_->servo(i);
      if (!s.alive)
        continue;
      js.name.push_back(bus_->joint(i).name);
      js.position.push_back(s.position);
      js.velocity.push_back(s.velocity);
      js.effort.push_back(s.load * 1.5);  // fraction of the AX-12A's 1.5 N·m stall torque
    }
    if (!js.name.empty())
    {
      joint_pub_.publish(js);
      diagnostics_.tick();
    }
    // Report what changed for the worse.
    const std::string error = bus_->lastError();
    bool reported = false;
    for (size_t i = 0; i < 2; ++i)
    {
      const ServoState& s = bus_->servo(i);
      if ((alive[i] && !s.alive && bus_->portOpen()) || (!torque_off[i] && s.torque_off))
      {
        diagnostics_.health().reportError(getName(), error);
        reported = true;
      }
      alive[i] = s.alive;
      torque_off[i] = s.torque_off;
    }
    if (port_open && !bus_->portOpen())
    {
      diagnostics_.health().reportError(getName(), "PhantomX port down: " + error);
      reported = true;
    }
    if (!reported && !error.empty() && error != previous_error)  // e.g. a reply with a position beyond 0-1023
      diagnostics_.health().reportError(getName(), error);
    previous_error = error;
    port_open = bus_->portOpen();
    if (bus_->rejectedPackets() != rejected)
      diagnostics_.health().reportError(getName(), std::to_string(bus_->rejectedPackets()) +
                                                       " status packets rejected (bad checksum)");
    rejected = bus_->rejectedPackets();
    {
      std::lock_guard<std::mutex> lock(mutex_);
      states_ = {bus_->servo(0), bus_->servo(1)};
      port_open_ = bus_->portOpen();
      last_error_ = error;
      rejected_ = rejected;
    }
    next += period;
    const double wait = next - biovision_common::steadySeconds();
    if (wait > 0.0)
      std::this_thread::sleep_for(std::chrono::duration<double>(wait));
    else
      next = biovision_common::steadySeconds();
  }
}
}  // namespace phantomx_driver

PLUGINLIB_EXPORT_CLASS(phantomx_driver::PhantomXDriverNodelet, nodelet::Nodelet)
