#pragma once

// Test helpers that keep each parameter default written once in effect: a package's YAML defaults
// (config/<node>.yaml) must equal its dynamic_reconfigure .cfg defaults, and every value the .cfg lets a
// user dial in must pass the core parameter struct's validate(). Used by each package's gtest of its
// parameter files; header-only, needs yaml-cpp.

#include <cmath>
#include <sstream>
#include <string>
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

/// One line per .cfg parameter that the YAML file lacks or gives another value than the .cfg default.
/// YAML keys that are not reconfigurable (start-up only) are ignored.
template <typename Config>
std::vector<std::string> yamlDefaultMismatches(const std::string& yaml_path)
{
  const YAML::Node yaml = YAML::LoadFile(yaml_path);
  const dynamic_reconfigure::Config d = configDefaults<Config>();
  std::vector<std::string> problems;
  auto check = [&](const std::string& name, auto expected, auto same) {
    if (!yaml[name])
    {
      problems.push_back(name + ": missing from " + yaml_path);
      return;
    }
    using T = decltype(expected);
    const T got = yaml[name].template as<T>();
    if (!same(got, expected))
    {
      std::ostringstream s;
      s << name << ": " << yaml_path << " says " << got << ", the .cfg default is " << expected;
      problems.push_back(s.str());
    }
  };
  auto equal = [](const auto& a, const auto& b) { return a == b; };
  for (const auto& p : d.ints)
    check(p.name, p.value, equal);
  for (const auto& p : d.bools)
    check(p.name, static_cast<bool>(p.value), equal);
  for (const auto& p : d.strs)
    check(p.name, p.value, equal);
  for (const auto& p : d.doubles)
    check(p.name, p.value, [](double a, double b) { return std::abs(a - b) <= 1e-12 * std::max(1.0, std::abs(b)); });
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
