#include "biovision_memory/ros/memory_nodelet.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include <biovision_msgs/EgoMap.h>
#include <biovision_msgs/LtmItemArray.h>
#include <geometry_msgs/TransformStamped.h>
#include <nav_msgs/OccupancyGrid.h>
#include <pluginlib/class_list_macros.hpp>
#include <tf2_eigen/tf2_eigen.h>
#include <visualization_msgs/MarkerArray.h>

#include "biovision_common/object_label.hpp"
#include "biovision_ros_common/image_message_converter.hpp"
#include "biovision_ros_common/processing_times.hpp"

namespace biovision_memory
{
namespace
{
// A recognised object's |x| / z and |y| / z in its optical frame can be at most this (63 deg off the axis):
// wider than any lens of the stereo cameras here (Bumblebee-2's widest, 2.5 mm: 97 deg across, slope 1.1).
constexpr double kMaxViewSlope = 2.0;

Pose2D planar(const Eigen::Isometry3d& T)
{
  const Eigen::Vector3d x = T.linear().col(0);
  return {T.translation().x(), T.translation().y(), std::atan2(x.y(), x.x())};
}

template <typename T>
void param(const ros::NodeHandle& pnh, const std::string& name, T& value)
{
  pnh.param(name, value, value);
}
}  // namespace

MemoryNodelet::~MemoryNodelet()
{
  timer_.stop();
  if (database_ && stm_)
    save();
}

void MemoryNodelet::readParameters(const ros::NodeHandle& pnh, Settings& s, ShortTermMemoryParameters& stm,
                                   LongTermMemoryParameters& ltm, ObjectMemoryParameters& objects,
                                   LandmarkCorrectorParameters& corrector)
{
  param(pnh, "map_frame", s.map_frame);
  param(pnh, "odom_frame", s.odom_frame);
  param(pnh, "base_frame", s.base_frame);
  param(pnh, "database", s.database);
  param(pnh, "start_empty_on_bad_database", s.start_empty_on_bad_database);
  param(pnh, "start_empty", s.start_empty);
  param(pnh, "save_period", s.save_period);
  param(pnh, "ltm_period", s.ltm_period);
  param(pnh, "publish_period", s.publish_period);
  param(pnh, "disparity_timeout", s.disparity_timeout);
  param(pnh, "tf_timeout", s.tf_timeout);
  param(pnh, "landmark_correction", s.landmark_correction);
  param(pnh, "publish_map_to_odom", s.publish_map_to_odom);
  param(pnh, "map_to_odom_rate", s.map_to_odom_rate);
  auto positive = [](const char* name, double v, double hi) {
    if (!(v > 0.0 && v <= hi))
    {
      std::ostringstream m;
      m << "~" << name << " = " << v << " is outside (0, " << hi << "]";
      throw std::invalid_argument(m.str());
    }
  };
  positive("save_period", s.save_period, 3600);
  positive("ltm_period", s.ltm_period, 3600);
  positive("publish_period", s.publish_period, 3600);
  positive("disparity_timeout", s.disparity_timeout, 3600);
  positive("tf_timeout", s.tf_timeout, 10);
  positive("map_to_odom_rate", s.map_to_odom_rate, 1000);

  param(pnh, "stm/max_range", stm.scan.max_range);
  param(pnh, "stm/min_obstacle_height", stm.scan.min_obstacle_height);
  param(pnh, "stm/max_obstacle_height", stm.scan.max_obstacle_height);
  param(pnh, "stm/strips", stm.scan.strips);
  param(pnh, "stm/min_obstacle_pixels", stm.scan.min_obstacle_pixels);
  param(pnh, "stm/min_valid_fraction", stm.scan.min_valid_fraction);
  param(pnh, "stm/bin_width", stm.scan.bin_width);
  param(pnh, "stm/pixel_step", stm.scan.pixel_step);
  param(pnh, "stm/sectors", stm.sectors);
  param(pnh, "stm/sector_width", stm.sector_width);
  param(pnh, "stm/obstacle_horizon_time", stm.obstacle_horizon_time);
  param(pnh, "stm/free_horizon_time", stm.free_horizon_time);
  param(pnh, "stm/horizon_distance", stm.horizon_distance);
  param(pnh, "stm/map_completion_radius", stm.map_completion_radius);
  stm.validate();

  ReinforcementRules rules;
  param(pnh, "ltm/initial_strength", rules.initial_strength);
  param(pnh, "ltm/reinforcement", rules.reinforcement);
  param(pnh, "ltm/max_strength", rules.max_strength);
  param(pnh, "ltm/penalty", rules.penalty);
  param(pnh, "ltm/forget_period", rules.forget_period);
  ltm.rules = rules;
  param(pnh, "ltm/cell_size", ltm.cell_size);
  param(pnh, "ltm/min_points", ltm.min_points);
  param(pnh, "ltm/free_margin", ltm.free_margin);
  ltm.validate();

  objects.rules = rules;
  param(pnh, "objects/match_distance", objects.match_distance);
  param(pnh, "objects/averaging_window", objects.averaging_window);
  param(pnh, "objects/max_depth", objects.max_depth);
  objects.validate();

  param(pnh, "landmarks/window", corrector.window);
  param(pnh, "landmarks/window_time", corrector.window_time);
  param(pnh, "landmarks/gain", corrector.gain);
  param(pnh, "landmarks/min_spread", corrector.min_spread);
  param(pnh, "landmarks/max_jump", corrector.max_jump);
  param(pnh, "landmarks/max_depth", corrector.max_depth);
  corrector.validate();
}

void MemoryNodelet::onInitNodelet()
{
  ros::NodeHandle& nh = getNodeHandle();
  ros::NodeHandle& pnh = getPrivateNodeHandle();
  ShortTermMemoryParameters stm;
  LongTermMemoryParameters ltm;
  ObjectMemoryParameters objects;
  LandmarkCorrectorParameters corrector;
  try
  {
    readParameters(pnh, settings_, stm, ltm, objects, corrector);
    stm_ = std::make_unique<ShortTermMemory>(stm);
    ltm_ = std::make_unique<LongTermMemory>(ltm);
    objects_ = std::make_unique<ObjectMemory>(objects);
    corrector_ = std::make_unique<LandmarkCorrector>(corrector);
    if (!settings_.database.empty())
    {
      MemoryDatabase::Options options;
      options.cell_size = ltm.cell_size;
      options.start_empty_on_bad = settings_.start_empty_on_bad_database;
      database_ = std::make_unique<MemoryDatabase>(settings_.database, options);
      if (!database_->movedAside().empty())
        diagnostics_.health().reportError(getName(),
                                          "the memory database was refused, starting with an empty "
                                          "memory; the refused file is kept as " +
                                              database_->movedAside() + ": " + database_->refusal());
      if (settings_.start_empty)
        database_->clear();
      ltm_->load(database_->loadCells());
      objects_->load(database_->loadObjects());
      NODELET_INFO("memory database %s: %zu map cells, %zu objects", settings_.database.c_str(), ltm_->cells().size(),
                   objects_->objects().size());
    }
  }
  catch (const std::exception& e)  // invalid_argument, DatabaseError
  {
    // A refused database or bad parameters: do not run with a wrong memory (LazyNodelet logs it as FATAL).
    throw;
  }

  tf_buffer_ = std::make_unique<tf2_ros::Buffer>(ros::Duration(30.0));
  tf_listener_ = std::make_unique<tf2_ros::TransformListener>(*tf_buffer_, nh);
  tf_broadcaster_ = std::make_unique<tf2_ros::TransformBroadcaster>();

  stm_pub_ = advertise<biovision_msgs::EgoMap>(nh, "memory/stm", 5);
  stm_markers_pub_ = advertise<visualization_msgs::MarkerArray>(nh, "memory/stm_markers", 2);
  ltm_pub_ = advertise<nav_msgs::OccupancyGrid>(nh, "memory/ltm", 1, true);
  items_pub_ = advertise<biovision_msgs::LtmItemArray>(nh, "memory/ltm_items", 1, true);
  ltm_markers_pub_ = advertise<visualization_msgs::MarkerArray>(nh, "memory/ltm_markers", 1, true);
  list_srv_ = nh.advertiseService("memory/list_objects", &MemoryNodelet::onList, this);
  query_srv_ = nh.advertiseService("memory/query_object", &MemoryNodelet::onQuery, this);
  forget_srv_ = nh.advertiseService("memory/forget_object", &MemoryNodelet::onForget, this);

  biovision_ros_common::DiagnosticsOptions options;
  options.status_name = "memory";
  options.rate_topic = "memory/stm";
  options.default_max_rate = 100.0;
  options.idle = [this] { return !isSubscribed(); };
  options.working_message = "remembering";
  options.details = [this](diagnostic_updater::DiagnosticStatusWrapper& s) { details(s); };
  diagnostics_.init(nh, pnh, getName(), options);
  diagnostics_.clockJumps().onJumpBack([this] { onTimeJumpBack(); });

  timer_ = nh.createWallTimer(ros::WallDuration(std::min(1.0, settings_.save_period)), &MemoryNodelet::onTimer, this);
  if (settings_.publish_map_to_odom)
    map_to_odom_timer_ = nh.createTimer(ros::Duration(1.0 / settings_.map_to_odom_rate),
                                        &MemoryNodelet::onMapToOdomTimer, this);
}

void MemoryNodelet::subscribe()
{
  ros::NodeHandle& nh = getNodeHandle();
  disparity_sub_ = nh.subscribe("disparity", 2, &MemoryNodelet::onDisparity, this);
  info_sub_ = nh.subscribe("camera_info", 1, &MemoryNodelet::onCameraInfo, this);
  objects_sub_ = nh.subscribe("objects", 10, &MemoryNodelet::onObjects, this);
}

void MemoryNodelet::unsubscribe()
{
  disparity_sub_.shutdown();
  info_sub_.shutdown();
  objects_sub_.shutdown();
}

bool MemoryNodelet::lookup(const std::string& target, const std::string& source, const ros::Time& stamp,
                           Eigen::Isometry3d& out, std::string& error)
{
  try
  {
    out = tf2::transformToEigen(
        tf_buffer_->lookupTransform(target, source, stamp, ros::Duration(settings_.tf_timeout)));
    return true;
  }
  catch (const tf2::TransformException& e)
  {
    error = e.what();
    return false;
  }
}

void MemoryNodelet::onCameraInfo(const sensor_msgs::CameraInfoConstPtr& msg)
{
  if (msg->P[0] > 0 && msg->width > 0)
  {
    std::lock_guard<std::mutex> lock(mutex_);
    camera_info_ = *msg;
    have_camera_info_ = true;
  }
}

void MemoryNodelet::onDisparity(const stereo_msgs::DisparityImageConstPtr& msg)
{
  const biovision_ros_common::ScopedProcessingTimer timer(getName());  // loop_bench's CPU per stage
  // The clock, not the stamps: a disparity map arrives a stereo latency after the timer's `now`, and the
  // objects later still, so stamps alone look like backward jumps (the mission demo reset the STM on
  // every map with BioBin's ~0.3 s latency).
  diagnostics_.clockJumps().observe(ros::Time::now());
  const ros::Time stamp = msg->header.stamp;
  cv::Mat disparity;
  try
  {
    disparity = biovision_ros_common::ImageMessageConverter::toFloat32(msg->image);
  }
  catch (const std::exception& e)
  {
    diagnostics_.health().reportError(getName(), std::string("dropping disparity: ") + e.what());
    return;
  }
  if (!(msg->f > 0.0f) || !(msg->T > 0.0f) || !std::isfinite(msg->f) || !std::isfinite(msg->T))
  {
    diagnostics_.health().reportError(getName(), "dropping disparity with f = " + std::to_string(msg->f) +
                                                     " px and T = " + std::to_string(msg->T) + " m");
    return;
  }
  // Values below min_disparity are invalid (stereo_msgs); the scanner takes ≤ 0 as invalid.
  if (msg->min_disparity > 0.0f)
    disparity.setTo(-1.0f, disparity < msg->min_disparity);
  Eigen::Isometry3d base_from_camera, odom_from_base;
  std::string error;
  if (!lookup(settings_.base_frame, msg->header.frame_id, stamp, base_from_camera, error) ||
      !lookup(settings_.odom_frame, settings_.base_frame, stamp, odom_from_base, error))
  {
    ++tf_failures_;
    diagnostics_.health().reportError(getName(), "skipping a disparity frame, no transform: " + error);
    return;
  }
  DisparityCamera camera;
  camera.fx = camera.fy = msg->f;
  camera.baseline = msg->T;
  camera.cx = 0.5 * (disparity.cols - 1);
  camera.cy = 0.5 * (disparity.rows - 1);
  const Pose2D odom_pose = planar(odom_from_base);
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (have_camera_info_ && camera_info_.width > 0)
    {
      const double scale = static_cast<double>(disparity.cols) / camera_info_.width;  // a downscaled disparity
      camera.fy = camera_info_.P[5] * scale;
      camera.cx = camera_info_.P[2] * scale;
      camera.cy = camera_info_.P[6] * scale;
    }
    try
    {
      stm_->update(disparity, camera, base_from_camera, odom_pose, stamp.toSec());
      odom_pose_ = odom_pose;
    }
    catch (const std::invalid_argument& e)
    {
      diagnostics_.health().reportError(getName(), std::string("dropping disparity: ") + e.what());
      return;
    }
    ++frames_;
    last_disparity_ = stamp;
    last_disparity_wall_ = ros::WallTime::now();
    if (last_ltm_update_.isZero() || (stamp - last_ltm_update_).toSec() >= settings_.ltm_period)
    {
      const Pose2D map_pose = corrector_->mapFromOdom().compose(odom_pose);
      ltm_->update(stm_->lastScan(), map_pose, stamp.toSec());
      last_ltm_update_ = stamp;
    }
  }
  publishStm(stamp);
  diagnostics_.tick();
  if (last_publish_.isZero() || (stamp - last_publish_).toSec() >= settings_.publish_period)
  {
    publishLtm(stamp);
    last_publish_ = stamp;
  }
}

