#include "biovision_common/tool_options.hpp"

#include <cstdlib>
#include <iostream>

#include "biovision_common/atomic_file.hpp"

namespace biovision_common
{
ToolOptions::ToolOptions(const std::string& tool, const std::string& description) : app_(description, tool) {}

void ToolOptions::parse(int argc, char** argv)
{
  for (int i = 1; i < argc; ++i)
    command_ += (i > 1 ? " " : "") + std::string(argv[i]);
  try
  {
    app_.parse(argc, argv);
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
}  // namespace biovision_common
