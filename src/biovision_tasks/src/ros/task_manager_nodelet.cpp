#include "biovision_tasks/ros/task_manager_nodelet.hpp"

#include <cmath>
#include <cstdio>

#include <geometry_msgs/PoseStamped.h>
#include <std_msgs/Float64.h>
#include <pluginlib/class_list_macros.hpp>
#include <tf2/LinearMath/Quaternion.h>
#include <tf2/LinearMath/Transform.h>

#include "biovision_tasks/ros/task_message_converter.hpp"

namespace biovision_tasks
{
namespace
{
constexpr size_t kMaxSightings = 200;  // bounded memory whatever the objects rate

tf2::Transform toTf(const geometry_msgs::Transform& t)
{
  return tf2::Transform(tf2::Quaternion(t.rotation.x, t.rotation.y, t.rotation.z, t.rotation.w),
                        tf2::Vector3(t.translation.x, t.translation.y, t.translation.z));
}

// Base controller behaviours that mean "no progress" or "stopped itself".
bool isTrapped(const std::string& b)
{
  return b == "trapped";
}
bool isFault(const std::string& b)
{
  return b == "watchdog" || b == "bumper" || b == "stall" || b == "fault";
}

std::string seconds(double s)
{
  char text[32];
  std::snprintf(text, sizeof text, "%.1f s", s);
  return text;
}
}  // namespace

TaskManagerNodelet::~TaskManagerNodelet()
{
  if (action_)
    action_->shutdown();
}

TaskParameters TaskManagerNodelet::parametersFromConfig(const TaskManagerConfig& config, TaskParameters base)
{
  dynamic_reconfigure::Config message;
  config.__toMessage__(message);
  for (const auto& d : message.doubles)
    for (const auto& [name, field] : TaskParameters::namedDoubles())
      if (name == d.name)
        base.*field = d.value;
  for (const auto& i : message.ints)
    for (const auto& [name, field] : TaskParameters::namedInts())
      if (name == i.name)
        base.*field = i.value;
  return base;
}

void TaskManagerNodelet::onInit()
{
  ros::NodeHandle& nh = getNodeHandle();
  ros::NodeHandle& pnh = getPrivateNodeHandle();
  map_frame_ = pnh.param<std::string>("map_frame", "map");
  base_frame_ = pnh.param<std::string>("base_frame", "base_link");
  camera_frame_ = pnh.param<std::string>("camera_frame", "stereo_left_optical");
  pose_timeout_ = pnh.param("pose_timeout", 1.0);
  seen_hold_ = pnh.param("seen_hold", 1.0);
  goal_refresh_ = pnh.param("goal_refresh", 10.0);
  const double rate = pnh.param("rate", 5.0);
  const double service_timeout = pnh.param("service_timeout", 2.0);
  if (!(rate > 0) || !(pose_timeout_ > 0) || !(seen_hold_ >= 0) || !(goal_refresh_ > 0) || !(service_timeout > 0))
    throw std::invalid_argument(
        "task_manager: ~rate, ~pose_timeout, ~goal_refresh and ~service_timeout must be > 0, ~seen_hold >= 0");
  manager_ = std::make_unique<TaskManager>(parameters_);
  tf_listener_ = std::make_unique<tf2_ros::TransformListener>(tf_buffer_);

  goal_pub_ = nh.advertise<geometry_msgs::PoseStamped>("goal", 1);
  bearing_pub_ = nh.advertise<std_msgs::Float64>("goal_bearing", 1);
  status_pub_ = nh.advertise<biovision_msgs::TaskStatus>("tasks/status", 5);
  objects_sub_ = nh.subscribe("objects", 5, &TaskManagerNodelet::onObjects, this);
  ltm_sub_ = nh.subscribe("memory/ltm", 1, &TaskManagerNodelet::onLtm, this);
  items_sub_ = nh.subscribe("memory/ltm_items", 1, &TaskManagerNodelet::onLtmItems, this);
  base_sub_ = nh.subscribe("attractor/base", 5, &TaskManagerNodelet::onBaseState, this);
  gesture_action_sub_ = nh.subscribe("hri/action", 5, &TaskManagerNodelet::onGestureAction, this);
  head_mode_client_ = std::make_unique<biovision_ros_common::AsyncServiceClient<biovision_msgs::SetHeadMode>>(
      nh, "head/set_mode", service_timeout);
  base_stop_client_ = std::make_unique<biovision_ros_common::AsyncServiceClient<std_srvs::Trigger>>(nh, "base/stop",
                                                                                                    service_timeout);
  greet_client_ = std::make_unique<biovision_ros_common::AsyncServiceClient<std_srvs::Trigger>>(nh, "hri/greet",
                                                                                                service_timeout);
  stop_greet_client_ = std::make_unique<biovision_ros_common::AsyncServiceClient<std_srvs::Trigger>>(
      nh, "hri/stop_greet", service_timeout);
  cancel_srv_ = nh.advertiseService("tasks/cancel", &TaskManagerNodelet::onCancel, this);

  biovision_ros_common::DiagnosticsOptions d;
  d.status_name = "Task manager";
  d.rate_topic = "tasks/status";
  d.default_max_rate = 2 * rate;
  d.working_message = "cycling";
  d.details = [this](diagnostic_updater::DiagnosticStatusWrapper& s) { details(s); };
  diagnostics_.init(nh, pnh, getName(), d);
  diagnostics_.clockJumps().onJumpBack([this] { onTimeJumpBack(); });

  reconfigure_server_ = std::make_unique<dynamic_reconfigure::Server<TaskManagerConfig>>(reconfigure_mutex_, pnh);
  reconfigure_server_->setCallback([this](TaskManagerConfig& c, uint32_t level) { reconfigure(c, level); });

  action_ = std::make_unique<actionlib::SimpleActionServer<biovision_msgs::ExecuteTaskAction>>(nh, "tasks/execute",
                                                                                               false);
  action_->registerGoalCallback([this] { onGoal(); });
  action_->registerPreemptCallback([this] { onPreempt(); });
  action_->start();

  const std::string mission = pnh.param<std::string>("mission", "");
  if (!mission.empty())
  {
    try
    {
      for (const auto& t : TaskSpec::loadFile(mission))
        manager_->add(t);
      NODELET_INFO("task_manager: mission %s loaded", mission.c_str());
    }
    catch (const std::invalid_argument& e)
    {
      diagnostics_.health().reportError(getName(), std::string("mission refused: ") + e.what());
    }
  }
  timer_ = nh.createTimer(ros::Duration(1.0 / rate), &TaskManagerNodelet::step, this);
}

void TaskManagerNodelet::reconfigure(TaskManagerConfig& config, uint32_t)
{
  const TaskParameters p = parametersFromConfig(config, TaskParameters());
  try
  {
    p.validate();
  }
  catch (const std::invalid_argument& e)
  {
    diagnostics_.health().reportError(getName(), std::string("reconfigure rejected: ") + e.what());
    config = applied_config_;
    return;
  }
  std::lock_guard<std::mutex> lock(mutex_);
  parameters_ = p;
  applied_config_ = config;
  // The manager builds new tasks with the new set; running tasks keep theirs. Rebuild only when idle.
  if (manager_ && manager_->idle())
    manager_ = std::make_unique<TaskManager>(parameters_);
}

void TaskManagerNodelet::onObjects(const biovision_msgs::RecognizedObjectArrayConstPtr& msg)
{
  diagnostics_.clockJumps().observe(ros::Time::now());  // the clock: stamps lag by the recognition latency
  geometry_msgs::TransformStamped t;
  try
  {
    t = tf_buffer_.lookupTransform(map_frame_, msg->header.frame_id, msg->header.stamp,
                                   ros::Duration(0.25));  // map -> odom comes at 10 Hz
  }
  catch (const tf2::TransformException& e)
  {
    NODELET_WARN_THROTTLE(5.0, "task_manager: objects not placed in %s: %s", map_frame_.c_str(), e.what());
    return;
  }
  const tf2::Transform to_map = toTf(t.transform);
  std::lock_guard<std::mutex> lock(mutex_);
  for (const auto& o : msg->objects)
  {
    if (!o.has_position || !std::isfinite(o.position.x) || !std::isfinite(o.position.y) || !std::isfinite(o.position.z))
      continue;
    const tf2::Vector3 p = to_map * tf2::Vector3(o.position.x, o.position.y, o.position.z);
    seen_.push_back({o.label, p.x(), p.y(), o.score, msg->header.stamp.toSec()});
  }
  while (seen_.size() > kMaxSightings)
    seen_.pop_front();
}

void TaskManagerNodelet::onLtm(const nav_msgs::OccupancyGridConstPtr& msg)
{
  try
  {
    OccupancyMap m = TaskMessageConverter::fromMessage(*msg);
    std::lock_guard<std::mutex> lock(mutex_);
    map_ = std::move(m);
  }
  catch (const std::invalid_argument& e)
  {
    diagnostics_.health().reportError(getName(), std::string("memory/ltm refused: ") + e.what());
  }
}

void TaskManagerNodelet::onLtmItems(const biovision_msgs::LtmItemArrayConstPtr& msg)
{
  auto objects = TaskMessageConverter::rememberedObjects(*msg);
  std::lock_guard<std::mutex> lock(mutex_);
  remembered_ = std::move(objects);
}

void TaskManagerNodelet::onBaseState(const biovision_msgs::AttractorStateConstPtr& msg)
{
  std::lock_guard<std::mutex> lock(mutex_);
  base_behaviour_ = msg->behaviour;
  base_state_time_ = msg->header.stamp.isZero() ? ros::Time::now() : msg->header.stamp;
}

void TaskManagerNodelet::onGestureAction(const std_msgs::StringConstPtr& msg)
{
  std::lock_guard<std::mutex> lock(mutex_);
  gesture_action_ = msg->data;
  gesture_action_time_ = ros::Time::now();
}

void TaskManagerNodelet::onGoal()
{
  const auto goal = action_->acceptNewGoal();
  std::vector<TaskSpec> specs;
  try
  {
    if (goal->task == "mission")
    {
      if (goal->arguments.empty())
        throw std::invalid_argument("task 'mission' needs the mission file as its argument");
      specs = TaskSpec::loadFile(goal->arguments[0]);
    }
    else
    {
      std::string line = goal->task;
      for (const auto& a : goal->arguments)
        line += " " + a;
      specs = TaskSpec::parseText(line);
    }
  }
  catch (const std::invalid_argument& e)
  {
    biovision_msgs::ExecuteTaskResult r;
    r.success = false;
    r.message = e.what();
    action_->setAborted(r, r.message);
    return;
  }
  std::lock_guard<std::mutex> lock(mutex_);
  // A new goal replaces the previous goal's tasks (SimpleActionServer semantics).
  for (int id : goal_tasks_)
    manager_->cancel(id, "replaced by a new goal");
  goal_tasks_.clear();
  for (const auto& s : specs)
    goal_tasks_.insert(manager_->add(s));
  goal_start_ = ros::Time::now();
}

void TaskManagerNodelet::onPreempt()
{
  std::lock_guard<std::mutex> lock(mutex_);
  for (int id : goal_tasks_)
    manager_->cancel(id, "preempted");
  goal_tasks_.clear();
  biovision_msgs::ExecuteTaskResult r;
  r.success = false;
  r.message = "preempted";
  r.duration = static_cast<float>((ros::Time::now() - goal_start_).toSec());
  action_->setPreempted(r, r.message);
}

bool TaskManagerNodelet::onCancel(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res)
{
  std::lock_guard<std::mutex> lock(mutex_);
  const bool any = !manager_->idle();
  manager_->cancelAll("cancelled by tasks/cancel");
  res.success = true;
  res.message = any ? "cancelled" : "nothing to cancel";
  return true;
}

void TaskManagerNodelet::onTimeJumpBack()
{
  std::lock_guard<std::mutex> lock(mutex_);
  manager_->reset();
  seen_.clear();
  if (action_ && action_->isActive())
  {
    biovision_msgs::ExecuteTaskResult r;
    r.success = false;
    r.message = "ROS time jumped back: tasks cancelled";
    action_->setAborted(r, r.message);
  }
  goal_tasks_.clear();
  head_mode_.clear();
  gesture_action_.clear();
  gesture_action_time_ = ros::Time();
}

Percept TaskManagerNodelet::perceive(const ros::Time& now)
{
  Percept p;
  p.time = now.toSec();
  try
  {
    const auto t = tf_buffer_.lookupTransform(map_frame_, base_frame_, ros::Time(0));
    // A static chain (a zero stamp) is always current; a dynamic one must be recent.
    if (t.header.stamp.isZero() || (now - t.header.stamp).toSec() <= pose_timeout_)
    {
      const auto& q = t.transform.rotation;
      p.pose = {t.transform.translation.x, t.transform.translation.y,
                std::atan2(2 * (q.w * q.z + q.x * q.y), 1 - 2 * (q.y * q.y + q.z * q.z))};
      p.pose_valid = std::isfinite(p.pose.x) && std::isfinite(p.pose.y) && std::isfinite(p.pose.yaw);
    }
  }
  catch (const tf2::TransformException&)
  {
  }
  try
  {
    const auto t = tf_buffer_.lookupTransform(map_frame_, camera_frame_, ros::Time(0));
    if (t.header.stamp.isZero() || (now - t.header.stamp).toSec() <= pose_timeout_)
    {
      // The optical z axis (the viewing direction) in map: the third column of the rotation.
      const auto& q = t.transform.rotation;
      const double zx = 2 * (q.x * q.z + q.w * q.y), zy = 2 * (q.y * q.z - q.w * q.x);
      if (std::hypot(zx, zy) > 1e-3)
        p.view_yaw = std::atan2(zy, zx);
    }
  }
  catch (const tf2::TransformException&)
  {
  }
  for (const auto& o : seen_)
    if (p.time - o.last_seen <= seen_hold_)
      p.seen.push_back(o);
  p.remembered = remembered_;
  p.map = map_;
  const bool fresh = (now - base_state_time_).toSec() <= 2.0;
  p.base_trapped = fresh && isTrapped(base_behaviour_);
  p.base_fault = fresh && isFault(base_behaviour_);
  if (!gesture_action_.empty())
  {
    p.gesture_action = gesture_action_;
    p.gesture_action_time = gesture_action_time_.toSec();
  }
  return p;
}

void TaskManagerNodelet::collectServiceAnswers()
{
  const ros::WallTime now = ros::WallTime::now();
  if (const auto r = head_mode_client_->take())
  {
    head_mode_answer_ = head_mode_requested_ + ": ";
    if (r->answered && r->response.success)
    {
      head_mode_ = head_mode_requested_;
      head_mode_answer_ += "accepted";
      head_mode_failed_ = false;
    }
    else
    {
      // Unknown now: a call given up on may still take effect in the head controller, so the wanted mode
      // is sent again (after kServiceRetry) even when it is the one last accepted.
      head_mode_.clear();
      head_mode_failed_ = true;
      head_mode_retry_at_ = now + ros::WallDuration(kServiceRetry);
      head_mode_answer_ += (r->timed_out  ? "no answer within " + seconds(head_mode_client_->timeout())
                            : r->answered ? "refused: " + r->response.message
                                          : "no head controller");
      NODELET_WARN_THROTTLE(5.0, "task_manager: head/set_mode %s", head_mode_answer_.c_str());
    }
    head_mode_requested_.clear();
  }
  if (const auto r = base_stop_client_->take())
  {
    const bool stopped = r->answered && r->response.success;
    // An answer to a stop the tasks have since left behind (a goal or turn sent after the call began)
    // stops nothing now: the next stop calls again.
    stopped_ = stopped && !moved_since_stop_call_ && sent_.base == MotorCommand::Base::Stop;
    base_stop_failed_ = !stopped;
    if (!stopped)
      base_stop_retry_at_ = now + ros::WallDuration(kServiceRetry);
    base_stop_answer_ = stopped        ? "answered"
                        : r->answered  ? "refused: " + r->response.message
                        : r->timed_out ? "no answer within " + seconds(base_stop_client_->timeout())
                                       : "no base controller";
    if (!stopped)
      NODELET_WARN_THROTTLE(5.0, "task_manager: base/stop %s", base_stop_answer_.c_str());
  }
  for (auto* client : {greet_client_.get(), stop_greet_client_.get()})
    if (const auto r = client->take())
    {
      const bool ok = r->answered && r->response.success;
      greet_answer_ = std::string(client == greet_client_.get() ? "hri/greet " : "hri/stop_greet ") +
                      (ok             ? "answered: " + r->response.message
                       : r->answered  ? "refused: " + r->response.message
                       : r->timed_out ? "no answer within " + seconds(client->timeout())
                                      : "no HRI node");
      if (!ok && client == greet_client_.get())
      {
        greeting_ = false;  // call again (the greet task is still waiting), after kServiceRetry
        greet_retry_at_ = now + ros::WallDuration(kServiceRetry);
        NODELET_WARN_THROTTLE(5.0, "task_manager: %s", greet_answer_.c_str());
      }
    }
}

void TaskManagerNodelet::command(const MotorCommand& c, const Percept& p, const ros::Time& now)
{
  // Services are called off this cycle and answered later (a hung server must not stop the tasks);
  // a mode or stop that was not answered is asked for again, at most every kServiceRetry.
  collectServiceAnswers();
  const ros::WallTime wall = ros::WallTime::now();
  if (!c.head_mode.empty() && c.head_mode != head_mode_ && head_mode_requested_.empty() &&
      !(head_mode_failed_ && wall < head_mode_retry_at_))
  {
    biovision_msgs::SetHeadMode::Request request;
    request.mode = c.head_mode;
    request.target = c.head_target;
    if (head_mode_client_->start(request))
      head_mode_requested_ = c.head_mode;
  }
  if (c.greet && !greeting_ && wall >= greet_retry_at_ && greet_client_->start(std_srvs::Trigger::Request()))
    greeting_ = true;
  else if (!c.greet && greeting_)
  {
    stop_greet_client_->start(std_srvs::Trigger::Request());  // best effort: the HRI behaviour times out anyway
    greeting_ = false;
  }
  if (c.base == MotorCommand::Base::Stop)
  {
    if (!stopped_ && !base_stop_client_->busy() && !(base_stop_failed_ && wall < base_stop_retry_at_) &&
        base_stop_client_->start(std_srvs::Trigger::Request()))
      moved_since_stop_call_ = false;
    sent_ = c;
    return;
  }
  const bool same_kind = !stopped_ && sent_.base == c.base;
  const bool stale = (now - sent_time_).toSec() >= goal_refresh_;
  if (c.base == MotorCommand::Base::Goal)
  {
    if (same_kind && !stale && std::hypot(c.goal_x - sent_.goal_x, c.goal_y - sent_.goal_y) <= 0.05)
      return;
    geometry_msgs::PoseStamped goal;
    goal.header.stamp = now;
    goal.header.frame_id = map_frame_;
    goal.pose.position.x = c.goal_x;
    goal.pose.position.y = c.goal_y;
    const double yaw = std::atan2(c.goal_y - p.pose.y, c.goal_x - p.pose.x);
    goal.pose.orientation.z = std::sin(yaw / 2);
    goal.pose.orientation.w = std::cos(yaw / 2);
    goal_pub_.publish(goal);
  }
  else  // Heading: a bearing relative to the robot's heading now
  {
    if (same_kind && !stale && std::abs(std::remainder(c.heading - sent_.heading, 2 * M_PI)) <= 0.05)
      return;
    std_msgs::Float64 bearing;
    bearing.data = std::remainder(c.heading - p.pose.yaw, 2 * M_PI);
    bearing_pub_.publish(bearing);
  }
  stopped_ = false;
  moved_since_stop_call_ = true;
  sent_ = c;
  sent_time_ = now;
}

void TaskManagerNodelet::finishGoal()
{
  if (!action_->isActive() || goal_tasks_.empty())
    return;
  bool all_done = true, all_ok = true;
  std::string message;
  for (int id : goal_tasks_)
  {
    bool done = false;
    for (const auto& f : manager_->finished())
      if (f.id == id)
      {
        done = true;
        all_ok = all_ok && f.state == TaskState::Succeeded;
        message += (message.empty() ? "" : "; ") + f.name + ": " + toString(f.state) +
                   (f.reason.empty() ? "" : " (" + f.reason + ")");
      }
    all_done = all_done && done;
  }
  if (!all_done)
    return;
  biovision_msgs::ExecuteTaskResult r;
  r.success = all_ok;
  r.message = message;
  r.duration = static_cast<float>((ros::Time::now() - goal_start_).toSec());
  goal_tasks_.clear();
  if (all_ok)
    action_->setSucceeded(r, message);
  else
    action_->setAborted(r, message);
}

void TaskManagerNodelet::step(const ros::TimerEvent&)
{
  const ros::Time now = ros::Time::now();
  if (diagnostics_.clockJumps().observe(now))
    return;
  std::lock_guard<std::mutex> lock(mutex_);
  const Percept p = perceive(now);
  const MotorCommand c = manager_->step(p);
  command(c, p, now);
  biovision_msgs::TaskStatus status = TaskMessageConverter::toMessage(manager_->status());
  status.header.stamp = now;
  status_pub_.publish(status);
  diagnostics_.tick();
  if (action_->isActive())
  {
    biovision_msgs::ExecuteTaskFeedback f;
    f.status = status;
    action_->publishFeedback(f);
    finishGoal();
  }
}

void TaskManagerNodelet::details(diagnostic_updater::DiagnosticStatusWrapper& s)
{
  std::lock_guard<std::mutex> lock(mutex_);
  const auto st = manager_->status();
  s.add("task", st.macro_task);
  s.add("micro-task", st.micro_task);
  s.add("mode", st.mode);
  s.add("state", toString(st.state));
  s.add("message", st.message);
  s.add("finished tasks", manager_->finished().size());
  s.add("home known", manager_->record().home_known);
  s.add("path length [m]", manager_->record().path_length);
  s.add("LTM cells", map_.empty() ? 0 : map_.cells().total());
  s.add("hri", greet_answer_.empty() ? "not called" : greet_answer_);
  s.add("last gesture action", gesture_action_.empty() ? "none" : gesture_action_);
  s.add("head mode", head_mode_);
  s.add("head/set_mode", head_mode_answer_.empty() ? "not called" : head_mode_answer_);
  s.add("base/stop", base_stop_answer_.empty() ? "not called" : base_stop_answer_);
  s.add("service calls left unanswered", head_mode_client_->abandoned() + base_stop_client_->abandoned());
  if (head_mode_failed_)
    s.mergeSummary(diagnostic_msgs::DiagnosticStatus::WARN, "head/set_mode " + head_mode_answer_);
  if (base_stop_failed_)
    s.mergeSummary(diagnostic_msgs::DiagnosticStatus::WARN, "base/stop " + base_stop_answer_);
}
}  // namespace biovision_tasks

PLUGINLIB_EXPORT_CLASS(biovision_tasks::TaskManagerNodelet, nodelet::Nodelet)
