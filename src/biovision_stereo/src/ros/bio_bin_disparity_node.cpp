// Standalone node: loads the BioBinDisparityNodelet in its own process.
#include <nodelet/loader.h>
#include <ros/ros.h>

int main(int argc, char** argv)
{
  ros::init(argc, argv, "biobin_disparity");
  nodelet::Loader loader;
  const nodelet::M_string remappings(ros::names::getRemappings());
  if (!loader.load(ros::this_node::getName(), "biovision_stereo/BioBinDisparityNodelet", remappings, nodelet::V_string()))
    return 1;
  ros::spin();
  return 0;
}
