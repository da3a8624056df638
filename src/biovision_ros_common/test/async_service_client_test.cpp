// AsyncServiceClient against real servers on a real roscore: an answer arrives, a server that never
// answers is given up after the time-out without blocking the caller, its connection dropped so that no
// thread is left waiting and later calls still start, a missing server is reported as such.
#include <optional>

#include <gtest/gtest.h>
#include <ros/ros.h>
#include <roscpp/Empty.h>

#include "biovision_ros_common/async_service_client.hpp"
#include "biovision_ros_common/rostest_helpers.hpp"

using biovision_ros_common::AsyncServiceClient;
using HangingServer = biovision_ros_common::HangingServiceServer<roscpp::Empty>;
using biovision_ros_common::waitFor;
using Client = AsyncServiceClient<roscpp::Empty>;

namespace
{
bool answerAtOnce(roscpp::Empty::Request&, roscpp::Empty::Response&)
{
  return true;
}
}  // namespace

TEST(AsyncServiceClient, DeliversTheAnswerOnce)
{
  ros::NodeHandle nh;
  ros::ServiceServer server = nh.advertiseService("answers", answerAtOnce);
  Client client(nh, "answers", 5.0);
  EXPECT_FALSE(client.take());  // nothing called yet
  ASSERT_TRUE(client.start(roscpp::Empty::Request()));
  std::optional<Client::Result> r;
  ASSERT_TRUE(waitFor([&] { return bool(r = client.take()); }, 5.0));
  EXPECT_TRUE(r->answered);
  EXPECT_FALSE(r->timed_out);
  EXPECT_FALSE(client.take());  // handed out once
  EXPECT_FALSE(client.busy());
}

TEST(AsyncServiceClient, GivesUpOnAServerThatNeverAnswersWithoutBlockingTheCaller)
{
  ros::NodeHandle nh;
  HangingServer server("hangs");
  Client client(nh, "hangs", 0.5, 2);
  ASSERT_TRUE(client.start(roscpp::Empty::Request()));
  // start() came back while the server holds the call: the caller did not wait for it.
  ASSERT_TRUE(waitFor([&] { return server.entered() == 1; }, 5.0));
  EXPECT_TRUE(client.busy());
  EXPECT_FALSE(client.start(roscpp::Empty::Request()));  // one call at a time
  EXPECT_FALSE(client.take());
  std::optional<Client::Result> r;
  ASSERT_TRUE(waitFor([&] { return bool(r = client.take()); }, 5.0));
  EXPECT_FALSE(r->answered);
  EXPECT_TRUE(r->timed_out);
  EXPECT_LE(client.abandoned(), 1);

  // The given-up call's connection is dropped, so roscpp returns it: no thread is left waiting, and calls to
  // a server that still holds every call keep starting and timing out (no lock-out).
  ASSERT_TRUE(waitFor([&] { return client.abandoned() == 0; }, 5.0));
  for (int i = 0; i < 5; ++i)
  {
    ASSERT_TRUE(client.start(roscpp::Empty::Request())) << "call " << i;
    ASSERT_TRUE(waitFor([&] { return bool(r = client.take()); }, 5.0));
    EXPECT_TRUE(r->timed_out);
    ASSERT_TRUE(waitFor([&] { return client.abandoned() == 0; }, 5.0)) << "call " << i;
  }

  // Once the server lets go, calls are answered again (the held ones' late answers never reach take()).
  server.release();
  EXPECT_FALSE(client.take());
  ASSERT_TRUE(client.start(roscpp::Empty::Request()));
  ASSERT_TRUE(waitFor([&] { return bool(r = client.take()); }, 5.0));
  EXPECT_TRUE(r->answered);
}

TEST(AsyncServiceClient, ReportsAMissingServer)
{
  ros::NodeHandle nh;
  Client client(nh, "nobody_serves_this", 5.0);
  ASSERT_TRUE(client.start(roscpp::Empty::Request()));
  std::optional<Client::Result> r;
  ASSERT_TRUE(waitFor([&] { return bool(r = client.take()); }, 5.0));
  EXPECT_FALSE(r->answered);
  EXPECT_FALSE(r->timed_out);
}

TEST(AsyncServiceClient, RefusesANonPositiveTimeout)
{
  ros::NodeHandle nh;
  EXPECT_THROW(Client(nh, "x", 0.0), std::invalid_argument);
  EXPECT_THROW(Client(nh, "x", 1.0, 0), std::invalid_argument);
}

int main(int argc, char** argv)
{
  return biovision_ros_common::RosTestRun(argc, argv, "async_service_client_test", 2).run();
}
