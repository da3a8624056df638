#pragma once

#include <atomic>
#include <mutex>
#include <string>
#include <vector>

#include <image_transport/image_transport.h>
#include <nodelet/nodelet.h>
#include <ros/ros.h>

namespace biovision_ros_common
{
/// Base of every BioVision nodelet that processes a stream: it subscribes to its inputs only while
/// someone listens to one of its outputs (image_pipeline's connectCb pattern, factored as opencv_apps
/// does), so an idle graph costs nothing. With `~lazy: false` it subscribes at start and stays subscribed
/// (for outputs consumed by a service or a log rather than a subscriber).
///
/// Subclasses implement onInitNodelet() (advertise with advertise()/advertiseImage(), set up parameters),
/// subscribe() and unsubscribe(); those two run with the connection lock held.
class LazyNodelet : public nodelet::Nodelet
{
public:
  ~LazyNodelet() override = default;

protected:
  /// Called once by onInit(); advertise the outputs here. An exception thrown here stops the nodelet and is
  /// logged as FATAL with its what() (the nodelet loader itself exits 1 without a message).
  virtual void onInitNodelet() = 0;
  /// Subscribe to the inputs (first listener came, or ~lazy is false).
  virtual void subscribe() = 0;
  /// Shut the input subscriptions down (last listener left).
  virtual void unsubscribe() = 0;

  /// Advertises an output whose listeners decide whether the inputs are subscribed.
  template <typename Message>
  ros::Publisher advertise(ros::NodeHandle& nh, const std::string& topic, uint32_t queue_size, bool latch = false)
  {
    auto cb = [this](const ros::SingleSubscriberPublisher&) { connectionChanged(); };
    ros::Publisher p = nh.advertise<Message>(topic, queue_size, ros::SubscriberStatusCallback(cb),
                                             ros::SubscriberStatusCallback(cb), ros::VoidConstPtr(), latch);
    publishers_.push_back(p);
    return p;
  }
  image_transport::Publisher advertiseImage(image_transport::ImageTransport& it, const std::string& topic,
                                            uint32_t queue_size);

  /// True while the inputs are subscribed.
  bool isSubscribed() const { return subscribed_; }
  /// Keeps the inputs subscribed while `busy` though nobody listens to an output: a behaviour started
  /// by a service (hri/greet) needs its images whether or not its topics have subscribers. Takes the
  /// connection lock and may call subscribe()/unsubscribe(): call it without holding a lock an input
  /// callback takes (unsubscribing waits for a running callback).
  void setBusy(bool busy);
  /// Transport hints for image inputs: "raw", overridable per node by ~image_transport.
  image_transport::TransportHints imageHints();

private:
  void onInit() final;
  /// Compares the listeners of every advertised output with the subscription state.
  void connectionChanged();
  bool anyListener() const;

  std::mutex connection_mutex_;
  std::vector<ros::Publisher> publishers_;
  std::vector<image_transport::Publisher> image_publishers_;
  bool lazy_ = true;
  std::atomic<bool> busy_{false};
  bool initialised_ = false;
  bool subscribed_ = false;
};
}  // namespace biovision_ros_common
