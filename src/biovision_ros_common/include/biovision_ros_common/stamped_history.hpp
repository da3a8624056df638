#pragma once

#include <cmath>
#include <cstddef>
#include <deque>
#include <stdexcept>

#include <boost/shared_ptr.hpp>
#include <ros/time.h>

namespace biovision_ros_common
{
/// The last few messages of one input stream (shared pointers: no copies), newest last, so that a
/// consumer can pair another stream's message with the one of the same instant rather than the latest.
/// Inputs are taken to arrive in stamp order (one producer, as stereo and camera drivers publish): once
/// a message newer than `t` has arrived, one stamped `t` will not come. A stamp before the newest (a
/// looped bag, a restarted simulator) starts the history again. Not thread-safe. `Message` needs a
/// `header.stamp`.
template <class Message>
class StampedHistory
{
public:
  using ConstPtr = boost::shared_ptr<const Message>;

  /// Keeps at most `capacity` messages (>= 1; std::invalid_argument otherwise): memory stays bounded.
  explicit StampedHistory(std::size_t capacity) : capacity_(capacity)
  {
    if (capacity_ == 0)
      throw std::invalid_argument("StampedHistory: capacity must be at least 1");
  }

  /// Adds a message; a null one is ignored.
  void add(const ConstPtr& message)
  {
    if (!message)
      return;
    if (!messages_.empty() && message->header.stamp < messages_.back()->header.stamp)
      messages_.clear();
    messages_.push_back(message);
    while (messages_.size() > capacity_)
      messages_.pop_front();
  }

  void clear() { messages_.clear(); }
  bool empty() const { return messages_.empty(); }
  std::size_t size() const { return messages_.size(); }
  /// The newest message, or null.
  ConstPtr latest() const { return messages_.empty() ? ConstPtr() : messages_.back(); }

  /// The message stamped exactly `stamp`, or null.
  ConstPtr exact(const ros::Time& stamp) const
  {
    for (auto it = messages_.rbegin(); it != messages_.rend(); ++it)
      if ((*it)->header.stamp == stamp)
        return *it;
    return ConstPtr();
  }

  /// The message nearest in time to `stamp` and at most `max_age` [s] from it (the earlier one on a tie),
  /// or null.
  ConstPtr nearest(const ros::Time& stamp, double max_age) const
  {
    ConstPtr best;
    double best_gap = max_age;
    for (const ConstPtr& m : messages_)
    {
      const double gap = std::abs((m->header.stamp - stamp).toSec());
      if (gap < best_gap || (gap == best_gap && !best))
      {
        best = m;
        best_gap = gap;
      }
    }
    return best;
  }

  /// True once a message stamped after `stamp` has arrived: one stamped `stamp` will not come any more.
  bool passed(const ros::Time& stamp) const { return !messages_.empty() && messages_.back()->header.stamp > stamp; }

private:
  std::size_t capacity_;
  std::deque<ConstPtr> messages_;
};
}  // namespace biovision_ros_common
