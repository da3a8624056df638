// The base controller's defaults are written once, in the structs (BaseAttractorParameters,
// BaseControllerSettings): config/base_controller.yaml and cfg/BaseController.cfg (through its generated
// header) must agree with them, and each .cfg range must be exactly what validate() accepts.
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <string>

#include <biovision_attractor/BaseControllerConfig.h>
#include <dynamic_reconfigure/Config.h>
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include "biovision_attractor/base_attractor_parameters.hpp"
#include "biovision_attractor/base_controller_settings.hpp"
#include "biovision_attractor/ros/base_controller_config.hpp"
#include "biovision_ros_common/parameter_file_check.hpp"

using namespace biovision_attractor;

namespace
{
constexpr double kInf = std::numeric_limits<double>::infinity();

std::map<std::string, double> doublesOf(const BaseControllerConfig& config)
{
  dynamic_reconfigure::Config message;
  config.__toMessage__(message);
  std::map<std::string, double> values;
  for (const auto& d : message.doubles)
    values[d.name] = d.value;
  return values;
}

bool accepts(const std::string& name, double value)
{
  BaseAttractorParameters p;
  for (const auto& n : BaseAttractorParameters::namedDoubles())
    if (n.name == name)
      p.*n.field = value;
  // Only the coupling slow_distance > safety_distance: move the partner out of the way.
  if (name == "safety_distance")
    p.slow_distance = 5.0;
  if (name == "slow_distance")
    p.safety_distance = 0.0;
  try
  {
    p.validate();
    return true;
  }
  catch (const std::invalid_argument&)
  {
    return false;
  }
}
}  // namespace

TEST(BaseControllerConfig, YamlHoldsTheStructDefaultsAndNothingElse)
{
  const YAML::Node yaml = YAML::LoadFile(BASE_CONTROLLER_YAML);
  const BaseAttractorParameters p;
  std::set<std::string> known;
  for (const auto& n : BaseAttractorParameters::namedDoubles())
  {
    known.insert(n.name);
    ASSERT_TRUE(yaml[n.name]) << n.name << " missing from the YAML";
    EXPECT_EQ(yaml[n.name].as<double>(), p.*n.field) << n.name;
  }
  const BaseControllerSettings s;
  const std::map<std::string, double> numbers = {{"control_rate", s.control_rate},
                                                 {"stm_timeout", s.stm_timeout},
                                                 {"odom_timeout", s.odom_timeout},
                                                 {"max_goal_distance", s.max_goal_distance}};
  known.insert("odom_frame");
  ASSERT_TRUE(yaml["odom_frame"]);
  EXPECT_EQ(yaml["odom_frame"].as<std::string>(), s.odom_frame);
  for (const auto& [name, value] : numbers)
  {
    known.insert(name);
    ASSERT_TRUE(yaml[name]) << name << " missing from the YAML";
    EXPECT_EQ(yaml[name].as<double>(), value) << name;
  }
  for (const auto& entry : yaml)
    EXPECT_TRUE(known.count(entry.first.as<std::string>())) << entry.first.as<std::string>() << ": not a parameter";
  EXPECT_NO_THROW(s.validate());
  const auto problems = biovision_ros_common::yamlDefaultMismatches<BaseControllerConfig>(BASE_CONTROLLER_YAML);
  EXPECT_TRUE(problems.empty()) << biovision_ros_common::joinLines(problems);
}

TEST(BaseControllerConfig, CfgOffersEveryParameterWithTheStructDefault)
{
  const BaseAttractorParameters defaults;
  const BaseAttractorParameters from_cfg = toBaseAttractorParameters(BaseControllerConfig::__getDefault__());
  const std::map<std::string, double> cfg = doublesOf(BaseControllerConfig::__getDefault__());
  EXPECT_EQ(cfg.size(), BaseAttractorParameters::namedDoubles().size());
  for (const auto& n : BaseAttractorParameters::namedDoubles())
  {
    EXPECT_TRUE(cfg.count(n.name)) << n.name << " missing from the .cfg";
    EXPECT_EQ(from_cfg.*n.field, defaults.*n.field) << n.name;
  }
  // Each name fills its own field: distinct values come back distinct.
  dynamic_reconfigure::Config message;
  double value = 0.0;
  for (const auto& n : BaseAttractorParameters::namedDoubles())
  {
    dynamic_reconfigure::DoubleParameter d;
    d.name = n.name;
    d.value = value += 0.01;
    message.doubles.push_back(d);
  }
  BaseControllerConfig config = BaseControllerConfig::__getDefault__();
  ASSERT_TRUE(config.__fromMessage__(message));
  const BaseAttractorParameters numbered = toBaseAttractorParameters(config);
  value = 0.0;
  for (const auto& n : BaseAttractorParameters::namedDoubles())
    EXPECT_DOUBLE_EQ(numbered.*n.field, value += 0.01) << n.name;
}

TEST(BaseControllerConfig, CfgRangesAreWhatValidateAccepts)
{
  const std::map<std::string, double> lows = doublesOf(BaseControllerConfig::__getMin__());
  const std::map<std::string, double> highs = doublesOf(BaseControllerConfig::__getMax__());
  for (const auto& n : BaseAttractorParameters::namedDoubles())
  {
    const double low = lows.at(n.name), high = highs.at(n.name);
    EXPECT_EQ(low, n.lower) << n.name;
    EXPECT_EQ(high, n.upper) << n.name;
    EXPECT_TRUE(accepts(n.name, low)) << n.name << ": the .cfg minimum " << low << " is rejected";
    EXPECT_FALSE(accepts(n.name, std::nextafter(low, -kInf))) << n.name << ": accepts below the .cfg minimum";
    EXPECT_TRUE(accepts(n.name, high)) << n.name << ": the .cfg maximum " << high << " is rejected";
    EXPECT_FALSE(accepts(n.name, std::nextafter(high, kInf))) << n.name << ": accepts above the .cfg maximum";
  }
}

TEST(BaseControllerSettings, RejectsBadSettings)
{
  BaseControllerSettings s;
  s.odom_frame.clear();
  EXPECT_THROW(s.validate(), std::invalid_argument);
  s = BaseControllerSettings();
  s.stm_timeout = NAN;
  EXPECT_THROW(s.validate(), std::invalid_argument);
  s = BaseControllerSettings();
  s.control_rate = 0.5;
  EXPECT_THROW(s.validate(), std::invalid_argument);
  s = BaseControllerSettings();
  s.odom_timeout = 0.01;  // below one control period at 20 Hz
  EXPECT_THROW(s.validate(), std::invalid_argument);
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
