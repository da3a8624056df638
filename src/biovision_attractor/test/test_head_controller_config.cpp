// The head controller's defaults are written once, in the structs (HeadAttractorParameters,
// HeadControllerSettings): config/head_controller.yaml and cfg/HeadController.cfg (through its generated
// header) must agree with them, and each .cfg range must be exactly what validate() accepts.
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <string>

#include <biovision_attractor/HeadControllerConfig.h>
#include <dynamic_reconfigure/Config.h>
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include "biovision_attractor/head_attractor_parameters.hpp"
#include "biovision_attractor/head_controller_settings.hpp"
#include "biovision_attractor/ros/head_controller_nodelet.hpp"

using namespace biovision_attractor;

namespace
{
constexpr double kInf = std::numeric_limits<double>::infinity();

// The .cfg's double parameters of one of the generated configs (default, min or max), by name.
std::map<std::string, double> doublesOf(const HeadControllerConfig& config)
{
  dynamic_reconfigure::Config message;
  config.__toMessage__(message);
  std::map<std::string, double> values;
  for (const auto& d : message.doubles)
    values[d.name] = d.value;
  return values;
}

// Whether validate() accepts `value` for the parameter `name`, the others at their defaults -- except that
// look_ahead_period is tried with look_ahead_duration 0, its only coupling.
bool accepts(const std::string& name, double value)
{
  HeadAttractorParameters p;
  if (name == "look_ahead_period")
    p.look_ahead_duration = 0.0;
  for (const auto& [field_name, field] : HeadAttractorParameters::namedDoubles())
    if (field_name == name)
      p.*field = value;
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

TEST(HeadControllerConfig, YamlHoldsTheStructDefaultsAndNothingElse)
{
  const YAML::Node yaml = YAML::LoadFile(HEAD_CONTROLLER_YAML);
  const HeadAttractorParameters p;
  std::set<std::string> known;
  for (const auto& [name, field] : HeadAttractorParameters::namedDoubles())
  {
    known.insert(name);
    ASSERT_TRUE(yaml[name]) << name << " missing from the YAML";
    EXPECT_EQ(yaml[name].as<double>(), p.*field) << name;
  }
  for (const auto& [name, field] : HeadAttractorParameters::namedBools())
  {
    known.insert(name);
    ASSERT_TRUE(yaml[name]) << name << " missing from the YAML";
    EXPECT_EQ(yaml[name].as<bool>(), p.*field) << name;
  }
  const HeadControllerSettings s;
  const std::map<std::string, std::string> strings = {
      {"mode", s.mode}, {"pan_joint", s.pan_joint}, {"tilt_joint", s.tilt_joint}};
  const std::map<std::string, double> numbers = {{"control_rate", s.control_rate},
                                                 {"joint_state_timeout", s.joint_state_timeout},
                                                 {"min_region_area", s.min_region_area},
                                                 {"horizontal_fov", s.horizontal_fov}};
  for (const auto& [name, value] : strings)
  {
    known.insert(name);
    ASSERT_TRUE(yaml[name]) << name << " missing from the YAML";
    EXPECT_EQ(yaml[name].as<std::string>(), value) << name;
  }
  for (const auto& [name, value] : numbers)
  {
    known.insert(name);
    ASSERT_TRUE(yaml[name]) << name << " missing from the YAML";
    EXPECT_EQ(yaml[name].as<double>(), value) << name;
  }
  for (const auto& entry : yaml)
    EXPECT_TRUE(known.count(entry.first.as<std::string>())) << entry.first.as<std::string>() << ": not a parameter";
  EXPECT_NO_THROW(s.validate());
}

TEST(HeadControllerConfig, CfgOffersEveryTunableWithTheStructDefault)
{
  const HeadAttractorParameters defaults;
  // parametersFromConfig() throws for a .cfg parameter without a field.
  const HeadAttractorParameters from_cfg = HeadControllerNodelet::parametersFromConfig(
      HeadControllerConfig::__getDefault__(), HeadAttractorParameters());
  const std::map<std::string, double> cfg = doublesOf(HeadControllerConfig::__getDefault__());
  for (const auto& [name, field] : HeadAttractorParameters::namedDoubles())
  {
    EXPECT_TRUE(cfg.count(name)) << name << " missing from the .cfg";
    EXPECT_EQ(from_cfg.*field, defaults.*field) << name;
  }
  // No field has two names: each keeps the distinct value written under its name.
  HeadAttractorParameters numbered;
  double number = 0;
  for (const auto& [name, field] : HeadAttractorParameters::namedDoubles())
    numbered.*field = ++number;
  number = 0;
  for (const auto& [name, field] : HeadAttractorParameters::namedDoubles())
    EXPECT_EQ(numbered.*field, ++number) << name << ": its field has another name too";
  EXPECT_EQ(cfg.size(), HeadAttractorParameters::namedDoubles().size());
  for (const auto& [name, field] : HeadAttractorParameters::namedBools())
    EXPECT_EQ(from_cfg.*field, defaults.*field) << name;
  EXPECT_EQ(HeadControllerConfig::__getDefault__().tilt_dynamics, defaults.tilt_dynamics);
}

TEST(HeadControllerConfig, CfgRangesAreWhatValidateAccepts)
{
  const std::map<std::string, double> lows = doublesOf(HeadControllerConfig::__getMin__());
  const std::map<std::string, double> highs = doublesOf(HeadControllerConfig::__getMax__());
  // Bounded only through another parameter (look_ahead_period); checked when a set is applied.
  const std::set<std::string> coupled = {"look_ahead_duration"};
  for (const auto& [name, field] : HeadAttractorParameters::namedDoubles())
  {
    (void)field;
    const double low = lows.at(name), high = highs.at(name);
    EXPECT_TRUE(std::isfinite(low)) << name << ": validate() bounds every parameter from below";
    EXPECT_TRUE(accepts(name, low)) << name << ": the .cfg minimum " << low << " is rejected";
    EXPECT_FALSE(accepts(name, std::nextafter(low, -kInf)))
        << name << ": validate() accepts values below the .cfg minimum";
    if (std::isfinite(high))
    {
      EXPECT_TRUE(accepts(name, high)) << name << ": the .cfg maximum " << high << " is rejected";
      EXPECT_FALSE(accepts(name, std::nextafter(high, kInf)))
          << name << ": validate() accepts values above the .cfg maximum";
    }
    else if (!coupled.count(name))
    {
      EXPECT_TRUE(accepts(name, 1e6)) << name << ": no .cfg maximum but validate() rejects large values";
    }
  }
  EXPECT_FALSE(accepts("look_ahead_duration", HeadAttractorParameters().look_ahead_period + 1));
}

TEST(HeadControllerConfig, ParametersFromConfigMapsEachNameToItsField)
{
  // Distinct values per parameter: a field filled from the wrong name shows.
  dynamic_reconfigure::Config message;
  double value = 0.001;
  std::map<std::string, double> sent;
  for (const auto& [name, field] : HeadAttractorParameters::namedDoubles())
  {
    (void)field;
    dynamic_reconfigure::DoubleParameter d;
    d.name = name;
    d.value = value += 0.001;
    sent[name] = d.value;
    message.doubles.push_back(d);
  }
  dynamic_reconfigure::BoolParameter b;
  b.name = "tilt_dynamics";
  b.value = false;
  message.bools.push_back(b);
  HeadControllerConfig config = HeadControllerConfig::__getDefault__();
  ASSERT_TRUE(config.__fromMessage__(message));
  const HeadAttractorParameters p = HeadControllerNodelet::parametersFromConfig(config, HeadAttractorParameters());
  for (const auto& [name, field] : HeadAttractorParameters::namedDoubles())
    EXPECT_EQ(p.*field, sent[name]) << name;
  EXPECT_FALSE(p.tilt_dynamics);
  EXPECT_EQ(config.alpha_attraction, sent["alpha_attraction"]) << "the generated member and the name agree";
  EXPECT_EQ(config.tilt, sent["tilt"]);
}

TEST(HeadControllerSettings, RejectsBadSettings)
{
  HeadControllerSettings s;
  s.mode = "wander";
  EXPECT_THROW(s.validate(), std::invalid_argument);
  s = HeadControllerSettings();
  s.control_rate = 0;
  EXPECT_THROW(s.validate(), std::invalid_argument);
  s = HeadControllerSettings();
  s.pan_joint.clear();
  EXPECT_THROW(s.validate(), std::invalid_argument);
  s = HeadControllerSettings();
  s.horizontal_fov = NAN;
  EXPECT_THROW(s.validate(), std::invalid_argument);
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
