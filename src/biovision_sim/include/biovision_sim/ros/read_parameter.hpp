#pragma once

#include <stdexcept>
#include <string>

#include <ros/node_handle.h>

namespace biovision_sim
{
/// Reads the private parameter `name` into `value` when it is set; when unset, `value` keeps the
/// default it holds (so each default is written once, in the parameter struct). Throws
/// std::invalid_argument naming the parameter when it is set with a type that does not convert to T.
template <typename T>
void readParameter(const ros::NodeHandle& private_nh, const std::string& name, T& value)
{
  if (private_nh.hasParam(name) && !private_nh.getParam(name, value))
    throw std::invalid_argument("parameter ~" + name + " has the wrong type");
}
}  // namespace biovision_sim
