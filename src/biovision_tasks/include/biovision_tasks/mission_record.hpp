#pragma once

#include <map>
#include <string>

#include "biovision_tasks/percept.hpp"

namespace biovision_tasks
{
/// What a mission has learned so far, shared by its tasks: where home is (the first localised pose) and
/// where each searched object was found (map frame). Owned by the TaskManager.
struct MissionRecord
{
  bool home_known = false;
  Percept::Pose home;
  std::map<std::string, Percept::Object> found;  ///< by label
  double path_length = 0;                        ///< [m] driven since the mission record began
};
}  // namespace biovision_tasks
