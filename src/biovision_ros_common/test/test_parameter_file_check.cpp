// yamlStructMismatches: the drivers' test that config/<node>.yaml holds their struct defaults key for key.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <string>

#include "biovision_ros_common/parameter_file_check.hpp"

namespace
{
struct Example
{
  int width = 640;
  double rate = 15.0;
  bool enabled = true;
  std::string port = "/dev/ttyUSB0";
};

template <typename Read>
void visitExample(Example& e, Read&& read)
{
  read("width", e.width);
  read("rate", e.rate);
  read("enabled", e.enabled);
  read("port", e.port);
}

class YamlStructMismatches : public ::testing::Test
{
protected:
  std::vector<std::string> check(const std::string& yaml)
  {
    std::ofstream(path_) << yaml;
    return biovision_ros_common::yamlStructMismatches<Example>(path_,
                                                               [](auto& e, auto&& read) { visitExample(e, read); });
  }
  void TearDown() override { std::remove(path_.c_str()); }

  std::string path_ = ::testing::TempDir() + "parameter_file_check_" + std::to_string(::getpid()) + ".yaml";
};
}  // namespace

TEST_F(YamlStructMismatches, TheDefaultsKeyForKeyAreNoProblem)
{
  EXPECT_TRUE(check("width: 640\nrate: 15.0\nenabled: true\nport: /dev/ttyUSB0\n").empty());
  // Floating point within 1e-12 relative: "15" and 15.0 + 1e-12 are the default.
  EXPECT_TRUE(check("width: 640\nrate: 15.000000000001\nenabled: true\nport: /dev/ttyUSB0\n").empty());
}

TEST_F(YamlStructMismatches, EachMissingWrongOrExtraKeyIsOneProblemNamingIt)
{
  const auto problems = check("width: 320\nrate: 15.001\nport: /dev/ttyUSB0\nbaud: 9600\n");
  ASSERT_EQ(problems.size(), 4u) << biovision_ros_common::joinLines(problems);
  EXPECT_EQ(problems[0].rfind("width: ", 0), 0u);
  EXPECT_NE(problems[0].find("says 320, the struct default is 640"), std::string::npos) << problems[0];
  EXPECT_EQ(problems[1].rfind("rate: ", 0), 0u);
  EXPECT_EQ(problems[2].rfind("enabled: missing from ", 0), 0u);
  EXPECT_EQ(problems[3].rfind("baud: in ", 0), 0u);
  EXPECT_NE(problems[3].find("not a parameter"), std::string::npos);
}

TEST_F(YamlStructMismatches, AValueOfTheWrongTypeOrAFileThatDoesNotParseThrows)
{
  EXPECT_THROW(check("width: wide\nrate: 15\nenabled: true\nport: p\n"), YAML::Exception);
  EXPECT_THROW(check("width: [640\n"), YAML::Exception);
}
