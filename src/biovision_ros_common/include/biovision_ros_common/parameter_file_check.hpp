#pragma once

// Test helpers that keep each parameter default written once in effect: a package's YAML defaults
// (config/<node>.yaml) must equal its dynamic_reconfigure .cfg defaults or its core parameter struct's,
// and every value the .cfg lets a user dial in must pass the core parameter struct's validate(). Used by
// each package's gtest of its parameter files; header-only, needs yaml-cpp.

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <dynamic_reconfigure/Config.h>
#include <yaml-cpp/yaml.h>

namespace biovision_ros_common
{
/// The problems, one a line, for a test's failure message.
inline std::string joinLines(const std::vector<std::string>& lines)
{
  std::string s;
  for (const auto& l : lines)
    s += l + "\n";
  return s;
}

/// The .cfg defaults of `Config` (a dynamic_reconfigure generated class) as a message.
template <typename Config>
dynamic_reconfigure::Config configDefaults()
{
  dynamic_reconfigure::Config message;
  Config::__getDefault__().__toMessage__(message);
  return message;
}

/// Appends "<name>: ..." to `problems` when `yaml` lacks `name` or holds another value than `expected`
/// (floating point: within 1e-12 relative). `source` names where `expected` comes from, for the message.
template <typename T>
void checkYamlValue(const YAML::Node& yaml, const std::string& yaml_path, const std::string& name, const T& expected,
                    const char* source, std::vector<std::string>& problems)
{
  if (!yaml[name])
  {
    problems.push_back(name + ": missing from " + yaml_path);
    return;
  }
  const T got = yaml[name].template as<T>();
  bool same;
  if constexpr (std::is_floating_point_v<T>)
    same = std::abs(got - expected) <= T(1e-12) * std::max(T(1), std::abs(expected));
  else
    same = got == expected;
  if (!same)
  {
    std::ostringstream s;
    s << name << ": " << yaml_path << " says " << got << ", the " << source << " default is " << expected;
    problems.push_back(s.str());
  }
}

/// One line per .cfg parameter that the YAML file lacks or gives another value than the .cfg default.
/// YAML keys that are not reconfigurable (start-up only) are ignored.
template <typename Config>
std::vector<std::string> yamlDefaultMismatches(const std::string& yaml_path)
{
  const YAML::Node yaml = YAML::LoadFile(yaml_path);
  const dynamic_reconfigure::Config d = configDefaults<Config>();
  std::vector<std::string> problems;
  for (const auto& p : d.ints)
    checkYamlValue(yaml, yaml_path, p.name, p.value, ".cfg", problems);
  for (const auto& p : d.bools)
    checkYamlValue(yaml, yaml_path, p.name, static_cast<bool>(p.value), ".cfg", problems);
  for (const auto& p : d.strs)
    checkYamlValue(yaml, yaml_path, p.name, p.value, ".cfg", problems);
  for (const auto& p : d.doubles)
    checkYamlValue(yaml, yaml_path, p.name, p.value, ".cfg", problems);
  return problems;
}

/// One line per difference between the YAML file and the defaults of a core parameter struct: a field the
/// file lacks or gives another value, and a key of the file that is no field (for nodes whose every
/// parameter is read at start-up, without a .cfg). `visit(parameters, read)` calls read(name, field&) for
/// each field, as the packages' visitParameters() do. Throws YAML::Exception when the file does not parse.
template <typename Parameters, typename Visit>
std::vector<std::string> yamlStructMismatches(const std::string& yaml_path, Visit&& visit)
{
  const YAML::Node yaml = YAML::LoadFile(yaml_path);
  Parameters defaults;
  std::set<std::string> fields;
  std::vector<std::string> problems;
  visit(defaults, [&](const std::string& name, const auto& value) {
    fields.insert(name);
    checkYamlValue(yaml, yaml_path, name, value, "struct", problems);
  });
  for (const auto& kv : yaml)
  {
    const auto key = kv.first.as<std::string>();
    if (!fields.count(key))
      problems.push_back(key + ": in " + yaml_path + " but not a parameter");
  }
  return problems;
}

/// Configs at the corners of the .cfg ranges: for each int or double parameter, one Config with it at its
/// minimum and one at its maximum, every other parameter at its default. Labelled "name=min" / "name=max".
template <typename Config>
std::vector<std::pair<std::string, Config>> rangeCorners()
{
  dynamic_reconfigure::Config lo, hi;
  Config::__getMin__().__toMessage__(lo);
  Config::__getMax__().__toMessage__(hi);
  const dynamic_reconfigure::Config defaults = configDefaults<Config>();
  std::vector<std::pair<std::string, Config>> corners;
  auto add = [&](const std::string& label, const dynamic_reconfigure::Config& message) {
    Config c = Config::__getDefault__();
    c.__fromMessage__(const_cast<dynamic_reconfigure::Config&>(message));
    corners.emplace_back(label, c);
  };
  for (size_t i = 0; i < defaults.ints.size(); ++i)
    for (const auto* bound : {&lo, &hi})
    {
      dynamic_reconfigure::Config m = defaults;
      m.ints[i].value = bound->ints[i].value;
      add(m.ints[i].name + (bound == &lo ? "=min " : "=max ") + std::to_string(m.ints[i].value), m);
    }
  for (size_t i = 0; i < defaults.doubles.size(); ++i)
    for (const auto* bound : {&lo, &hi})
    {
      dynamic_reconfigure::Config m = defaults;
      m.doubles[i].value = bound->doubles[i].value;
      add(m.doubles[i].name + (bound == &lo ? "=min " : "=max ") + std::to_string(m.doubles[i].value), m);
    }
  return corners;
}
}  // namespace biovision_ros_common
