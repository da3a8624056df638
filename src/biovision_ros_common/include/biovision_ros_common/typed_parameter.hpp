#pragma once

#include <stdexcept>
#include <string>
#include <type_traits>

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

/// The parameter types a value of T may be given as, for error messages.
template <typename T>
std::string acceptedTypes()
{
  if constexpr (std::is_same_v<T, bool>)
    return "bool";
  else if constexpr (std::is_integral_v<T>)
    return "int";
  else if constexpr (std::is_floating_point_v<T>)
    return "double or int";
  else
    return "string";
}

/// Reads the private parameter `name` into `value` when it is set and leaves `value` (the default) when it
/// is not. Throws std::invalid_argument naming the parameter and the type it needs when it is set with a
/// type that does not fit: a string for a number, a number for a string, a double for an int (roscpp
/// would round it: `_pan_id:=1.6` became 2); an int for a double is taken. NodeHandle::param() silently
/// keeps the default instead, and a driver told `_port:=123` opened /dev/ttyUSB0.
template <typename T>
void readTypedParameter(const ros::NodeHandle& pnh, const std::string& name, T& value)
{
  if (!pnh.hasParam(name))
    return;
  XmlRpc::XmlRpcValue raw;
  pnh.getParam(name, raw);
  T read{};
  const bool integral_given_a_double = std::is_integral_v<T> && !std::is_same_v<T, bool> &&
                                       raw.getType() == XmlRpc::XmlRpcValue::TypeDouble;
  if (integral_given_a_double || !pnh.getParam(name, read))
    throw std::invalid_argument(pnh.resolveName(name) + " holds a value of type " + xmlRpcTypeName(raw) +
                                ", where it needs " + acceptedTypes<T>());
  value = read;
}
}  // namespace biovision_ros_common
