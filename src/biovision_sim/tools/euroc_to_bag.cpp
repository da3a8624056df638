// euroc_to_bag: a folder of real stereo pairs in the EuRoC layout (mav0/cam0/data, cam1/data, data.csv,
// sensor.yaml) -> a ROS bag of raw images with camera_info that rectifies them (stereo_image_proc's
// rectify nodelets produce a row-aligned pair from it).
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>

#include <cv_bridge/cv_bridge.h>
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <rosbag/bag.h>
#include <sensor_msgs/CameraInfo.h>

#include "biovision_common/tool_options.hpp"

namespace
{
struct Camera
{
  cv::Mat K, D;  // 3x3, 1x4 (radial-tangential = plumb_bob k1 k2 p1 p2)
  cv::Mat T_BS;  // 4x4 body <- sensor
  cv::Size size;
};

Camera readSensor(const std::string& path)
{
  cv::FileStorage fs(path, cv::FileStorage::READ);
  if (!fs.isOpened())
    throw std::runtime_error("cannot read " + path);
  Camera c;
  std::vector<double> intr, dist, tbs, res;
  fs["intrinsics"] >> intr;
  fs["distortion_coefficients"] >> dist;
  fs["T_BS"]["data"] >> tbs;
  fs["resolution"] >> res;
  if (intr.size() != 4 || dist.size() != 4 || tbs.size() != 16 || res.size() != 2)
    throw std::runtime_error(path + ": needs intrinsics[4], distortion_coefficients[4], T_BS.data[16], resolution[2]");
  c.K = (cv::Mat_<double>(3, 3) << intr[0], 0, intr[2], 0, intr[1], intr[3], 0, 0, 1);
  c.D = cv::Mat(dist).reshape(1, 1).clone();
  c.T_BS = cv::Mat(tbs).reshape(1, 4).clone();
  c.size = cv::Size(static_cast<int>(res[0]), static_cast<int>(res[1]));
  return c;
}

sensor_msgs::CameraInfo info(const Camera& c, const cv::Mat& R, const cv::Mat& P, const std::string& frame)
{
  sensor_msgs::CameraInfo m;
  m.header.frame_id = frame;
  m.width = c.size.width;
  m.height = c.size.height;
  m.distortion_model = "plumb_bob";
  m.D = {c.D.at<double>(0), c.D.at<double>(1), c.D.at<double>(2), c.D.at<double>(3), 0.0};
  for (int i = 0; i < 9; ++i)
  {
    m.K[i] = c.K.at<double>(i / 3, i % 3);
    m.R[i] = R.at<double>(i / 3, i % 3);
  }
  for (int i = 0; i < 12; ++i)
    m.P[i] = P.at<double>(i / 4, i % 4);
  return m;
}
}  // namespace

int main(int argc, char** argv)
{
  std::string dataset, output, frame = "stereo_left_optical";
  biovision_common::ToolOptions options(
      "euroc_to_bag",
      "Pairs listed in cam0/data.csv whose images exist in both cam0/data and cam1/data are written as\n"
      "stereo/{left,right}/image_raw (mono8) + camera_info with the stereo rectification (cv::stereoRectify of\n"
      "the sensor.yaml intrinsics, distortion and extrinsics).");
  options.app().add_option("--dataset", dataset, "EuRoC folder DIR/mav0")->required();
  options.app().add_option("--output", output, "bag file to write")->required();
  options.app().add_option("--frame", frame, "frame_id of images and camera_info");
  options.parse(argc, argv);
  try
  {
    const Camera c0 = readSensor(dataset + "/cam0/sensor.yaml"), c1 = readSensor(dataset + "/cam1/sensor.yaml");
    if (c0.size != c1.size)
      throw std::runtime_error("cam0 and cam1 resolutions differ");
    // cam0 -> cam1 transform: T_c1_c0 = inv(T_B_c1) * T_B_c0.
    const cv::Mat T = c1.T_BS.inv() * c0.T_BS;
    const cv::Mat R = T(cv::Rect(0, 0, 3, 3)).clone(), t = T(cv::Rect(3, 0, 1, 3)).clone();
    cv::Mat R0, R1, P0, P1, Q;
    cv::stereoRectify(c0.K, c0.D, c1.K, c1.D, c0.size, R, t, R0, R1, P0, P1, Q, cv::CALIB_ZERO_DISPARITY, 0);
    const auto info0 = info(c0, R0, P0, frame), info1 = info(c1, R1, P1, frame);
    std::ifstream csv(dataset + "/cam0/data.csv");
    if (!csv)
      throw std::runtime_error("cannot read " + dataset + "/cam0/data.csv");
    rosbag::Bag bag(output, rosbag::bagmode::Write);
    std::string line;
    int pairs = 0, not_shipped = 0;
    while (std::getline(csv, line))
    {
      if (line.empty() || line[0] == '#')
        continue;
      std::stringstream row(line);
      std::string ns, file;
      if (!std::getline(row, ns, ',') || !std::getline(row, file))
        continue;
      file.erase(file.find_last_not_of(" \r\n") + 1);
      // Listed but not shipped (the micro set has the first 20 of 95): counted, not read (imread would log
      // an error for each).
      const std::string left_file = dataset + "/cam0/data/" + file, right_file = dataset + "/cam1/data/" + file;
      if (!std::filesystem::exists(left_file) || !std::filesystem::exists(right_file))
      {
        ++not_shipped;
        continue;
      }
      const cv::Mat left = cv::imread(left_file, cv::IMREAD_GRAYSCALE);
      const cv::Mat right = cv::imread(right_file, cv::IMREAD_GRAYSCALE);
      if (left.empty() || right.empty())
        throw std::runtime_error("cannot decode " + (left.empty() ? left_file : right_file));
      ros::Time stamp;
      stamp.fromNSec(std::stoull(ns));
      std_msgs::Header h;
      h.stamp = stamp;
      h.frame_id = frame;
      auto l = info0, r = info1;
      l.header = r.header = h;
      bag.write("/stereo/left/image_raw", stamp, cv_bridge::CvImage(h, "mono8", left).toImageMsg());
      bag.write("/stereo/right/image_raw", stamp, cv_bridge::CvImage(h, "mono8", right).toImageMsg());
      bag.write("/stereo/left/camera_info", stamp, l);
      bag.write("/stereo/right/camera_info", stamp, r);
      ++pairs;
    }
    bag.close();
    std::printf(
        "euroc_to_bag: %d pairs (%d listed frames not in the data set), baseline %.4f m, rectified fx "
        "%.1f -> %s\n",
        pairs, not_shipped, -P1.at<double>(0, 3) / P1.at<double>(0, 0), P0.at<double>(0, 0), output.c_str());
    return pairs > 0 ? 0 : 1;
  }
  catch (const std::exception& e)
  {
    std::cerr << "euroc_to_bag: " << e.what() << "\n";
    return 1;
  }
}
