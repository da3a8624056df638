#pragma once

#include <algorithm>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <ros/ros.h>

namespace biovision_ros_common
{
/// A ROS service client whose calls never block the caller: each call runs on a thread of its own and
/// the caller polls for the answer (a control loop's timer, say).
///
/// Why: roscpp's ServiceClient::call() has no time-out. A server that accepted the connection and never
/// answers blocks the caller for good. In `make demo` (2026-12-05) the task manager's first head/set_mode
/// call hung that way (the head controller's end of the socket was left without an owner) inside the
/// task manager's step, under its lock: no task status, no goal, the mission never began.
///
/// A call not answered within `timeout` (wall seconds) is given up: take() reports it as timed out, its
/// connection is dropped (each call has a persistent client of its own, so shutting that client down
/// closes the connection and roscpp returns the call) and the next start() opens a new connection. Should
/// roscpp still hold a given-up call, at most `max_abandoned` such threads wait; then start() refuses until
/// one ends (bounded threads whatever the server does).
/// Thread-safe; neither copyable nor movable (hold it by pointer).
template <class Service>
class AsyncServiceClient
{
public:
  using Request = typename Service::Request;
  using Response = typename Service::Response;

  /// What became of a call.
  struct Result
  {
    bool answered = false;   ///< the server answered (its response says whether it succeeded)
    bool timed_out = false;  ///< no answer within the time-out (false with !answered: no server, or it dropped)
    Response response;       ///< valid when answered
  };

  /// `service`: resolved in `nh`; `timeout` > 0 [wall s]; `max_abandoned` >= 1 calls left waiting at most.
  AsyncServiceClient(const ros::NodeHandle& nh, const std::string& service, double timeout, int max_abandoned = 4)
    : nh_(nh), service_(service), timeout_(timeout), max_abandoned_(max_abandoned)
  {
    if (!(timeout > 0) || max_abandoned < 1)
      throw std::invalid_argument("AsyncServiceClient: timeout must be > 0 and max_abandoned >= 1");
  }

  /// Starts a call with `request`. False (nothing started) while the previous call is still waiting for
  /// its answer within the time-out, or while max_abandoned calls are left waiting.
  bool start(const Request& request)
  {
    std::lock_guard<std::mutex> lock(mutex_);
    expire();
    if ((current_ && !current_->done()) || static_cast<int>(abandoned_.size()) >= max_abandoned_)
      return false;
    auto call = std::make_shared<Call>();
    call->started = ros::WallTime::now();
    // Persistent: its own connection, which shutdown() drops when the call is given up.
    call->client = nh_.serviceClient<Service>(service_, true);
    std::thread([call, client = call->client, request]() mutable {
      Service srv;
      srv.request = request;
      const bool answered = client.call(srv);
      call->finish(answered, srv.response);
    }).detach();
    current_ = call;
    return true;
  }

  /// True while a call waits for its answer within the time-out.
  bool busy()
  {
    std::lock_guard<std::mutex> lock(mutex_);
    expire();
    return current_ && !current_->done();
  }

  /// The outcome of the last call once it is known (answered, failed or timed out); handed out once.
  std::optional<Result> take()
  {
    std::lock_guard<std::mutex> lock(mutex_);
    expire();
    if (!current_ || !current_->done())
      return std::nullopt;
    Result r = current_->result();
    current_.reset();
    return r;
  }

  /// Calls given up on whose threads still wait for roscpp.
  int abandoned()
  {
    std::lock_guard<std::mutex> lock(mutex_);
    expire();
    return static_cast<int>(abandoned_.size());
  }

  const std::string& service() const { return service_; }
  double timeout() const { return timeout_; }

private:
  struct Call
  {
    ros::WallTime started;
    ros::ServiceClient client;
    std::mutex m;
    bool finished = false, gave_up = false;
    Result r;

    void finish(bool answered, const Response& response)
    {
      std::lock_guard<std::mutex> lock(m);
      finished = true;
      if (!gave_up)
      {
        r.answered = answered;
        r.response = response;
      }
    }
    bool done()
    {
      std::lock_guard<std::mutex> lock(m);
      return finished || gave_up;
    }
    bool running()
    {
      std::lock_guard<std::mutex> lock(m);
      return !finished;
    }
    Result result()
    {
      std::lock_guard<std::mutex> lock(m);
      return r;
    }
  };

  // Under mutex_: the current call past its time-out is given up (its result says so); finished
  // abandoned calls are forgotten.
  void expire()
  {
    if (current_ && (ros::WallTime::now() - current_->started).toSec() > timeout_)
    {
      bool give_up = false;
      {
        std::lock_guard<std::mutex> lock(current_->m);
        if (!current_->finished && !current_->gave_up)
        {
          give_up = current_->gave_up = true;
          current_->r.timed_out = true;
        }
      }
      if (give_up)
      {
        abandoned_.push_back(current_);
        current_->client.shutdown();  // drops the connection: roscpp returns the call (as failed)
      }
    }
    abandoned_.erase(std::remove_if(abandoned_.begin(), abandoned_.end(),
                                    [](const std::shared_ptr<Call>& c) { return !c->running(); }),
                     abandoned_.end());
  }

  ros::NodeHandle nh_;
  std::string service_;
  double timeout_ = 2.0;
  int max_abandoned_ = 4;
  std::mutex mutex_;
  std::shared_ptr<Call> current_;
  std::vector<std::shared_ptr<Call>> abandoned_;
};
}  // namespace biovision_ros_common
