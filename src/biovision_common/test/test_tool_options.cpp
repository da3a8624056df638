#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <vector>

#include "biovision_common/tool_options.hpp"

using namespace biovision_common;

namespace
{
struct Parsed
{
  int threads = 2;
  double scale = 1.0;
  std::vector<int> levels{0, 1};
  bool shaped = false;
};

/// Declares the options a typical tool has and parses `args` (argv[0] added).
Parsed parse(std::vector<std::string> args, ToolOptions* keep = nullptr)
{
  Parsed p;
  ToolOptions local("tool", "test tool");
  ToolOptions& options = keep ? *keep : local;
  options.app().add_option("--threads", p.threads, "threads")->check(kPositive);
  options.app().add_option("--scale", p.scale, "scale");
  options.app().add_option("--levels", p.levels, "levels")->delimiter(',');
  options.app().add_flag("--shaped", p.shaped, "flag");
  args.insert(args.begin(), "tool");
  std::vector<char*> argv;
  for (auto& a : args)
    argv.push_back(a.data());
  options.parse(static_cast<int>(argv.size()), argv.data());
  return p;
}
}  // namespace

TEST(ToolOptions, TypedValuesListsAndFlags)
{
  ToolOptions options("tool", "test tool");
  const Parsed p = parse({"--threads", "3", "--scale", "0.5", "--levels", "2,3,4", "--shaped"}, &options);
  EXPECT_EQ(p.threads, 3);
  EXPECT_DOUBLE_EQ(p.scale, 0.5);
  EXPECT_EQ(p.levels, (std::vector<int>{2, 3, 4}));
  EXPECT_TRUE(p.shaped);
  EXPECT_EQ(options.command(), "--threads 3 --scale 0.5 --levels 2,3,4 --shaped");
}

TEST(ToolOptions, RoslaunchArgumentsAreSkipped)
{
  ToolOptions options("tool", "test tool");
  const Parsed p = parse({"--threads", "4", "__name:=emulator", "__log:=/tmp/x.log"}, &options);
  EXPECT_EQ(p.threads, 4);
  EXPECT_EQ(options.command(), "--threads 4");
}

TEST(ToolOptions, DefaultsStayWhenOptionsAreAbsent)
{
  const Parsed p = parse({});
  EXPECT_EQ(p.threads, 2);
  EXPECT_EQ(p.levels, (std::vector<int>{0, 1}));
  EXPECT_FALSE(p.shaped);
}

// The hand-written parser this replaces read "--threads x" as 0: now it is an error (exit status 2).
TEST(ToolOptions, IllTypedUnknownOrMissingValuesExitWithStatus2)
{
  EXPECT_EXIT(parse({"--threads", "x"}), testing::ExitedWithCode(2), "threads");
  EXPECT_EXIT(parse({"--threads", "0"}), testing::ExitedWithCode(2), "--threads: 0 is not > 0");
  EXPECT_EXIT(parse({"--scale", "1.5abc"}), testing::ExitedWithCode(2), "scale");
  EXPECT_EXIT(parse({"--levels", "1,b"}), testing::ExitedWithCode(2), "levels");
  EXPECT_EXIT(parse({"--no-such-option"}), testing::ExitedWithCode(2), "no-such-option");
  EXPECT_EXIT(parse({"--threads"}), testing::ExitedWithCode(2), "threads");
}

TEST(ToolOptions, HelpExitsWithStatus0)
{
  EXPECT_EXIT(parse({"--help"}), testing::ExitedWithCode(0), "");
}

// Usage texts do not repeat the defaults: --help reads them from the variables.
TEST(ToolOptions, HelpShowsTheDefaults)
{
  ToolOptions options("tool", "test tool");
  parse({}, &options);
  const std::string help = options.app().help();
  EXPECT_NE(help.find("=2"), std::string::npos) << help;
  EXPECT_NE(help.find("[0,1]"), std::string::npos) << help;
}

TEST(ToolOptions, JsonIsWrittenWholeAndReadsBack)
{
  const std::string path = testing::TempDir() + "/biovision_common_tool.json";
  nlohmann::json doc;
  doc["method"] = "biobin \"fast\"";  // quotes and backslashes are escaped by the library, not by hand
  doc["figures"] = {{"bad1", 14.77}, {"scenes", 35}};
  writeJsonFile(path, doc);
  std::ifstream in(path);
  const nlohmann::json back = nlohmann::json::parse(in);
  EXPECT_EQ(back, doc);
}

// bench_report.py shows the figures in the order of the file: ordered_json keeps the tool's order.
TEST(ToolOptions, OrderedJsonKeepsTheKeysInTheOrderTheyWereAdded)
{
  const std::string path = testing::TempDir() + "/biovision_common_tool_ordered.json";
  nlohmann::ordered_json doc;
  doc["zeta"] = 1;
  doc["alpha"] = {{"second", 2.5}, {"first", 0.1}};
  writeJsonFile(path, doc);
  std::ifstream in(path);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_LT(text.find("zeta"), text.find("alpha"));
  EXPECT_LT(text.find("second"), text.find("first"));
  EXPECT_EQ(text.find("0.10000"), std::string::npos);  // shortest round-trip form, not 0.10000000000000001
  EXPECT_EQ(nlohmann::ordered_json::parse(text), doc);
}