void MemoryNodelet::onObjects(const biovision_msgs::RecognizedObjectArrayConstPtr& msg)
{
  diagnostics_.clockJumps().observe(ros::Time::now());
  Eigen::Isometry3d odom_from_camera;
  std::string error;
  bool any = false;
  for (const auto& o : msg->objects)
    any = any || o.has_position;
  if (!any)
    return;
  if (!lookup(settings_.odom_frame, msg->header.frame_id, msg->header.stamp, odom_from_camera, error))
  {
    ++tf_failures_;
    diagnostics_.health().reportError(getName(), "skipping recognised objects, no transform: " + error);
    return;
  }
  std::lock_guard<std::mutex> lock(mutex_);
  for (const auto& o : msg->objects)
  {
    const Eigen::Vector3d p(o.position.x, o.position.y, o.position.z);
    if (!o.has_position || !p.allFinite() || o.label.empty())
      continue;
    const std::string problem = biovision_common::ObjectLabel::problem(o.label);
    if (!problem.empty())
    {
      diagnostics_.health().reportError(getName(), "skipping a recognised object: " + problem);
      continue;
    }
    // Behind the camera (no stereo position; ObjectMemory::observe refuses a negative depth) or outside any
    // camera's view: a corrupt position, which would be remembered at absurd map coordinates.
    if (!(p.z() > 0.0) || std::abs(p.x()) > kMaxViewSlope * p.z() || std::abs(p.y()) > kMaxViewSlope * p.z())
    {
      diagnostics_.health().reportError(getName(),
                                        "skipping a recognised object outside its camera's view (z <= 0, "
                                        "or |x| or |y| over 2 z)");
      continue;
    }
    const Eigen::Vector3d in_odom = odom_from_camera * p;
    const Pose2D& map_from_odom = corrector_->mapFromOdom();
    const Eigen::Vector2d xy = map_from_odom.apply(in_odom.head<2>());
    const auto sighting = objects_->observe(o.label, {xy.x(), xy.y(), in_odom.z()}, msg->header.stamp.toSec(), p.z());
    if (sighting.too_far)
    {
      ++far_sightings_;
      continue;
    }
    ++sightings_;
    if (sighting.landmark && settings_.landmark_correction &&
        corrector_->observe(sighting.remembered.head<2>(), in_odom.head<2>(), msg->header.stamp.toSec(), p.z()))
      ++landmark_sightings_;
  }
}

