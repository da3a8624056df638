// run_report: a run folder's pictures (pan.png, rates.png) and self-contained report.html (RunReport).
#include <iostream>

#include <nlohmann/json.hpp>

#include "biovision_common/tool_options.hpp"
#include "biovision_monitor/run_report.hpp"

int main(int argc, char** argv)
{
  biovision_common::ToolOptions options(
      "run_report",
      "Writes pan.png, rates.png and a self-contained report.html into a run's folder (make demo's "
      "out/demo) from its report.json, pan.csv, fixations.json, recognition.json and panel.png.");
  std::string folder, json;
  options.app().add_option("folder", folder, "the run's folder")->required()->check(CLI::ExistingDirectory);
  options.app().add_option("--json", json, "also write the list of files written here");
  options.parse(argc, argv);
  try
  {
    const auto written = biovision_monitor::RunReport(folder).write();
    for (const auto& f : written)
      std::cout << "run_report: wrote " << f << "\n";
    if (!json.empty())
      biovision_common::writeJsonFile(json, nlohmann::json{{"command", options.command()}, {"written", written}});
  }
  catch (const std::exception& e)
  {
    std::cerr << "run_report: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
