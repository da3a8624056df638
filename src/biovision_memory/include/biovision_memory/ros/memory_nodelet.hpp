#pragma once

#include <cmath>
#include <memory>
#include <mutex>
#include <string>

#include <biovision_msgs/ForgetObject.h>
#include <biovision_msgs/ListMemoryObjects.h>
#include <biovision_msgs/QueryObject.h>
#include <biovision_msgs/RecognizedObjectArray.h>
#include <ros/ros.h>
#include <sensor_msgs/CameraInfo.h>
#include <stereo_msgs/DisparityImage.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_broadcaster.h>
#include <tf2_ros/transform_listener.h>

#include "biovision_memory/landmark_corrector.hpp"
#include "biovision_memory/long_term_memory.hpp"
#include "biovision_memory/memory_database.hpp"
#include "biovision_memory/object_memory.hpp"
#include "biovision_memory/short_term_memory.hpp"
#include "biovision_ros_common/lazy_nodelet.hpp"
#include "biovision_ros_common/nodelet_diagnostics.hpp"

namespace biovision_memory
{
/// The `memory` nodelet (thesis §5.3): the short-term memory from `disparity` (published as `memory/stm`
/// at the disparity rate), the long-term map and the object/landmark memory in `map` (persisted in
/// SQLite), and `map → odom` corrected from fixed landmarks. Topics, services and parameters: README.
/// Frames come from tf (head pan and tilt through base_link → the disparity's optical frame; the base's
/// pose through odom → base_link). Bad input (missing tf, unusable disparity) is skipped with a throttled
/// error and an ERROR diagnostic; without disparity the STM ages out (diagnostics say so). Time going
/// backwards resets the STM and the landmark window and clamps the memories' time tags.
class MemoryNodelet : public biovision_ros_common::LazyNodelet
{
public:
  /// Writes what is not yet saved.
  ~MemoryNodelet() override;

  /// All parameters read from ~ (config/memory.yaml).
  struct Settings
  {
    std::string map_frame = "map";
    std::string odom_frame = "odom";
    std::string base_frame = "base_link";
    std::string database;  ///< SQLite file; "" = no persistence
    bool start_empty_on_bad_database = false;
    bool start_empty = false;        // forget what the database holds at start (a new mission)
    double save_period = 5.0;        ///< [s] wall time between database transactions
    double ltm_period = 0.5;         ///< [s] ROS time between LTM updates (one reinforcement per period)
    double publish_period = 1.0;     ///< [s] between memory/ltm and memory/ltm_items
    double disparity_timeout = 1.0;  ///< [s] without disparity the STM is ageing (diagnostics)
    double tf_timeout = 0.1;         ///< [s] waiting for a transform at the disparity's stamp
    bool landmark_correction = true;
    bool publish_map_to_odom = true;
    double map_to_odom_rate = 10.0;  ///< [Hz]
  };

  /// Reads Settings and the core parameter structs from `pnh` (names as in config/memory.yaml).
  /// Throws std::invalid_argument naming the parameter when one is out of range.
  static void readParameters(const ros::NodeHandle& pnh, Settings& settings, ShortTermMemoryParameters& stm,
                             LongTermMemoryParameters& ltm, ObjectMemoryParameters& objects,
                             LandmarkCorrectorParameters& corrector);

private:
  void onInitNodelet() override;
  void subscribe() override;
  void unsubscribe() override;

  void onDisparity(const stereo_msgs::DisparityImageConstPtr& msg);
  void onCameraInfo(const sensor_msgs::CameraInfoConstPtr& msg);
  void onObjects(const biovision_msgs::RecognizedObjectArrayConstPtr& msg);
  void onTimer(const ros::WallTimerEvent&);
  void onMapToOdomTimer(const ros::TimerEvent&);
  bool onList(biovision_msgs::ListMemoryObjects::Request&, biovision_msgs::ListMemoryObjects::Response& res);
  /// One remembered object as an LtmItem (kind "object" or "landmark"), for memory/ltm_items and the list service.
  biovision_msgs::LtmItem objectItem(const std::string& label, const ObjectMemory::Object& o, uint32_t id) const;
  bool onQuery(biovision_msgs::QueryObject::Request& req, biovision_msgs::QueryObject::Response& res);
  bool onForget(biovision_msgs::ForgetObject::Request& req, biovision_msgs::ForgetObject::Response& res);
  void onTimeJumpBack();

  bool lookup(const std::string& target, const std::string& source, const ros::Time& stamp, Eigen::Isometry3d& out,
              std::string& error);
  void publishStm(const ros::Time& stamp);
  void publishLtm(const ros::Time& stamp);
  void save();
  void details(diagnostic_updater::DiagnosticStatusWrapper& s);

  Settings settings_;
  std::mutex mutex_;  // the memories and the state below
  std::unique_ptr<ShortTermMemory> stm_;
  std::unique_ptr<LongTermMemory> ltm_;
  std::unique_ptr<ObjectMemory> objects_;
  std::unique_ptr<LandmarkCorrector> corrector_;
  std::unique_ptr<MemoryDatabase> database_;
  std::string last_save_error_;
  ros::Time last_disparity_, last_ltm_update_, last_publish_;
  ros::WallTime last_disparity_wall_, last_save_;
  Pose2D odom_pose_{NAN, NAN, NAN};  // base_link in odom at the last STM move (NaN: none yet)
  bool have_camera_info_ = false;
  sensor_msgs::CameraInfo camera_info_;
  unsigned frames_ = 0, tf_failures_ = 0, sightings_ = 0, far_sightings_ = 0, landmark_sightings_ = 0;

  std::unique_ptr<tf2_ros::Buffer> tf_buffer_;
  std::unique_ptr<tf2_ros::TransformListener> tf_listener_;
  std::unique_ptr<tf2_ros::TransformBroadcaster> tf_broadcaster_;
  ros::Subscriber disparity_sub_, info_sub_, objects_sub_;
  ros::Publisher stm_pub_, stm_markers_pub_, ltm_pub_, items_pub_, ltm_markers_pub_;
  ros::ServiceServer list_srv_, query_srv_, forget_srv_;
  ros::WallTimer timer_;
  ros::Timer map_to_odom_timer_;
  ros::Time map_to_odom_stamp_;  // of the last map -> odom sent (the timer's thread only)
  biovision_ros_common::NodeletDiagnostics diagnostics_;
};
}  // namespace biovision_memory