void MemoryNodelet::onMapToOdomTimer(const ros::TimerEvent&)
{
  Pose2D m;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    m = corrector_->mapFromOdom();
  }
  geometry_msgs::TransformStamped t;
  // Stamped a little ahead, as localisers do, so lookups at the latest odometry stamp succeed.
  t.header.stamp = ros::Time::now() + ros::Duration(1.0 / settings_.map_to_odom_rate);
  // A timer on sim time catches up on missed periods with the clock standing still: the same stamp again is
  // dropped by every listener with a TF_REPEATED_DATA warning (11 in a demo's start-up). An earlier stamp (the
  // clock jumped back) is sent: listeners start over.
  if (t.header.stamp == map_to_odom_stamp_)
    return;
  map_to_odom_stamp_ = t.header.stamp;
  t.header.frame_id = settings_.map_frame;
  t.child_frame_id = settings_.odom_frame;
  t.transform.translation.x = m.x;
  t.transform.translation.y = m.y;
  t.transform.rotation.z = std::sin(0.5 * m.yaw);
  t.transform.rotation.w = std::cos(0.5 * m.yaw);
  tf_broadcaster_->sendTransform(t);
}

void MemoryNodelet::onTimer(const ros::WallTimerEvent&)
{
  const ros::Time now = ros::Time::now();
  diagnostics_.clockJumps().observe(now);
  bool stale = false;
  double silence = 0.0;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!last_disparity_.isZero())
    {
      silence = (now - last_disparity_).toSec();
      stale = silence > settings_.disparity_timeout;
      if (stale)
      {
        // No new view: the STM keeps ageing (moved by odometry when tf has it), so free space fades.
        Eigen::Isometry3d odom_from_base;
        std::string error;
        Pose2D pose{NAN, NAN, NAN};
        if (lookup(settings_.odom_frame, settings_.base_frame, ros::Time(0), odom_from_base, error))
          pose = planar(odom_from_base);
        stm_->moveTo(pose, now.toSec());
        if (std::isfinite(pose.x))
          odom_pose_ = pose;
      }
    }
    ltm_->forget(now.toSec());
    objects_->forget(now.toSec());
  }
  if (stale)
  {
    if (isSubscribed())
      diagnostics_.health().reportError(getName(), "no disparity for " + std::to_string(silence) +
                                                       " s: the short-term memory is ageing out");
    publishStm(now);
  }
  if ((ros::WallTime::now() - last_save_).toSec() >= settings_.save_period)
  {
    last_save_ = ros::WallTime::now();
    save();
  }
}

