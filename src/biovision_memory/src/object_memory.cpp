#include "biovision_memory/object_memory.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "biovision_common/object_label.hpp"

namespace biovision_memory
{
void ObjectMemoryParameters::validate() const
{
  rules.validate();
  if (!(match_distance > 0.0 && match_distance <= 10.0))
  {
    std::ostringstream m;
    m << "ObjectMemoryParameters.match_distance = " << match_distance << " is outside (0, 10]";
    throw std::invalid_argument(m.str());
  }
  if (averaging_window < 1 || averaging_window > 1000)
  {
    std::ostringstream m;
    m << "ObjectMemoryParameters.averaging_window = " << averaging_window << " is outside [1, 1000]";
    throw std::invalid_argument(m.str());
  }
  if (!(max_depth > 0.0 && max_depth <= 100.0))
  {
    std::ostringstream m;
    m << "ObjectMemoryParameters.max_depth = " << max_depth << " is outside (0, 100]";
    throw std::invalid_argument(m.str());
  }
}

ObjectMemory::ObjectMemory(const ObjectMemoryParameters& parameters) : parameters_(parameters)
{
  parameters_.validate();
}

void ObjectMemory::setParameters(const ObjectMemoryParameters& parameters)
{
  parameters.validate();
  parameters_ = parameters;
}

ObjectMemory::Sighting ObjectMemory::observe(const std::string& label, const Eigen::Vector3d& position, double stamp,
                                             double depth)
{
  const std::string problem = biovision_common::ObjectLabel::problem(label);
  if (!problem.empty())  // the rule the database checks on load: what is remembered can be loaded again
    throw std::invalid_argument("ObjectMemory::observe: " + problem);
  if (!position.allFinite() || !std::isfinite(stamp))
    throw std::invalid_argument("ObjectMemory::observe: non-finite position or stamp for '" + label + "'");
  if (!(depth >= 0.0 && std::isfinite(depth)))
    throw std::invalid_argument("ObjectMemory::observe: negative or non-finite depth for '" + label + "'");
  Sighting sighting;
  if (depth > parameters_.max_depth)
  {
    sighting.too_far = true;
    return sighting;
  }
  const ReinforcementRules& r = parameters_.rules;
  auto it = objects_.find(label);
  if (it != objects_.end())
  {
    Object& o = it->second;
    o.strength = r.decay(o.strength, o.last_change, stamp);
    if (o.strength <= 0)
    {
      objects_.erase(it);
      it = objects_.end();
    }
  }
  dirty_[label] = true;
  if (it == objects_.end())
  {
    Object o;
    o.label = label;
    o.position = position;
    o.strength = r.initial_strength;
    o.observations = 1;
    o.first_seen = o.last_seen = o.last_change = stamp;
    objects_.emplace(label, o);
    sighting.remembered = position;
    return sighting;
  }
  Object& o = it->second;
  forgetCandidate(o, stamp);
  sighting.landmark = r.fixed(o.strength);
  sighting.remembered = o.position;
  // A running mean over the last averaging_window sightings' weight.
  const auto average = [this](Eigen::Vector3d& mean, std::uint32_t observations, const Eigen::Vector3d& p) {
    const double w = 1.0 / std::min<double>(observations + 1, parameters_.averaging_window);
    mean = (1.0 - w) * mean + w * p;
  };
  if ((position - o.position).norm() <= parameters_.match_distance)
  {
    if (!sighting.landmark)
      average(o.position, o.observations, position);
    o.strength = r.reinforce(o.strength);
    ++o.observations;
    // A stamp older than the last change (time went back) never moves it back: rule (c) would then count
    // the whole gap as forgetting periods at the next sighting.
    o.last_seen = std::max(o.last_seen, stamp);
    o.last_change = std::max(o.last_change, stamp);
    if (o.candidate_strength > 0)  // the old place confirmed: the candidate contradicted
    {
      o.candidate_strength = std::max(0, r.weaken(o.candidate_strength));
      if (o.candidate_strength == 0)
        o.candidate_observations = 0;
    }
    return sighting;
  }
  // Seen elsewhere: the old place is contradicted, the candidate place supported.
  o.strength = r.weaken(o.strength);
  o.last_change = std::max(o.last_change, stamp);
  if (o.candidate_strength > 0 && (position - o.candidate_position).norm() <= parameters_.match_distance)
  {
    average(o.candidate_position, o.candidate_observations, position);
    o.candidate_strength = r.reinforce(o.candidate_strength);
    ++o.candidate_observations;
    o.candidate_last_change = std::max(o.candidate_last_change, stamp);
  }
  else
  {
    o.candidate_position = position;
    o.candidate_strength = r.initial_strength;
    o.candidate_observations = 1;
    o.candidate_last_change = stamp;
  }
  if (o.strength <= 0 || (o.candidate_observations >= kMinCandidateSightings && o.candidate_strength >= o.strength))
  {
    o.position = o.candidate_position;
    o.strength = o.candidate_strength;
    o.observations = o.candidate_observations;
    o.first_seen = o.last_seen = stamp;
    o.candidate_strength = 0;
    o.candidate_observations = 0;
    sighting.relocated = true;
  }
  return sighting;
}

void ObjectMemory::forgetCandidate(Object& o, double stamp) const
{
  if (o.candidate_strength <= 0)
    return;
  o.candidate_strength = parameters_.rules.decay(o.candidate_strength, o.candidate_last_change, stamp);
  if (o.candidate_strength <= 0)
  {
    o.candidate_strength = 0;
    o.candidate_observations = 0;
  }
}

std::vector<std::string> ObjectMemory::forget(double stamp)
{
  std::vector<std::string> removed;
  for (auto it = objects_.begin(); it != objects_.end();)
  {
    forgetCandidate(it->second, stamp);  // not stored: never makes the object dirty
    const double before = it->second.last_change;
    it->second.strength = parameters_.rules.decay(it->second.strength, it->second.last_change, stamp);
    if (it->second.strength <= 0)
    {
      removed.push_back(it->first);
      dirty_[it->first] = false;
      it = objects_.erase(it);
      continue;
    }
    if (it->second.last_change != before)
      dirty_[it->first] = true;
    ++it;
  }
  return removed;
}

bool ObjectMemory::remove(const std::string& label)
{
  if (objects_.erase(label) == 0)
    return false;
  dirty_[label] = false;
  return true;
}

const ObjectMemory::Object* ObjectMemory::find(const std::string& label) const
{
  const auto it = objects_.find(label);
  return it == objects_.end() ? nullptr : &it->second;
}

void ObjectMemory::clear()
{
  for (const auto& [label, o] : objects_)
    dirty_[label] = false;
  objects_.clear();
}

void ObjectMemory::load(const std::vector<Object>& objects)
{
  for (const Object& o : objects)
    objects_[o.label] = o;
}

void ObjectMemory::rebaseTime(double now)
{
  for (auto& [label, o] : objects_)
  {
    o.candidate_last_change = std::min(o.candidate_last_change, now);  // not stored: not dirty
    if (o.last_change > now || o.last_seen > now || o.first_seen > now)
    {
      o.last_change = std::min(o.last_change, now);
      o.last_seen = std::min(o.last_seen, now);
      o.first_seen = std::min(o.first_seen, now);
      dirty_[label] = true;
    }
  }
}

ObjectMemory::Changes ObjectMemory::takeChanges()
{
  Changes changes;
  for (const auto& [label, present] : dirty_)
  {
    const auto it = objects_.find(label);
    if (present && it != objects_.end())
      changes.upserted.push_back(it->second);
    else if (it == objects_.end())
      changes.removed.push_back(label);
  }
  dirty_.clear();
  return changes;
}
}  // namespace biovision_memory
