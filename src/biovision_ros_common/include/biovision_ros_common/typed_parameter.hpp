#pragma once

#include <stdexcept>
#include <string>

#include <ros/ros.h>
#include <xmlrpcpp/XmlRpcValue.h>

namespace biovision_ros_common
{
/// XmlRpc's name of a parameter value's type ("int", "string", ...), for error messages.
inline std::string xmlRpcTypeName(const XmlRpc::XmlRpcValue& v)
{
  switch (v.getType())
  {
    case XmlRpc::XmlRpcValue::TypeBoolean:
      return "bool";
    case XmlRpc::XmlRpcValue::TypeInt:
      return "int";
    case XmlRpc::XmlRpcValue::TypeDouble:
      return "double";
    case XmlRpc::XmlRpcValue::TypeString:
      return "string";
    case XmlRpc::XmlRpcValue::TypeArray:
      return "list";
    case XmlRpc::XmlRpcValue::TypeStruct:
      return "dictionary";
    default:
      return "other";
  }
}

/// Reads the private parameter `name` into `value` when it is set and leaves `value` (the default) when it
/// is not. Throws std::invalid_argument naming the parameter when it is set with a type that does not
/// convert (a string for a number, a number for a string; roscpp reads an int as a double): NodeHandle::
/// param() silently keeps the default there, and a driver told `_port:=123` opened /dev/ttyUSB0.
template <typename T>
void readTypedParameter(const ros::NodeHandle& pnh, const std::string& name, T& value)
{
  if (!pnh.hasParam(name))
    return;
  T read{};
  if (!pnh.getParam(name, read))
  {
    XmlRpc::XmlRpcValue raw;
    pnh.getParam(name, raw);
    throw std::invalid_argument(pnh.resolveName(name) + " holds a value of type " + xmlRpcTypeName(raw) +
                                ", not the type this parameter needs");
  }
  value = read;
}
}  // namespace biovision_ros_common
