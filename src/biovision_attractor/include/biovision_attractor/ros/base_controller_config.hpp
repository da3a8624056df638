#pragma once

#include <stdexcept>
#include <string>

#include <biovision_attractor/BaseControllerConfig.h>
#include <dynamic_reconfigure/Config.h>

#include "biovision_attractor/base_attractor_parameters.hpp"

namespace biovision_attractor
{
/// The one mapping of cfg/BaseController.cfg onto BaseAttractorParameters (by the names of
/// BaseAttractorParameters::namedDoubles). Does not validate. Throws std::logic_error for a .cfg parameter
/// without a field.
inline BaseAttractorParameters toBaseAttractorParameters(const BaseControllerConfig& config)
{
  dynamic_reconfigure::Config values;
  config.__toMessage__(values);
  BaseAttractorParameters p;
  for (const auto& d : values.doubles)
  {
    bool found = false;
    for (const auto& n : BaseAttractorParameters::namedDoubles())
      if (d.name == n.name)
      {
        p.*n.field = d.value;
        found = true;
      }
    if (!found)
      throw std::logic_error("cfg/BaseController.cfg parameter '" + d.name + "' has no BaseAttractorParameters field");
  }
  if (!values.ints.empty() || !values.strs.empty() || !values.bools.empty())
    throw std::logic_error("cfg/BaseController.cfg has int, string or bool parameters, which have no field");
  return p;
}
}  // namespace biovision_attractor
