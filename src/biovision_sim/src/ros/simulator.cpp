#include "biovision_sim/ros/simulator.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include <cv_bridge/cv_bridge.h>
#include <geometry_msgs/PoseStamped.h>
#include <geometry_msgs/TransformStamped.h>
#include <geometry_msgs/Twist.h>
#include <nav_msgs/Odometry.h>
#include <opencv2/imgproc.hpp>
#include <rosgraph_msgs/Clock.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/JointState.h>
#include <std_msgs/Float64.h>
#include <std_msgs/String.h>
#include <stereo_msgs/DisparityImage.h>
#include <visualization_msgs/MarkerArray.h>

#include "biovision_sim/ros/camera_info.hpp"
#include "biovision_sim/ros/read_parameter.hpp"

namespace biovision_sim
{
namespace
{
urdf::Model loadRobotDescription()
{
  urdf::Model model;
  if (!model.initParam("robot_description"))
    throw std::runtime_error("no robot_description (load biovision_description's URDF first)");
  return model;
}

Eigen::Isometry3d toEigen(const urdf::Pose& p)
{
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translation() << p.position.x, p.position.y, p.position.z;
  t.linear() = Eigen::Quaterniond(p.rotation.w, p.rotation.x, p.rotation.y, p.rotation.z).toRotationMatrix();
  return t;
}

/// The chain root -> tip of the robot description (fixed and revolute joints only). Throws
/// std::runtime_error when tip is missing, not below root, or joined by another joint type.
KinematicChain chainFromUrdf(const urdf::Model& model, const std::string& root, const std::string& tip)
{
  std::vector<KinematicChain::Link> reversed;
  urdf::LinkConstSharedPtr link = model.getLink(tip);
  if (!link)
    throw std::runtime_error("robot_description has no link '" + tip + "'");
  while (link && link->name != root)
  {
    const urdf::JointConstSharedPtr j = link->parent_joint;
    if (!j)
      throw std::runtime_error("link '" + tip + "' is not below '" + root + "' in robot_description");
    KinematicChain::Link l;
    l.origin = toEigen(j->parent_to_joint_origin_transform);
    if (j->type == urdf::Joint::REVOLUTE || j->type == urdf::Joint::CONTINUOUS)
    {
      l.joint = j->name;
      l.axis = Eigen::Vector3d(j->axis.x, j->axis.y, j->axis.z);
    }
    else if (j->type != urdf::Joint::FIXED)
      throw std::runtime_error("joint '" + j->name + "' is neither fixed nor revolute");
    reversed.push_back(l);
    link = model.getLink(j->parent_link_name);
  }
  KinematicChain chain;
  for (auto it = reversed.rbegin(); it != reversed.rend(); ++it)
    chain.append(*it);
  return chain;
}

/// A servo within the URDF limits of `joint`. Throws std::runtime_error when the joint has none.
Servo servoFromUrdf(const urdf::Model& model, const std::string& joint, double max_speed)
{
  const auto j = model.getJoint(joint);
  if (!j || !j->limits)
    throw std::runtime_error("robot_description has no limited joint '" + joint + "'");
  return Servo(j->limits->lower, j->limits->upper, max_speed);
}

/// Distance between the optical centres at zero joint angles [m].
double baselineOf(const KinematicChain& left, const KinematicChain& right)
{
  return (left.evaluate({}, {}).inverse() * right.evaluate({}, {})).translation().norm();
}

geometry_msgs::TransformStamped toTransform(const Eigen::Isometry3d& t, const std::string& parent,
                                            const std::string& child, const ros::Time& stamp)
{
  geometry_msgs::TransformStamped m;
  m.header.stamp = stamp;
  m.header.frame_id = parent;
  m.child_frame_id = child;
  m.transform.translation.x = t.translation().x();
  m.transform.translation.y = t.translation().y();
  m.transform.translation.z = t.translation().z();
  const Eigen::Quaterniond q(t.linear());
  m.transform.rotation.x = q.x();
  m.transform.rotation.y = q.y();
  m.transform.rotation.z = q.z();
  m.transform.rotation.w = q.w();
  return m;
}

/// A marker in map for a labelled object, coloured like the first texel of its texture.
visualization_msgs::Marker objectMarker(const World& world, size_t index)
{
  const World::Object& o = world.objects()[index];
  visualization_msgs::Marker m;
  m.header.frame_id = "map";
  m.ns = o.label;
  m.id = static_cast<int>(index);
  m.type = o.shape == "cylinder" ? visualization_msgs::Marker::CYLINDER : visualization_msgs::Marker::CUBE;
  m.pose.position.x = o.position.x();
  m.pose.position.y = o.position.y();
  m.pose.position.z = o.position.z();
  m.pose.orientation.z = std::sin(o.yaw / 2);
  m.pose.orientation.w = std::cos(o.yaw / 2);
  m.scale.x = o.size.x();
  m.scale.y = o.size.y();
  m.scale.z = o.size.z();
  const cv::Vec3f c = world.textures()[o.texture]->image().at<cv::Vec3f>(0, 0);
  m.color.b = c[0] / 255.f;
  m.color.g = c[1] / 255.f;
  m.color.r = c[2] / 255.f;
  m.color.a = 1.f;
  return m;
}
}  // namespace

Simulator::Simulator(const ros::NodeHandle& nh, const ros::NodeHandle& private_nh)
  : nh_(nh),
    parameters_(loadParameters(private_nh)),
    world_(World::load(parameters_.world)),
    renderer_(std::make_unique<SceneRenderer>(world_, parameters_.supersample)),
    robot_(loadRobotDescription()),
    left_chain_(chainFromUrdf(robot_, "base_link", "stereo_left_optical")),
    right_chain_(chainFromUrdf(robot_, "base_link", "stereo_right_optical")),
    pan_(servoFromUrdf(robot_, "head_pan_joint", parameters_.servo_speed)),
    tilt_(servoFromUrdf(robot_, "head_tilt_joint", parameters_.servo_speed)),
    base_(DifferentialDrive::Limits(), parameters_.start_x, parameters_.start_y, parameters_.start_yaw),
    calibration_(StereoCalibration::fromFieldOfView(parameters_.width, parameters_.height,
                                                    parameters_.horizontal_fov_deg * M_PI / 180.0,
                                                    baselineOf(left_chain_, right_chain_))),
    rng_(static_cast<unsigned>(parameters_.seed)),
    noise_(0.f, static_cast<float>(parameters_.noise_sigma)),
    it_(nh_)
{
  advertise();
  subscribe();
  publishObjectMarkers();
}

SimulatorParameters Simulator::loadParameters(const ros::NodeHandle& private_nh)
{
  SimulatorParameters p;
  readParameter(private_nh, "world", p.world);
  readParameter(private_nh, "camera_rate", p.camera_rate);
  readParameter(private_nh, "physics_rate", p.physics_rate);
  readParameter(private_nh, "width", p.width);
  readParameter(private_nh, "height", p.height);
  readParameter(private_nh, "horizontal_fov_deg", p.horizontal_fov_deg);
  readParameter(private_nh, "supersample", p.supersample);
  readParameter(private_nh, "noise_sigma", p.noise_sigma);
  readParameter(private_nh, "blur_sigma", p.blur_sigma);
  readParameter(private_nh, "seed", p.seed);
  readParameter(private_nh, "real_time_factor", p.real_time_factor);
  readParameter(private_nh, "publish_clock", p.publish_clock);
  readParameter(private_nh, "publish_map_to_odom", p.publish_map_to_odom);
  readParameter(private_nh, "start_x", p.start_x);
  readParameter(private_nh, "start_y", p.start_y);
  readParameter(private_nh, "start_yaw", p.start_yaw);
  readParameter(private_nh, "servo_speed", p.servo_speed);
  p.validate();
  return p;
}

void Simulator::advertise()
{
  left_pub_ = it_.advertise("stereo/left/image_raw", 1);
  right_pub_ = it_.advertise("stereo/right/image_raw", 1);
  depth_pub_ = it_.advertise("stereo/ground_truth/depth", 1);
  left_info_pub_ = nh_.advertise<sensor_msgs::CameraInfo>("stereo/left/camera_info", 1);
  right_info_pub_ = nh_.advertise<sensor_msgs::CameraInfo>("stereo/right/camera_info", 1);
  gt_disparity_pub_ = nh_.advertise<stereo_msgs::DisparityImage>("stereo/ground_truth/disparity", 1);
  joints_pub_ = nh_.advertise<sensor_msgs::JointState>("joint_states", 10);
  odom_pub_ = nh_.advertise<nav_msgs::Odometry>("odom", 10);
  gt_pose_pub_ = nh_.advertise<geometry_msgs::PoseStamped>("sim/ground_truth/pose", 10);
  collision_pub_ = nh_.advertise<std_msgs::String>("sim/collision", 10);
  objects_pub_ = nh_.advertise<visualization_msgs::MarkerArray>("sim/objects", 1, true);
  if (parameters_.publish_clock)
    clock_pub_ = nh_.advertise<rosgraph_msgs::Clock>("/clock", 10);
}

void Simulator::subscribe()
{
  pan_sub_ = nh_.subscribe<std_msgs::Float64>("head_pan_joint/command", 10, [this](const std_msgs::Float64ConstPtr& m) {
    if (pan_.command(m->data))
      ROS_WARN_THROTTLE(2.0, "sim: pan command %.3f rad clamped to [%.3f, %.3f]", m->data, pan_.lower(), pan_.upper());
  });
  tilt_sub_ = nh_.subscribe<std_msgs::Float64>(
      "head_tilt_joint/command", 10, [this](const std_msgs::Float64ConstPtr& m) {
        if (tilt_.command(m->data))
          ROS_WARN_THROTTLE(2.0, "sim: tilt command %.3f rad clamped to [%.3f, %.3f]", m->data, tilt_.lower(),
                            tilt_.upper());
      });
  cmd_sub_ = nh_.subscribe<geometry_msgs::Twist>("cmd_vel", 10, [this](const geometry_msgs::TwistConstPtr& m) {
    base_.command(m->linear.x, m->angular.z);
  });
  place_srv_ = nh_.advertiseService("sim/place_object", &Simulator::placeObject, this);
}

bool Simulator::placeObject(biovision_msgs::PlaceObject::Request& request,
                            biovision_msgs::PlaceObject::Response& response)
{
  World changed = world_;
  try
  {
    const int index = changed.placeObject(request.object, "sim/place_object");
    const World::Object& o = changed.objects()[index];
    if (o.obstacle && !base_.obstacleAt(base_.x(), base_.y(), changed).empty() &&
        base_.obstacleAt(base_.x(), base_.y(), world_).empty())
      throw std::runtime_error("sim/place_object: '" + o.label + "' would overlap the robot");
    world_ = std::move(changed);
    renderer_ = std::make_unique<SceneRenderer>(world_, parameters_.supersample);
    publishObjectMarkers();
    response.success = true;
    response.message = "placed '" + o.label + "'";
    ROS_INFO("sim: %s at (%.2f, %.2f)", response.message.c_str(), o.position.x(), o.position.y());
  }
  catch (const std::runtime_error& e)
  {
    response.success = false;
    response.message = e.what();
    ROS_ERROR("sim: %s", e.what());
  }
  return true;
}

void Simulator::publishObjectMarkers()
{
  visualization_msgs::MarkerArray markers;
  for (size_t i = 0; i < world_.objects().size(); ++i)
    markers.markers.push_back(objectMarker(world_, i));
  objects_pub_.publish(markers);
}

void Simulator::run()
{
  const SimulatorParameters& p = parameters_;
  const int steps_per_frame = std::max(1, static_cast<int>(std::lround(p.physics_rate / p.camera_rate)));
  epoch_ = p.publish_clock ? ros::Time(1.0) : ros::Time::now();  // ROS time 0 means "unset"
  wall_start_ = ros::WallTime::now();
  // The simulated odometry is perfect: map and odom coincide (unless a localisation node says otherwise).
  if (p.publish_map_to_odom)
    static_tf_.sendTransform(toTransform(Eigen::Isometry3d::Identity(), "map", "odom", epoch_));
  ROS_INFO("sim: world '%s' (%zu objects, %zu triangles), %dx%d at %.1f Hz, baseline %.3f m, real-time factor %.2f%s",
           world_.name().c_str(), world_.objects().size(), renderer_->triangles(), p.width, p.height, p.camera_rate,
           calibration_.baseline(), p.real_time_factor, p.publish_clock ? ", publishing /clock" : "");
  while (ros::ok())
  {
    ros::spinOnce();
    const ros::Time stamp = stepPhysics();
    publishClock(stamp);
    const Eigen::Isometry3d odom_from_base = odomFromBase();
    publishJointStatesAndTf(odom_from_base, stamp);
    publishOdometryAndGroundTruthPose(odom_from_base, stamp);
    if (step_ % steps_per_frame == 0)
      renderAndPublishCameras(odom_from_base, stamp);
    waitForWallClock();
  }
}

ros::Time Simulator::stepPhysics()
{
  const double dt = 1.0 / parameters_.physics_rate;
  pan_.step(dt);
  tilt_.step(dt);
  if (base_.step(dt, world_))
  {
    std_msgs::String m;
    m.data = base_.collidedWith();
    collision_pub_.publish(m);
    ROS_WARN_THROTTLE(1.0, "sim: collision with '%s'; base stopped", m.data.c_str());
  }
  // Accumulated, not step_ * dt: the committed bags were recorded with these stamps.
  t_ += dt;
  ++step_;
  return epoch_ + ros::Duration(t_);
}

Eigen::Isometry3d Simulator::odomFromBase() const
{
  Eigen::Isometry3d odom_from_base = Eigen::Isometry3d::Identity();
  odom_from_base.translation() << base_.x(), base_.y(), 0.0;
  odom_from_base.linear() = Eigen::AngleAxisd(base_.yaw(), Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return odom_from_base;
}

void Simulator::publishClock(const ros::Time& stamp)
{
  if (!parameters_.publish_clock)
    return;
  rosgraph_msgs::Clock c;
  c.clock = stamp;
  clock_pub_.publish(c);
}

void Simulator::publishJointStatesAndTf(const Eigen::Isometry3d& odom_from_base, const ros::Time& stamp)
{
  sensor_msgs::JointState js;
  js.header.stamp = stamp;
  js.name = {"head_pan_joint", "head_tilt_joint", "left_wheel_joint", "right_wheel_joint"};
  js.position = {pan_.position(), tilt_.position(), base_.leftWheelAngle(), base_.rightWheelAngle()};
  js.velocity = {pan_.velocity(), tilt_.velocity(), 0.0, 0.0};
  joints_pub_.publish(js);
  tf_.sendTransform(toTransform(odom_from_base, "odom", "base_link", stamp));
}

void Simulator::publishOdometryAndGroundTruthPose(const Eigen::Isometry3d& odom_from_base, const ros::Time& stamp)
{
  nav_msgs::Odometry odom;
  odom.header.stamp = stamp;
  odom.header.frame_id = "odom";
  odom.child_frame_id = "base_link";
  const auto tr = toTransform(odom_from_base, "odom", "base_link", stamp).transform;
  odom.pose.pose.position.x = tr.translation.x;
  odom.pose.pose.position.y = tr.translation.y;
  odom.pose.pose.orientation = tr.rotation;
  odom.twist.twist.linear.x = base_.linear();
  odom.twist.twist.angular.z = base_.angular();
  odom_pub_.publish(odom);
  // Ground truth in map, which coincides with odom.
  geometry_msgs::PoseStamped gt;
  gt.header.stamp = stamp;
  gt.header.frame_id = "map";
  gt.pose = odom.pose.pose;
  gt_pose_pub_.publish(gt);
}

void Simulator::renderAndPublishCameras(const Eigen::Isometry3d& odom_from_base, const ros::Time& stamp)
{
  const std::vector<std::string> names = {"head_pan_joint", "head_tilt_joint"};
  const std::vector<double> q = {pan_.position(), tilt_.position()};
  cv::Mat left, right, depth, right_depth;
  renderer_->render(odom_from_base * left_chain_.evaluate(names, q), calibration_.camera(), left, depth);
  renderer_->render(odom_from_base * right_chain_.evaluate(names, q), calibration_.camera(), right, right_depth);
  degrade(left);
  degrade(right);
  std_msgs::Header lh;
  lh.stamp = stamp;
  lh.frame_id = "stereo_left_optical";
  std_msgs::Header rh = lh;
  rh.frame_id = "stereo_right_optical";
  left_pub_.publish(cv_bridge::CvImage(lh, "bgr8", left).toImageMsg());
  right_pub_.publish(cv_bridge::CvImage(rh, "bgr8", right).toImageMsg());
  // Both camera_info in the left frame (see toCameraInfo); the right image keeps its own frame.
  left_info_pub_.publish(toCameraInfo(calibration_.left(), lh));
  right_info_pub_.publish(toCameraInfo(calibration_.right(), lh));
  publishGroundTruthDepth(depth, lh);
}

void Simulator::degrade(cv::Mat& image)
{
  if (parameters_.blur_sigma > 0)
    cv::GaussianBlur(image, image, cv::Size(), parameters_.blur_sigma);
  if (parameters_.noise_sigma > 0)
    for (auto p = image.begin<cv::Vec3b>(); p != image.end<cv::Vec3b>(); ++p)
      for (int c = 0; c < 3; ++c)
        (*p)[c] = cv::saturate_cast<uchar>((*p)[c] + noise_(rng_));
}

void Simulator::publishGroundTruthDepth(const cv::Mat& depth, const std_msgs::Header& header)
{
  if (depth_pub_.getNumSubscribers() > 0)
    depth_pub_.publish(cv_bridge::CvImage(header, "32FC1", depth).toImageMsg());
  if (gt_disparity_pub_.getNumSubscribers() == 0)
    return;
  const double fx = calibration_.camera().fx, baseline = calibration_.baseline();
  stereo_msgs::DisparityImage d;
  d.header = header;
  d.f = static_cast<float>(fx);
  d.T = static_cast<float>(baseline);
  d.min_disparity = 0;
  d.max_disparity = static_cast<float>(parameters_.width);
  d.delta_d = 1.f / 16;
  cv::Mat disparity(depth.size(), CV_32F);
  for (int y = 0; y < depth.rows; ++y)
    for (int x = 0; x < depth.cols; ++x)
    {
      const float z = depth.at<float>(y, x);
      disparity.at<float>(y, x) = std::isfinite(z) ? static_cast<float>(fx * baseline / z) : -1.f;
    }
  cv_bridge::CvImage(header, "32FC1", disparity).toImageMsg(d.image);
  gt_disparity_pub_.publish(d);
}

void Simulator::waitForWallClock() const
{
  // Sim time runs real_time_factor times as fast as wall time (0 = as fast as possible).
  if (parameters_.real_time_factor <= 0)
    return;
  const ros::WallTime due = wall_start_ + ros::WallDuration(t_ / parameters_.real_time_factor);
  const ros::WallTime now = ros::WallTime::now();
  if (due > now)
    (due - now).sleep();
}
}  // namespace biovision_sim