void MemoryNodelet::save()
{
  if (!database_)
    return;
  try
  {
    std::lock_guard<std::mutex> lock(mutex_);
    database_->save(ltm_->takeChanges(), objects_->takeChanges());
    last_save_error_.clear();
  }
  catch (const DatabaseError& e)
  {
    last_save_error_ = e.what();
    diagnostics_.health().reportError(getName(),
                                      std::string("saving the memory failed (kept in RAM, retrying): ") + e.what());
  }
}

void MemoryNodelet::onTimeJumpBack()
{
  std::lock_guard<std::mutex> lock(mutex_);
  const double now = ros::Time::now().toSec();
  stm_->reset();
  corrector_->reset(corrector_->mapFromOdom());
  ltm_->rebaseTime(now);
  objects_->rebaseTime(now);
  last_disparity_ = last_ltm_update_ = last_publish_ = ros::Time();
  NODELET_WARN("time went backwards: short-term memory reset, memory time tags clamped to now");
}

void MemoryNodelet::publishStm(const ros::Time& stamp)
{
  std::vector<ShortTermMemory::Sector> sectors;
  double width, range;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    // The base reads these: the STM completed by the long-term map around the base (map_completion_radius).
    sectors = stm_->sectors(*ltm_, corrector_->mapFromOdom().compose(odom_pose_));
    width = stm_->parameters().sector_width;
    range = stm_->parameters().scan.max_range;
  }
  biovision_msgs::EgoMap map;
  map.header.stamp = stamp;
  map.header.frame_id = settings_.base_frame;
  map.section_width = static_cast<float>(width);
  map.max_range = static_cast<float>(range);
  for (const auto& s : sectors)
  {
    map.section_angles.push_back(static_cast<float>(s.centre));
    map.obstacle_distance.push_back(static_cast<float>(s.distance));
    map.obstacle_offset.push_back(static_cast<float>(s.offset));
    map.confidence.push_back(static_cast<float>(s.confidence));
  }
  stm_pub_.publish(map);
  if (stm_markers_pub_.getNumSubscribers() == 0)
    return;
  // Fig. 5.3's radial slices: black = obstacle, green = free, grey = unknown; alpha = confidence.
  visualization_msgs::MarkerArray markers;
  for (size_t i = 0; i < sectors.size(); ++i)
  {
    const auto& s = sectors[i];
    visualization_msgs::Marker m;
    m.header = map.header;
    m.ns = "stm";
    m.id = static_cast<int>(i);
    m.type = visualization_msgs::Marker::TRIANGLE_LIST;
    m.scale.x = m.scale.y = m.scale.z = 1.0;
    m.pose.orientation.w = 1.0;
    const double r = s.obstacle ? s.distance : range;
    const int steps = 6;
    for (int k = 0; k < steps; ++k)
    {
      const double a0 = s.centre - width / 2 + width * k / steps, a1 = a0 + width / steps;
      geometry_msgs::Point o, p0, p1;
      p0.x = r * std::cos(a0);
      p0.y = r * std::sin(a0);
      p1.x = r * std::cos(a1);
      p1.y = r * std::sin(a1);
      m.points.push_back(o);
      m.points.push_back(p0);
      m.points.push_back(p1);
    }
    m.color.a = static_cast<float>(0.2 + 0.6 * s.confidence);
    if (s.confidence <= 0.0)
      m.color.r = m.color.g = m.color.b = 0.6f;
    else if (s.obstacle)
      m.color.r = m.color.g = m.color.b = 0.0f;
    else
      m.color.g = 0.8f;
    markers.markers.push_back(m);
  }
  stm_markers_pub_.publish(markers);
}

