// sim: the simulated BioVision robot (Pioneer 3DX + PhantomX pan/tilt + Bumblebee-2) in a textured
// world. Speaks the real drivers' topics, renders a rectified stereo pair, and publishes ground truth.
#include <cmath>
#include <memory>
#include <random>
#include <string>

#include <cv_bridge/cv_bridge.h>
#include <geometry_msgs/PoseStamped.h>
#include <geometry_msgs/TransformStamped.h>
#include <geometry_msgs/Twist.h>
#include <image_transport/image_transport.h>
#include <nav_msgs/Odometry.h>
#include <opencv2/imgproc.hpp>
#include <ros/ros.h>
#include <rosgraph_msgs/Clock.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/JointState.h>
#include <std_msgs/Float64.h>
#include <std_msgs/String.h>
#include <stereo_msgs/DisparityImage.h>
#include <tf2_ros/static_transform_broadcaster.h>
#include <tf2_ros/transform_broadcaster.h>
#include <urdf/model.h>
#include <visualization_msgs/MarkerArray.h>

#include "biovision_sim/differential_drive.hpp"
#include "biovision_sim/kinematic_chain.hpp"
#include "biovision_sim/scene_renderer.hpp"
#include "biovision_sim/servo.hpp"
#include "biovision_sim/world.hpp"

using namespace biovision_sim;

namespace
{
Eigen::Isometry3d toEigen(const urdf::Pose& p)
{
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translation() << p.position.x, p.position.y, p.position.z;
  t.linear() = Eigen::Quaterniond(p.rotation.w, p.rotation.x, p.rotation.y, p.rotation.z).toRotationMatrix();
  return t;
}

// The chain root -> tip of the robot description (fixed and revolute joints only).
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

geometry_msgs::TransformStamped toTransform(const Eigen::Isometry3d& t, const std::string& parent, const std::string& child,
                                            const ros::Time& stamp)
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

sensor_msgs::CameraInfo cameraInfo(const PinholeCamera& c, double baseline, const std::string& frame)
{
  sensor_msgs::CameraInfo info;
  info.header.frame_id = frame;
  info.width = c.width;
  info.height = c.height;
  info.distortion_model = "plumb_bob";
  info.D.assign(5, 0.0);
  info.K = {c.fx, 0, c.cx, 0, c.fy, c.cy, 0, 0, 1};
  info.R = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  info.P = {c.fx, 0, c.cx, -c.fx * baseline, 0, c.fy, c.cy, 0, 0, 0, 1, 0};
  return info;
}
}  // namespace

