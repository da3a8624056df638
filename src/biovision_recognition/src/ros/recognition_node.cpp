// Standalone node: loads the RecognitionNodelet in its own process.
#include <nodelet/loader.h>
#include <ros/ros.h>

int main(int argc, char** argv)
{
  ros::init(argc, argv, "recognition");
  nodelet::Loader loader;
  const nodelet::M_string remappings(ros::names::getRemappings());
  if (!loader.load(ros::this_node::getName(), "biovision_recognition/RecognitionNodelet", remappings, nodelet::V_string()))
    return 1;
  ros::spin();
  return 0;
}