void MemoryNodelet::publishLtm(const ros::Time& stamp)
{
  nav_msgs::OccupancyGrid grid;
  biovision_msgs::LtmItemArray items;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    const double cell = ltm_->parameters().cell_size;
    const int max_strength = ltm_->parameters().rules.max_strength;
    int x0 = std::numeric_limits<int>::max(), y0 = x0, x1 = std::numeric_limits<int>::min(), y1 = x1;
    for (const auto& [k, c] : ltm_->cells())
    {
      x0 = std::min(x0, c.ix);
      y0 = std::min(y0, c.iy);
      x1 = std::max(x1, c.ix);
      y1 = std::max(y1, c.iy);
    }
    if (ltm_->cells().empty())
      x0 = y0 = x1 = y1 = 0;
    const int margin = 5;
    x0 -= margin;
    y0 -= margin;
    x1 += margin;
    y1 += margin;
    grid.info.resolution = static_cast<float>(cell);
    grid.info.width = static_cast<uint32_t>(x1 - x0 + 1);
    grid.info.height = static_cast<uint32_t>(y1 - y0 + 1);
    grid.info.origin.position.x = x0 * cell;
    grid.info.origin.position.y = y0 * cell;
    grid.info.origin.orientation.w = 1.0;
    grid.data.assign(static_cast<size_t>(grid.info.width) * grid.info.height, -1);  // unknown
    for (const auto& [k, c] : ltm_->cells())
    {
      grid.data[static_cast<size_t>(c.iy - y0) * grid.info.width + (c.ix - x0)] = static_cast<int8_t>(
          std::clamp(100 * c.strength / max_strength, 1, 100));
      biovision_msgs::LtmItem item;
      item.id = static_cast<uint32_t>(k & 0xffffffff) ^ static_cast<uint32_t>(k >> 32);
      item.kind = "obstacle";
      item.position.x = ltm_->cellCentre(c.ix);
      item.position.y = ltm_->cellCentre(c.iy);
      item.radius = static_cast<float>(cell / 2);
      item.strength = static_cast<float>(c.strength) / max_strength;
      item.observations = c.observations;
      item.last_seen = ros::Time(std::max(0.0, c.last_seen));
      items.items.push_back(item);
    }
    uint32_t id = 0;
    for (const auto& [label, o] : objects_->objects())
    {
      items.items.push_back(objectItem(label, o, 0x80000000u | id++));
    }
  }
  grid.header.stamp = items.header.stamp = stamp;
  grid.header.frame_id = items.header.frame_id = settings_.map_frame;
  grid.info.map_load_time = stamp;
  ltm_pub_.publish(grid);
  items_pub_.publish(items);
  if (ltm_markers_pub_.getNumSubscribers() == 0)
    return;
  // The remembered objects for rviz (DESIGN §3's "+ MarkerArray" beside memory/ltm): a DELETEALL first, so
  // forgotten objects disappear, then per object a sphere (green = landmark, fixed at M_R; orange = object)
  // with alpha = strength and its label above it.
  visualization_msgs::MarkerArray markers;
  visualization_msgs::Marker clear;
  clear.header = grid.header;
  clear.action = visualization_msgs::Marker::DELETEALL;
  markers.markers.push_back(clear);
  int id = 0;
  for (const auto& item : items.items)
  {
    if (item.kind != "object" && item.kind != "landmark")
      continue;
    visualization_msgs::Marker sphere;
    sphere.header = grid.header;
    sphere.ns = "ltm_objects";
    sphere.id = id++;
    sphere.type = visualization_msgs::Marker::SPHERE;
    sphere.pose.position = item.position;
    sphere.pose.orientation.w = 1.0;
    sphere.scale.x = sphere.scale.y = sphere.scale.z = 2.0 * item.radius;
    const bool landmark = item.kind == "landmark";
    sphere.color.r = landmark ? 0.1f : 1.0f;
    sphere.color.g = landmark ? 0.8f : 0.5f;
    sphere.color.b = 0.1f;
    sphere.color.a = 0.3f + 0.7f * std::clamp(item.strength, 0.0f, 1.0f);
    visualization_msgs::Marker text = sphere;
    text.ns = "ltm_labels";
    text.type = visualization_msgs::Marker::TEXT_VIEW_FACING;
    text.pose.position.z += 0.25;
    text.scale.x = text.scale.y = 0.0;
    text.scale.z = 0.15;
    text.color.r = text.color.g = text.color.b = text.color.a = 1.0f;
    text.text = item.label + (landmark ? " (landmark)" : "");
    markers.markers.push_back(sphere);
    markers.markers.push_back(text);
  }
  ltm_markers_pub_.publish(markers);
}

