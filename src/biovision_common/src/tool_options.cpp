#include "biovision_common/tool_options.hpp"

#include <vector>

#include <cstdlib>
#include <iostream>

#include "biovision_common/atomic_file.hpp"

namespace biovision_common
{
namespace
{
/// A validator of numbers for which `accept` holds; `requirement` completes "<value> is not ...".
CLI::Validator numberWhere(bool (*accept)(double), const std::string& requirement, const std::string& name)
{
  return CLI::Validator(
      [accept, requirement](std::string& value) {
        double number = 0.0;
        if (!CLI::detail::lexical_cast(value, number))
          return std::string();  // not a number: the option's type check names the problem
        return accept(number) ? std::string() : value + " is not " + requirement;
      },
      name);
}
}  // namespace

const CLI::Validator kPositive = numberWhere([](double x) { return x > 0.0; }, "> 0", "POSITIVE");
const CLI::Validator kNonNegative = numberWhere([](double x) { return x >= 0.0; }, ">= 0", "NONNEGATIVE");

ToolOptions::ToolOptions(const std::string& tool, const std::string& description) : app_(description, tool)
{
  app_.option_defaults()->always_capture_default();  // --help prints "--threads INT=2"
}

namespace
{
template <typename Json>
bool writeJsonSaying(const std::string& tool, const std::string& path, const Json& document)
{
  if (path.empty())
    return true;
  try
  {
    writeJsonFile(path, document);
    return true;
  }
  catch (const FileError& e)
  {
    std::cerr << tool << ": " << e.what() << "\n";
    return false;
  }
}
}  // namespace

bool ToolOptions::writeJson(const std::string& path, const nlohmann::json& document) const
{
  return writeJsonSaying(app_.get_name(), path, document);
}

bool ToolOptions::writeJson(const std::string& path, const nlohmann::ordered_json& document) const
{
  return writeJsonSaying(app_.get_name(), path, document);
}

void ToolOptions::parse(int argc, char** argv)
{
  std::vector<char*> args;
  for (int i = 0; i < argc; ++i)
    if (i == 0 || std::string(argv[i]).rfind("__", 0) != 0)
      args.push_back(argv[i]);
  for (size_t i = 1; i < args.size(); ++i)
    command_ += (i > 1 ? " " : "") + std::string(args[i]);
  try
  {
    app_.parse(static_cast<int>(args.size()), args.data());
  }
  catch (const CLI::ParseError& e)
  {
    // exit() prints the help text (--help, code 0) or the error with a pointer to --help.
    const int code = app_.exit(e);
    std::exit(code == 0 ? 0 : 2);
  }
}

void writeJsonFile(const std::string& path, const nlohmann::json& document)
{
  writeFileAtomically(path, document.dump(2) + "\n");
}

void writeJsonFile(const std::string& path, const nlohmann::ordered_json& document)
{
  writeFileAtomically(path, document.dump(2) + "\n");
}
}  // namespace biovision_common
