#include "biovision_ros_common/lazy_nodelet.hpp"

#include <exception>

namespace biovision_ros_common
{
void LazyNodelet::onInit()
{
  getPrivateNodeHandle().param("lazy", lazy_, true);
  {
    // Connection callbacks may fire during advertising; they wait until the outputs are all known.
    std::lock_guard<std::mutex> lock(connection_mutex_);
    try
    {
      onInitNodelet();
    }
    catch (const std::exception& e)
    {
      // The nodelet loader turns an exception here into exit status 1 without a word: say why.
      NODELET_FATAL("cannot start: %s", e.what());
      throw;
    }
    initialised_ = true;
  }
  connectionChanged();
}

image_transport::Publisher LazyNodelet::advertiseImage(image_transport::ImageTransport& it, const std::string& topic,
                                                       uint32_t queue_size)
{
  auto cb = [this](const image_transport::SingleSubscriberPublisher&) { connectionChanged(); };
  image_transport::Publisher p = it.advertise(topic, queue_size, image_transport::SubscriberStatusCallback(cb),
                                              image_transport::SubscriberStatusCallback(cb));
  image_publishers_.push_back(p);
  return p;
}

image_transport::TransportHints LazyNodelet::imageHints()
{
  return image_transport::TransportHints("raw", ros::TransportHints(), getPrivateNodeHandle());
}

bool LazyNodelet::anyListener() const
{
  for (const auto& p : publishers_)
    if (p.getNumSubscribers() > 0)
      return true;
  for (const auto& p : image_publishers_)
    if (p.getNumSubscribers() > 0)
      return true;
  return false;
}

void LazyNodelet::setBusy(bool busy)
{
  if (busy_.exchange(busy) != busy)
    connectionChanged();
}

void LazyNodelet::connectionChanged()
{
  std::lock_guard<std::mutex> lock(connection_mutex_);
  if (!initialised_)
    return;
  const bool wanted = !lazy_ || busy_ || anyListener();
  if (wanted && !subscribed_)
  {
    NODELET_DEBUG("a listener came (or work started): subscribing to the inputs");
    subscribe();
    subscribed_ = true;
  }
  else if (!wanted && subscribed_)
  {
    NODELET_DEBUG("no listeners and no work: unsubscribing from the inputs");
    unsubscribe();
    subscribed_ = false;
  }
}
}  // namespace biovision_ros_common