int main(int argc, char** argv)
{
  ros::init(argc, argv, "sim");
  ros::NodeHandle nh, pnh("~");
  std::string world_file;
  if (!pnh.getParam("world", world_file))
  {
    ROS_FATAL("sim: ~world (a world YAML file) is required");
    return 1;
  }
  double camera_rate, physics_rate, hfov_deg, real_time_factor, noise_sigma, blur_sigma, start_x, start_y, start_yaw,
      servo_speed;
  int width, height, supersample, seed;
  bool publish_clock;
  pnh.param("camera_rate", camera_rate, 10.0);
  pnh.param("physics_rate", physics_rate, 50.0);
  pnh.param("width", width, 320);
  pnh.param("height", height, 240);
  pnh.param("horizontal_fov_deg", hfov_deg, 43.0);
  pnh.param("supersample", supersample, 2);
  pnh.param("noise_sigma", noise_sigma, 0.0);
  pnh.param("blur_sigma", blur_sigma, 0.0);  // optical blur [px], Gaussian
  pnh.param("seed", seed, 1);
  pnh.param("real_time_factor", real_time_factor, 1.0);
  pnh.param("publish_clock", publish_clock, true);
  pnh.param("start_x", start_x, 0.0);
  pnh.param("start_y", start_y, 0.0);
  pnh.param("start_yaw", start_yaw, 0.0);
  pnh.param("servo_speed", servo_speed, 3.0);
  if (!(camera_rate > 0 && physics_rate >= camera_rate && width >= 32 && height >= 24 && hfov_deg > 1 && hfov_deg < 179 &&
        real_time_factor >= 0 && noise_sigma >= 0 && blur_sigma >= 0 && blur_sigma <= 10 && servo_speed > 0 && supersample >= 1 && supersample <= 4))
  {
    ROS_FATAL("sim: bad parameters (need camera_rate > 0, physics_rate >= camera_rate, width >= 32, height >= 24, "
              "1 < horizontal_fov_deg < 179, real_time_factor >= 0, noise_sigma >= 0, 0 <= blur_sigma <= 10, servo_speed > 0, "
              "supersample 1..4)");
    return 1;
  }

  std::unique_ptr<World> world;
  try
  {
    world = std::make_unique<World>(World::load(world_file));
  }
  catch (const std::exception& e)
  {
    ROS_FATAL("sim: %s", e.what());
    return 1;
  }
  const SceneRenderer renderer(*world, supersample);

  urdf::Model model;
  if (!model.initParam("robot_description"))
  {
    ROS_FATAL("sim: no robot_description (load biovision_description's URDF first)");
    return 1;
  }
  KinematicChain left_chain, right_chain;
  try
  {
    left_chain = chainFromUrdf(model, "base_link", "stereo_left_optical");
    right_chain = chainFromUrdf(model, "base_link", "stereo_right_optical");
  }
  catch (const std::exception& e)
  {
    ROS_FATAL("sim: %s", e.what());
    return 1;
  }
  auto limits = [&](const std::string& joint, double& lo, double& hi) {
    const auto j = model.getJoint(joint);
    if (!j || !j->limits)
      throw std::runtime_error("robot_description has no limited joint '" + joint + "'");
    lo = j->limits->lower;
    hi = j->limits->upper;
  };
  double pan_lo, pan_hi, tilt_lo, tilt_hi;
  try
  {
    limits("head_pan_joint", pan_lo, pan_hi);
    limits("head_tilt_joint", tilt_lo, tilt_hi);
  }
  catch (const std::exception& e)
  {
    ROS_FATAL("sim: %s", e.what());
    return 1;
  }
  Servo pan(pan_lo, pan_hi, servo_speed), tilt(tilt_lo, tilt_hi, servo_speed);
  DifferentialDrive base(DifferentialDrive::Limits(), start_x, start_y, start_yaw);
  const PinholeCamera camera = PinholeCamera::fromFieldOfView(width, height, hfov_deg * M_PI / 180.0);
  const double baseline = (left_chain.evaluate({}, {}).inverse() * right_chain.evaluate({}, {})).translation().norm();

  image_transport::ImageTransport it(nh);
  image_transport::Publisher left_pub = it.advertise("stereo/left/image_raw", 1);
  image_transport::Publisher right_pub = it.advertise("stereo/right/image_raw", 1);
  image_transport::Publisher depth_pub = it.advertise("stereo/ground_truth/depth", 1);
  ros::Publisher left_info_pub = nh.advertise<sensor_msgs::CameraInfo>("stereo/left/camera_info", 1);
  ros::Publisher right_info_pub = nh.advertise<sensor_msgs::CameraInfo>("stereo/right/camera_info", 1);
  ros::Publisher gt_disparity_pub = nh.advertise<stereo_msgs::DisparityImage>("stereo/ground_truth/disparity", 1);
  ros::Publisher joints_pub = nh.advertise<sensor_msgs::JointState>("joint_states", 10);
  ros::Publisher odom_pub = nh.advertise<nav_msgs::Odometry>("odom", 10);
  ros::Publisher gt_pose_pub = nh.advertise<geometry_msgs::PoseStamped>("sim/ground_truth/pose", 10);
  ros::Publisher collision_pub = nh.advertise<std_msgs::String>("sim/collision", 10);
  ros::Publisher objects_pub = nh.advertise<visualization_msgs::MarkerArray>("sim/objects", 1, true);
  ros::Publisher clock_pub;
  if (publish_clock)
    clock_pub = nh.advertise<rosgraph_msgs::Clock>("/clock", 10);
  tf2_ros::TransformBroadcaster tf;
  tf2_ros::StaticTransformBroadcaster static_tf;

  ros::Subscriber pan_sub = nh.subscribe<std_msgs::Float64>("head_pan_joint/command", 10, [&](const std_msgs::Float64ConstPtr& m) {
    if (pan.command(m->data))
      ROS_WARN_THROTTLE(2.0, "sim: pan command %.3f rad clamped to [%.3f, %.3f]", m->data, pan.lower(), pan.upper());
  });
  ros::Subscriber tilt_sub = nh.subscribe<std_msgs::Float64>("head_tilt_joint/command", 10, [&](const std_msgs::Float64ConstPtr& m) {
    if (tilt.command(m->data))
      ROS_WARN_THROTTLE(2.0, "sim: tilt command %.3f rad clamped to [%.3f, %.3f]", m->data, tilt.lower(), tilt.upper());
  });
  ros::Subscriber cmd_sub = nh.subscribe<geometry_msgs::Twist>("cmd_vel", 10, [&](const geometry_msgs::TwistConstPtr& m) {
    base.command(m->linear.x, m->angular.z);
  });

  // Object markers (latched) and the static map -> odom (the simulated odometry is perfect).
  visualization_msgs::MarkerArray markers;
  for (size_t i = 0; i < world->objects().size(); ++i)
  {
    const auto& o = world->objects()[i];
    visualization_msgs::Marker m;
    m.header.frame_id = "map";
    m.ns = o.label;
    m.id = static_cast<int>(i);
    m.type = o.shape == "cylinder" ? visualization_msgs::Marker::CYLINDER : visualization_msgs::Marker::CUBE;
    m.pose.position.x = o.position.x();
    m.pose.position.y = o.position.y();
    m.pose.position.z = o.position.z();
    m.pose.orientation.z = std::sin(o.yaw / 2);
    m.pose.orientation.w = std::cos(o.yaw / 2);
    m.scale.x = o.size.x();
    m.scale.y = o.size.y();
    m.scale.z = o.size.z();
    const cv::Vec3f c = world->textures()[o.texture]->image().at<cv::Vec3f>(0, 0);
    m.color.b = c[0] / 255.f;
    m.color.g = c[1] / 255.f;
    m.color.r = c[2] / 255.f;
    m.color.a = 1.f;
    markers.markers.push_back(m);
  }
  objects_pub.publish(markers);

  std::mt19937 rng(static_cast<unsigned>(seed));
  std::normal_distribution<float> noise(0.f, static_cast<float>(noise_sigma));
  const double dt = 1.0 / physics_rate;
  const int steps_per_frame = std::max(1, static_cast<int>(std::lround(physics_rate / camera_rate)));
  const ros::Time epoch = publish_clock ? ros::Time(1.0) : ros::Time::now();  // ROS time 0 means "unset"
  double t = 0.0;
  long step = 0;
  const ros::WallTime wall_start = ros::WallTime::now();
  static_tf.sendTransform(toTransform(Eigen::Isometry3d::Identity(), "map", "odom", epoch));
  ROS_INFO("sim: world '%s' (%zu objects, %zu triangles), %dx%d at %.1f Hz, baseline %.3f m, real-time factor %.2f%s",
           world->name().c_str(), world->objects().size(), renderer.triangles(), width, height, camera_rate, baseline,
           real_time_factor, publish_clock ? ", publishing /clock" : "");

  while (ros::ok())
  {
    ros::spinOnce();
    pan.step(dt);
    tilt.step(dt);
    if (base.step(dt, *world))
    {
      std_msgs::String m;
      m.data = base.collidedWith();
      collision_pub.publish(m);
      ROS_WARN_THROTTLE(1.0, "sim: collision with '%s'; base stopped", m.data.c_str());
    }
    t += dt;
    ++step;
    const ros::Time stamp = epoch + ros::Duration(t);
    if (publish_clock)
    {
      rosgraph_msgs::Clock c;
      c.clock = stamp;
      clock_pub.publish(c);
    }

    // Joints, odometry and ground truth every physics step.
    sensor_msgs::JointState js;
    js.header.stamp = stamp;
    js.name = {"head_pan_joint", "head_tilt_joint", "left_wheel_joint", "right_wheel_joint"};
    js.position = {pan.position(), tilt.position(), base.leftWheelAngle(), base.rightWheelAngle()};
    js.velocity = {pan.velocity(), tilt.velocity(), 0.0, 0.0};
    joints_pub.publish(js);
    Eigen::Isometry3d world_from_base = Eigen::Isometry3d::Identity();
    world_from_base.translation() << base.x(), base.y(), 0.0;
    world_from_base.linear() = Eigen::AngleAxisd(base.yaw(), Eigen::Vector3d::UnitZ()).toRotationMatrix();
    tf.sendTransform(toTransform(world_from_base, "odom", "base_link", stamp));
    nav_msgs::Odometry odom;
    odom.header.stamp = stamp;
    odom.header.frame_id = "odom";
    odom.child_frame_id = "base_link";
    const auto tr = toTransform(world_from_base, "odom", "base_link", stamp).transform;
    odom.pose.pose.position.x = tr.translation.x;
    odom.pose.pose.position.y = tr.translation.y;
    odom.pose.pose.orientation = tr.rotation;
    odom.twist.twist.linear.x = base.linear();
    odom.twist.twist.angular.z = base.angular();
    odom_pub.publish(odom);
    geometry_msgs::PoseStamped gt;
    gt.header.stamp = stamp;
    gt.header.frame_id = "map";
    gt.pose = odom.pose.pose;
    gt_pose_pub.publish(gt);

    if (step % steps_per_frame == 0)
    {
      const std::vector<std::string> names = {"head_pan_joint", "head_tilt_joint"};
      const std::vector<double> q = {pan.position(), tilt.position()};
      cv::Mat left, right, depth, right_depth;
      renderer.render(world_from_base * left_chain.evaluate(names, q), camera, left, depth);
      renderer.render(world_from_base * right_chain.evaluate(names, q), camera, right, right_depth);
      if (blur_sigma > 0)
        for (cv::Mat* img : {&left, &right})
          cv::GaussianBlur(*img, *img, cv::Size(), blur_sigma);
      if (noise_sigma > 0)
        for (cv::Mat* img : {&left, &right})
          for (auto p = img->begin<cv::Vec3b>(); p != img->end<cv::Vec3b>(); ++p)
            for (int c = 0; c < 3; ++c)
              (*p)[c] = cv::saturate_cast<uchar>((*p)[c] + noise(rng));
      std_msgs::Header lh;
      lh.stamp = stamp;
      lh.frame_id = "stereo_left_optical";
      std_msgs::Header rh = lh;
      rh.frame_id = "stereo_right_optical";
      left_pub.publish(cv_bridge::CvImage(lh, "bgr8", left).toImageMsg());
      right_pub.publish(cv_bridge::CvImage(rh, "bgr8", right).toImageMsg());
      auto li = cameraInfo(camera, 0.0, lh.frame_id);
      li.header = lh;
      // A rectified pair shares the left frame in camera_info (image_geometry's StereoCameraModel,
      // and so stereo_image_proc, require equal frame ids); the right image keeps its own frame.
      auto ri = cameraInfo(camera, baseline, lh.frame_id);
      ri.header = lh;
      left_info_pub.publish(li);
      right_info_pub.publish(ri);
      if (depth_pub.getNumSubscribers() > 0)
        depth_pub.publish(cv_bridge::CvImage(lh, "32FC1", depth).toImageMsg());
      if (gt_disparity_pub.getNumSubscribers() > 0)
      {
        stereo_msgs::DisparityImage d;
        d.header = lh;
        d.f = static_cast<float>(camera.fx);
        d.T = static_cast<float>(baseline);
        d.min_disparity = 0;
        d.max_disparity = static_cast<float>(width);
        d.delta_d = 1.f / 16;
        cv::Mat disparity(depth.size(), CV_32F);
        for (int y = 0; y < depth.rows; ++y)
          for (int x = 0; x < depth.cols; ++x)
          {
            const float z = depth.at<float>(y, x);
            disparity.at<float>(y, x) = std::isfinite(z) ? static_cast<float>(camera.fx * baseline / z) : -1.f;
          }
        cv_bridge::CvImage(lh, "32FC1", disparity).toImageMsg(d.image);
        gt_disparity_pub.publish(d);
      }
    }
    // Pace: sim time runs real_time_factor times as fast as wall time (0 = as fast as possible).
    if (real_time_factor > 0)
    {
      const ros::WallTime due = wall_start + ros::WallDuration(t / real_time_factor);
      const ros::WallTime now = ros::WallTime::now();
      if (due > now)
        (due - now).sleep();
    }
  }
  return 0;
}
