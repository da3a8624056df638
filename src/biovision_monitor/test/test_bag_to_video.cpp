// bag_to_video on a small bag written here: the video has one panel frame per 1/fps of bag time plus the
// last, at the panel's size, and the head attractor tile holds its plot.
#include <cstdio>
#include <cstdlib>
#include <string>

#include <biovision_msgs/AttractorState.h>
#include <gtest/gtest.h>
#include <opencv2/videoio.hpp>
#include <rosbag/bag.h>

TEST(BagToVideo, OneFramePerStepAtThePanelsSize)
{
  const std::string bag_path = "/tmp/test_bag_to_video.bag", video = "/tmp/test_bag_to_video.avi";
  {
    rosbag::Bag bag(bag_path, rosbag::bagmode::Write);
    for (int k = 0; k <= 20; ++k)  // 2 s at 10 Hz
    {
      biovision_msgs::AttractorState s;
      s.controller = "head_pan";
      for (int i = 0; i < 9; ++i)
      {
        s.section_angles.push_back(float((-80 + 20 * i) * M_PI / 180));
        s.attraction.push_back(i == 4 ? 1.0f : 0.0f);
        s.repulsion.push_back(0.0f);
      }
      s.angle = 0.05f * k;
      bag.write("/attractor/head", ros::Time(100.0 + 0.1 * k), s);
    }
  }
  const std::string command = std::string(BAG_TO_VIDEO) + " " + bag_path + " " + video +
                              " --fps 5 --json /tmp/test_bag_to_video.json";
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  cv::VideoCapture capture(video);
  ASSERT_TRUE(capture.isOpened());
  int frames = 0;
  cv::Mat frame, last;
  while (capture.read(frame))
  {
    ++frames;
    last = frame.clone();
  }
  EXPECT_EQ(frames, 11);  // 0, 0.2, ..., 1.8 s and the end (2.0 s)
  ASSERT_FALSE(last.empty());
  EXPECT_EQ(last.cols, 4 * 320 + 3 * 2);
  EXPECT_EQ(last.rows, 2 * 240 + 2);
  // Tile 6 (head attractor, second row, third column): the plot's white background (MJPG: near white).
  const cv::Vec3b p = last.at<cv::Vec3b>(242 + 200, 2 * 322 + 160);
  EXPECT_GT(p[0] + p[1] + p[2], 600);
  // Tile 7 (STM, no data): the dark "no data" tile.
  const cv::Vec3b q = last.at<cv::Vec3b>(242 + 200, 3 * 322 + 20);
  EXPECT_LT(q[0] + q[1] + q[2], 300);
  EXPECT_NE(std::system((std::string(BAG_TO_VIDEO) + " /nonexistent.bag /tmp/x.avi 2>/dev/null").c_str()), 0);
  std::remove(bag_path.c_str());
  std::remove(video.c_str());
  std::remove("/tmp/test_bag_to_video.json");
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