biovision_msgs::LtmItem MemoryNodelet::objectItem(const std::string& label, const ObjectMemory::Object& o,
                                                  uint32_t id) const
{
  biovision_msgs::LtmItem item;
  item.id = id;
  item.kind = objects_->isLandmark(o) ? "landmark" : "object";
  item.label = label;
  item.position.x = o.position.x();
  item.position.y = o.position.y();
  item.position.z = o.position.z();
  item.radius = 0.1f;
  item.strength = static_cast<float>(objects_->confidence(o));
  item.observations = o.observations;
  item.last_seen = ros::Time(std::max(0.0, o.last_seen));
  return item;
}

bool MemoryNodelet::onList(biovision_msgs::ListMemoryObjects::Request&,
                           biovision_msgs::ListMemoryObjects::Response& res)
{
  std::lock_guard<std::mutex> lock(mutex_);
  uint32_t id = 0;
  for (const auto& [label, o] : objects_->objects())
  {
    res.items.push_back(objectItem(label, o, id++));
  }
  return true;
}

bool MemoryNodelet::onQuery(biovision_msgs::QueryObject::Request& req, biovision_msgs::QueryObject::Response& res)
{
  std::lock_guard<std::mutex> lock(mutex_);
  const auto* o = objects_->find(req.label);
  res.found = o != nullptr;
  if (!o)
  {
    res.message = "no memory of '" + req.label + "' (" + std::to_string(objects_->objects().size()) +
                  " objects remembered)";
    return true;
  }
  res.position.header.frame_id = settings_.map_frame;
  res.position.header.stamp = ros::Time(std::max(0.0, o->last_seen));
  res.position.point.x = o->position.x();
  res.position.point.y = o->position.y();
  res.position.point.z = o->position.z();
  res.first_seen = ros::Time(std::max(0.0, o->first_seen));
  res.last_seen = ros::Time(std::max(0.0, o->last_seen));
  res.confidence = static_cast<float>(objects_->confidence(*o));
  res.observations = o->observations;
  res.landmark = objects_->isLandmark(*o);
  res.message = "ok";
  return true;
}

