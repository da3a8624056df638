#pragma once

// Transitional: the hand-written --name value parser the tools used before ToolOptions (CLI11).
// Being replaced tool by tool; removed when no tool includes it.

#include <algorithm>
#include <cstdlib>
#include <iostream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "biovision_common/atomic_file.hpp"  // listDirectory

namespace biovision_common
{
class ToolArguments
{
public:
  /// Exits with the usage (status 0 for --help, 2 for an unknown option or a missing value).
  ToolArguments(int argc, char** argv, const std::string& usage, const std::set<std::string>& options,
                const std::set<std::string>& flags = {})
  {
    for (int i = 1; i < argc; ++i)
    {
      const std::string a = argv[i];
      if (a == "--help" || a == "-h")
      {
        std::cout << usage;
        std::exit(0);
      }
      if (flags.count(a))
        values_[a] = "1";
      else if (options.count(a) && i + 1 < argc)
        values_[a] = argv[++i];
      else
      {
        std::cerr << argv[0] << ": unknown option or missing value: " << a << "\n" << usage;
        std::exit(2);
      }
      command_ += (command_.empty() ? "" : " ") + a + (flags.count(a) ? "" : " " + values_[a]);
    }
  }
  bool has(const std::string& name) const { return values_.count(name) > 0; }
  std::string get(const std::string& name, const std::string& fallback = "") const
  {
    auto it = values_.find(name);
    return it == values_.end() ? fallback : it->second;
  }
  double number(const std::string& name, double fallback) const
  {
    return has(name) ? std::atof(get(name).c_str()) : fallback;
  }
  /// A comma-separated option, empty items dropped.
  std::vector<std::string> strings(const std::string& name, const std::string& fallback = "") const
  {
    std::vector<std::string> out;
    std::stringstream ss(get(name, fallback));
    std::string item;
    while (std::getline(ss, item, ','))
      if (!item.empty())
        out.push_back(item);
    return out;
  }
  std::vector<int> integers(const std::string& name, const std::vector<int>& fallback) const
  {
    if (!has(name))
      return fallback;
    std::vector<int> out;
    for (const auto& item : strings(name))
      out.push_back(std::atoi(item.c_str()));
    return out;
  }
  /// The options as given, for recording how a result was made.
  const std::string& command() const { return command_; }

private:
  std::map<std::string, std::string> values_;
  std::string command_;
};
}  // namespace biovision_common
