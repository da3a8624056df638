// sim: the simulated BioVision robot in a textured world (biovision_sim::Simulator).
#include <ros/ros.h>

#include "biovision_sim/ros/simulator.hpp"

int main(int argc, char** argv)
{
  ros::init(argc, argv, "sim");
  ros::NodeHandle nh, private_nh("~");
  try
  {
    biovision_sim::Simulator simulator(nh, private_nh);
    simulator.run();
  }
  catch (const std::exception& e)
  {
    ROS_FATAL("sim: %s", e.what());
    return 1;
  }
  return 0;
}