bool MemoryNodelet::onForget(biovision_msgs::ForgetObject::Request& req, biovision_msgs::ForgetObject::Response& res)
{
  std::lock_guard<std::mutex> lock(mutex_);
  res.success = objects_->remove(req.label);
  res.message = res.success ? "forgot '" + req.label + "'" : "no memory of '" + req.label + "'";
  return true;
}

void MemoryNodelet::details(diagnostic_updater::DiagnosticStatusWrapper& s)
{
  std::lock_guard<std::mutex> lock(mutex_);
  int known = 0, obstacles = 0;
  double oldest = 0.0;
  for (const auto& sec : stm_->sectors())
  {
    if (sec.confidence > 0)
    {
      ++known;
      oldest = std::max(oldest, sec.age);
    }
    obstacles += sec.obstacle ? 1 : 0;
  }
  const double silence = last_disparity_.isZero() ? -1.0 : (ros::WallTime::now() - last_disparity_wall_).toSec();
  s.add("disparity frames", frames_);
  s.add("seconds since the last disparity (wall)", silence);
  s.add("STM",
        silence > settings_.disparity_timeout ? "ageing: no disparity" : (silence < 0 ? "no disparity yet" : "fresh"));
  s.add("STM sectors known", known);
  s.add("STM sectors with an obstacle", obstacles);
  s.add("STM oldest known sector [s]", oldest);
  s.add("LTM cells", ltm_->cells().size());
  int landmarks = 0;
  for (const auto& [label, o] : objects_->objects())
    landmarks += objects_->isLandmark(o) ? 1 : 0;
  s.add("objects", objects_->objects().size());
  s.add("landmarks", landmarks);
  s.add("object sightings", sightings_);
  s.add("object sightings deeper than objects/max_depth (not used)", far_sightings_);
  s.add("landmark sightings used", landmark_sightings_);
  const Pose2D& m = corrector_->mapFromOdom();
  s.addf("map->odom", "x %.3f m, y %.3f m, yaw %.4f rad", m.x, m.y, m.yaw);
  s.add("tf failures", tf_failures_);
  s.add("database", settings_.database.empty() ? std::string("none (not persisted)") : settings_.database);
  if (database_)
  {
    s.add("database changes pending", database_->pending());
    s.add("database last save error", last_save_error_.empty() ? std::string("none") : last_save_error_);
    if (!database_->movedAside().empty())
    {
      // Stays visible (WARN) until the next start: somebody should look at the kept file.
      s.add("refused database kept as", database_->movedAside());
      s.add("refused because", database_->refusal());
      s.mergeSummary(diagnostic_msgs::DiagnosticStatus::WARN,
                     "memory database refused at start, kept as " + database_->movedAside());
    }
  }
}
}  // namespace biovision_memory

PLUGINLIB_EXPORT_CLASS(biovision_memory::MemoryNodelet, nodelet::Nodelet)
