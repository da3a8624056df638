#pragma once

#include <deque>
#include <memory>
#include <mutex>
#include <string>

#include <biovision_msgs/ForgetObject.h>
#include <biovision_msgs/LearnObject.h>
#include <biovision_msgs/ListObjects.h>
#include <biovision_msgs/RecognizedObjectArray.h>
#include <biovision_msgs/SalientRegionArray.h>
#include <biovision_recognition/RecognitionConfig.h>
#include <boost/thread/recursive_mutex.hpp>
#include <dynamic_reconfigure/server.h>
#include <image_transport/image_transport.h>
#include <nodelet/nodelet.h>
#include <ros/ros.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/RegionOfInterest.h>
#include <stereo_msgs/DisparityImage.h>

#include "biovision_recognition/object_recognizer.hpp"
#include "biovision_ros_common/lazy_nodelet.hpp"
#include "biovision_ros_common/nodelet_diagnostics.hpp"
#include "biovision_ros_common/stamped_history.hpp"

namespace biovision_recognition
{
/// ROS wrapper of ObjectRecognizer. For every `image` (the left camera) it looks in the latest
/// `saliency/regions` (when recent; else the whole image) and publishes `objects`
/// (biovision_msgs/RecognizedObjectArray) and, while watched, `recognition/debug_image`. With a recent
/// `disparity` and `camera_info` each object also gets its position in the camera frame, from the
/// disparity map of the image's own instant: while stereo runs, an image's objects wait for it (up to
/// `~max_disparity_wait`, or until a later map shows it was skipped; then the nearest one), in order. Services
/// `recognition/learn_object`, `recognition/forget_object`, `recognition/list_objects` edit the object
/// memory at run time; `~memory_file` is loaded at start and rewritten (atomically) after every edit.
class RecognitionNodelet : public biovision_ros_common::LazyNodelet
{
private:
  void onInitNodelet() override;
  void subscribe() override;
  void unsubscribe() override;
  void imageCallback(const sensor_msgs::ImageConstPtr& msg);
  void regionsCallback(const biovision_msgs::SalientRegionArrayConstPtr& msg);
  void disparityCallback(const stereo_msgs::DisparityImageConstPtr& msg);
  void infoCallback(const sensor_msgs::CameraInfoConstPtr& msg);
  bool learn(biovision_msgs::LearnObject::Request& req, biovision_msgs::LearnObject::Response& res);
  bool forget(biovision_msgs::ForgetObject::Request& req, biovision_msgs::ForgetObject::Response& res);
  bool list(biovision_msgs::ListObjects::Request& req, biovision_msgs::ListObjects::Response& res);
  void reconfigure(RecognitionConfig& config, uint32_t level);
  void details(diagnostic_updater::DiagnosticStatusWrapper& status);
  /// Loads ~memory_file after removing stale temporaries; a refused file is kept aside (never overwritten)
  /// and the node starts empty, saying where the file went in the log and diagnostics.
  void loadMemory();
  bool saveMemory(std::string& error);
  /// Why a learn box cannot be used ("" when it can): zero-area, under kMinBoxSide, or outside the image.
  static std::string boxProblem(const sensor_msgs::RegionOfInterest& box, const cv::Size& image);
  static constexpr uint32_t kMinBoxSide = 8;  ///< [px]: the smallest region ObjectRecognizer::describe takes
  /// A recognised image whose objects wait for the disparity map of the same instant.
  struct PendingObjects
  {
    biovision_msgs::RecognizedObjectArray message;  ///< positions not yet filled
    std::vector<RecognizedObject> found;            ///< the same objects, with their match points
    cv::Size image_size;
    ros::WallTime since;  ///< wall clock: a jump of ROS time (looped bag) never strands one
  };
  /// Publishes the pending objects, oldest first, as far as their disparity is settled: the map stamped
  /// like their image; or, once that cannot come (a later map arrived, stereo not running, waited
  /// max_disparity_wait_, too many pending, or `flush`), the nearest within max_input_age_ (or none).
  /// Call with state_mutex_ held.
  void releasePending(bool flush);
  /// Each pending object's box centre in the camera frame at its matches' disparity (ObjectLocator), from
  /// one conversion of `disparity`; objects without data keep has_position false. Counts where each depth
  /// came from, for diagnostics.
  void locate(const stereo_msgs::DisparityImage& disparity, PendingObjects& pending);

  std::unique_ptr<image_transport::ImageTransport> it_;
  image_transport::Subscriber image_sub_;
  ros::Subscriber regions_sub_, disparity_sub_, info_sub_;
  ros::Publisher objects_pub_;
  image_transport::Publisher debug_pub_;
  ros::ServiceServer learn_srv_, forget_srv_, list_srv_;

  std::mutex state_mutex_;  // recogniser, memory and the latest inputs
  std::unique_ptr<ObjectRecognizer> recognizer_;
  std::unique_ptr<ObjectMemory> memory_;
  std::string memory_file_;
  std::string refused_copy_, refusal_;  // where a memory refused at start went, and why
  std::string save_blocked_;            // why nothing may be saved (a refused file that could not be moved)
  int max_regions_ = 3;
  double max_input_age_ = 0.5;
  size_t max_input_pixels_ = 0;  // ~max_input_pixels: larger images are refused (bounded memory per frame)
  /// The last images recognised (grey, with their stamps), newest last: learn_object takes the one its
  /// request names, so a box projected for that instant is cut from that image even after the head moved.
  std::deque<std::pair<ros::Time, cv::Mat>> recent_gray_;
  static constexpr size_t kRecentImages = 8;
  biovision_msgs::SalientRegionArrayConstPtr regions_;
  /// The last disparity maps (shared, not copied): an image is located with the one of its own instant.
  biovision_ros_common::StampedHistory<stereo_msgs::DisparityImage> disparities_{4};  // = the subscriber's queue
  std::deque<PendingObjects> pending_;
  static constexpr size_t kMaxPending = 8;  ///< bounds the queue if stereo stalls without a time-out firing
  double max_disparity_wait_ = 0.3;         ///< ~max_disparity_wait [s] (wall clock); 0: never wait
  ros::WallTimer pending_timer_;            ///< releases what waited max_disparity_wait_ when no input comes
  sensor_msgs::CameraInfoConstPtr info_;

  boost::recursive_mutex reconfigure_mutex_;  // dynamic_reconfigure::Server takes a boost mutex; outlives it
  std::unique_ptr<dynamic_reconfigure::Server<RecognitionConfig>> reconfigure_server_;
  biovision_ros_common::NodeletDiagnostics diagnostics_;
  ObjectRecognizer::Statistics last_stats_;
  long regions_total_ = 0, spectra_built_total_ = 0;  // since start: how often a region size missed the cache
  size_t last_objects_ = 0;
  long located_at_matches_ = 0, located_by_box_ = 0;  // positions by ObjectLocator::Source, since start
  long own_disparity_ = 0, other_disparity_ = 0;      // images located with their own / a nearby map
  std::string model_id_;
};
}  // namespace biovision_recognition
