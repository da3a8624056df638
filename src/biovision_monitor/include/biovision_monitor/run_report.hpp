#pragma once

#include <string>
#include <vector>

namespace biovision_monitor
{
/// A run's pictures and its one-page report (for `make demo` and the *_eval tools): reads what the run
/// left in its folder and writes, next to it,
///  - pan.png: the head's pan and tilt [deg] over time (pan.csv: "t,pan,tilt" in s and rad; a "t,pan" file
///    of an older run gives pan alone) with the fixations of fixations.json marked by object name;
///  - rates.png: each topic's message rate [Hz] from report.json (topic_report), silent topics in red, and
///    beside it, when topic_report measured them, the latency since the header stamp (p50 bar, p95 tick)
///    [ms] — per stage, the time since the camera frame its output comes from was taken;
///  - path.png: the path driven (path.csv: "t,x,y" in s and m, map frame) over the long-term memory
///    (mission.json's ltm_map: a PGM of the grid's signed bytes, its origin and resolution), with home,
///    the target, the new obstacle and the remembered objects of mission.json (biovision_tasks'
///    mission_director);
///  - report.html: self-contained (the PNGs embedded as base64): the result, the topic table, the
///    fixations, the recognition summary (recognition.json), the mission's outcome (mission.json) and
///    every picture the folder holds among path.png, panel.png, rviz.png, pan.png, rates.png.
/// Inputs that are missing are left out (and named in the page); none is required.
class RunReport
{
public:
  explicit RunReport(std::string folder) : folder_(std::move(folder)) {}

  /// Writes the files; returns their paths. Throws biovision_common::FileError when a file cannot be
  /// written, std::runtime_error naming the file when an input is unreadable (bad JSON, bad CSV line).
  std::vector<std::string> write() const;

  /// Standard base64 of `bytes` (RFC 4648, with padding), for data: URIs.
  static std::string base64(const std::vector<unsigned char>& bytes);

private:
  std::string folder_;
};
}  // namespace biovision_monitor
