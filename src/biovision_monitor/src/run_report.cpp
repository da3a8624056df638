#include "biovision_monitor/run_report.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "biovision_common/atomic_file.hpp"
#include "biovision_monitor/drawing.hpp"
#include "biovision_common/path_plot.hpp"
#include "biovision_common/picture_page.hpp"
#include "biovision_monitor/time_series_plot.hpp"

namespace biovision_monitor
{
namespace
{
bool exists(const std::string& path)
{
  std::ifstream f(path);
  return f.good();
}

nlohmann::json readJson(const std::string& path)
{
  std::ifstream f(path);
  try
  {
    return nlohmann::json::parse(f);
  }
  catch (const nlohmann::json::exception& e)
  {
    throw std::runtime_error(path + ": not JSON: " + e.what());
  }
}

// A topic's latency_ms entry as topic_report writes it ({"p50": ms, "p95": ms, ...}); false when it is missing
// or not a pair of finite numbers (an older or hand-edited report.json): that topic shows no latency instead of
// the whole report failing on a JSON type error.
bool latencyOf(const nlohmann::json& topic, double& p50, double& p95)
{
  const auto it = topic.find("latency_ms");
  if (it == topic.end() || !it->is_object())
    return false;
  const auto a = it->find("p50"), b = it->find("p95");
  if (a == it->end() || b == it->end() || !a->is_number() || !b->is_number())
    return false;
  p50 = a->get<double>();
  p95 = b->get<double>();
  return std::isfinite(p50) && std::isfinite(p95);
}

std::string html(const std::string& text)
{
  std::string out;
  for (char c : text)
    switch (c)
    {
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '&':
        out += "&amp;";
        break;
      default:
        out += c;
    }
  return out;
}

void writePng(const std::string& path, const cv::Mat& image)
{
  std::vector<uchar> png;
  cv::imencode(".png", image, png);
  biovision_common::writeFileAtomically(path, png.data(), png.size());
}

// One CSV line without its CR (a file written on Windows) and surrounding blanks.
std::string trimmed(std::string text)
{
  const auto first = text.find_first_not_of(" \t\r");
  const auto last = text.find_last_not_of(" \t\r");
  return first == std::string::npos ? std::string() : text.substr(first, last - first + 1);
}

/// The rows of a CSV file whose header line names its columns: the values of `columns`, in that order, from
/// each row; a column named in `optional` may be missing from the file (its values are then NaN). Throws
/// std::runtime_error naming the file — and the line — when it cannot be read, its header lacks a required
/// column or names one twice, or a row is not exactly one number per header column.
std::vector<std::vector<double>> readCsv(const std::string& path, const std::vector<std::string>& columns,
                                         const std::vector<std::string>& optional = {})
{
  std::ifstream f(path);
  std::string line;
  if (!f || !std::getline(f, line))
    throw std::runtime_error(path + ": cannot be read");
  if (line.rfind("\xEF\xBB\xBF", 0) == 0)
    line.erase(0, 3);  // a UTF-8 byte order mark
  std::vector<std::string> header;
  std::istringstream names(line);
  for (std::string name; std::getline(names, name, ',');)
    header.push_back(trimmed(name));
  std::vector<int> index;  // the file's column of each of `columns`, -1 when absent
  for (const std::string& c : columns)
  {
    const auto n = std::count(header.begin(), header.end(), c);
    const bool may_miss = std::find(optional.begin(), optional.end(), c) != optional.end();
    if (n > 1 || (n == 0 && !may_miss))
      throw std::runtime_error(path + ":1: the header \"" + trimmed(line) + "\" must name the column \"" + c +
                               "\" once");
    index.push_back(n ? static_cast<int>(std::find(header.begin(), header.end(), c) - header.begin()) : -1);
  }
  std::vector<std::vector<double>> rows;
  for (int n = 2; std::getline(f, line); ++n)
  {
    line = trimmed(line);
    if (line.empty())
      continue;
    std::istringstream s(line);
    std::vector<double> values(header.size());
    bool ok = true;
    for (size_t c = 0; c < header.size() && ok; ++c)
    {
      char comma = ',';
      ok = (c == 0 || (s >> comma && comma == ',')) && static_cast<bool>(s >> values[c]);
    }
    ok = ok && (s >> std::ws).eof();  // nothing after the last column: no extra column, no "0.2xyz"
    if (!ok)
      throw std::runtime_error(path + ":" + std::to_string(n) + ": expected " + std::to_string(header.size()) +
                               " numbers (" + trimmed(names.str()) + "), got \"" + line + "\"");
    std::vector<double> row;
    for (int k : index)
      row.push_back(k >= 0 ? values[k] : NAN);
    rows.push_back(std::move(row));
  }
  return rows;
}

/// The head's angles over time from pan.csv (columns t, pan, tilt in s and rad; older runs wrote no tilt), in
/// degrees.
std::vector<TimeSeriesPlot::Series> readHeadCsv(const std::string& path)
{
  const auto rows = readCsv(path, {"t", "pan", "tilt"}, {"tilt"});
  const bool with_tilt = !rows.empty() && !std::isnan(rows[0][2]);
  std::vector<TimeSeriesPlot::Series> series = {{"pan", colours::kSum, {}}};
  if (with_tilt)
    series.push_back({"tilt", colours::kRepulsion, {}});
  for (const auto& r : rows)
    for (size_t i = 0; i < series.size(); ++i)
      series[i].points.emplace_back(r[0], r[i + 1] * 180.0 / M_PI);
  return series;
}

cv::Point2d point(const nlohmann::json& xy)
{
  if (xy.is_array() && xy.size() >= 2 && xy[0].is_number() && xy[1].is_number())
    return {xy[0].get<double>(), xy[1].get<double>()};
  return {NAN, NAN};
}

/// path.png: path.csv ("t,x,y", map frame) over the LTM of mission.json's ltm_map, with home, the
/// target (true: disc; remembered: ring), the new obstacle and the remembered objects.
cv::Mat pathPicture(const std::string& dir, const nlohmann::json& mission)
{
  std::vector<cv::Point2d> path;
  for (const auto& r : readCsv(dir + "path.csv", {"t", "x", "y"}))
    path.emplace_back(r[1], r[2]);
  biovision_common::GridView grid;
  cv::Point2d origin(0, 0);
  if (mission.contains("ltm_map"))
  {
    const auto& m = mission["ltm_map"];
    const std::string file = dir + m.value("file", std::string("ltm.pgm"));
    const cv::Mat pgm = cv::imread(file, cv::IMREAD_GRAYSCALE);
    if (pgm.empty())
      throw std::runtime_error(file + ": not a readable PGM");
    grid.width = pgm.cols;
    grid.height = pgm.rows;
    grid.resolution = m.value("resolution", 0.0);
    origin = point(m.value("origin", nlohmann::json()));
    grid.data.assign(pgm.datastart, pgm.dataend);  // uchar -> signed char: 255 = -1 = unknown
  }
  const cv::Scalar kHome(180, 0, 180), kTarget(0, 0, 210), kObstacle(200, 120, 0), kObject(60, 60, 60);
  std::vector<biovision_common::PathPlot::Mark> marks;
  const std::string target = mission.value("target", std::string("target"));
  for (const auto& o : mission.value("ltm_objects", nlohmann::json::array()))
    if (o.value("label", std::string()) != target)  // drawn below as the target's ring, not labelled twice
      marks.push_back({{o.value("x", NAN), o.value("y", NAN)}, o.value("label", std::string()), kObject, false});
  if (mission.contains("new_obstacle") && mission["new_obstacle"].is_object() && mission["new_obstacle"].contains("x"))
    marks.push_back({{mission["new_obstacle"].value("x", NAN), mission["new_obstacle"].value("y", NAN)},
                     "new obstacle",
                     kObstacle,
                     true});
  marks.push_back({point(mission.value("target_truth", nlohmann::json())), target, kTarget, true});
  // Named, or the ring beside the target's disc is unexplained.
  marks.push_back({point(mission.value("target_remembered", nlohmann::json())), "remembered", kTarget, false});
  marks.push_back({point(mission.value("home", nlohmann::json())), "home", kHome, true});
  return biovision_common::PathPlot().render(grid, origin, path, marks,
                                             "path driven over the long-term memory (map frame)", cv::Size(720, 560));
}

cv::Mat ratesChart(const nlohmann::json& report)
{
  const auto& topics = report.at("topics");
  const int rows = std::max<int>(1, int(topics.size()));
  const int row_h = 20, label_w = 260, width = 720;
  // Two columns when topic_report measured header-stamp latencies: rate bars, then p50 bars with a p95 tick.
  double max_rate = 1.0, max_latency = 0.0;
  for (const auto& [name, t] : topics.items())
  {
    max_rate = std::max(max_rate, t.value("rate_hz", 0.0));
    double p50, p95;
    if (latencyOf(t, p50, p95))
      max_latency = std::max({max_latency, p50, p95});
  }
  const bool latency = max_latency > 0;
  const int rate_w = latency ? 150 : width - label_w - 70, latency_x = label_w + rate_w + 60;
  const int latency_w = width - latency_x - 110;  // room for the "p50 / p95" label
  cv::Mat image(rows * row_h + 40, width, CV_8UC3, colours::kBackground);
  cv::putText(image, "message rate [Hz] per topic", {8, 16}, cv::FONT_HERSHEY_SIMPLEX, 0.45, colours::kAxis, 1,
              cv::LINE_AA);
  if (latency)
    cv::putText(image, "latency p50 / p95 [ms]", {latency_x, 16}, cv::FONT_HERSHEY_SIMPLEX, 0.4, colours::kAxis, 1,
                cv::LINE_AA);
  int y = 28;
  for (const auto& [name, t] : topics.items())
  {
    const double rate = t.value("rate_hz", 0.0);
    const int messages = t.value("messages", 0);
    const int bar = int(rate_w * std::clamp(rate / max_rate, 0.0, 1.0));  // a huge or negative rate stays in
    cv::putText(image, name, {8, y + 14}, cv::FONT_HERSHEY_SIMPLEX, 0.4, colours::kAxis, 1, cv::LINE_AA);
    const cv::Scalar colour = messages > 0 ? colours::kSum : colours::kRepulsion;
    cv::rectangle(image, {label_w, y + 3}, {label_w + std::max(bar, 2), y + row_h - 3}, colour, cv::FILLED);
    // Below 1 Hz with two decimals: a 0.15 Hz goal read "0.1" beside the table's 0.15.
    cv::putText(image, messages > 0 ? formatNumber(rate, std::abs(rate) < 1 ? 2 : 1) : std::string("silent"),
                {label_w + std::max(bar, 2) + 6, y + 14}, cv::FONT_HERSHEY_SIMPLEX, 0.4, colour, 1, cv::LINE_AA);
    double p50, p95;
    if (latency && latencyOf(t, p50, p95))
    {
      const int b50 = int(latency_w * std::clamp(p50 / max_latency, 0.0, 1.0));
      const int b95 = int(latency_w * std::clamp(p95 / max_latency, 0.0, 1.0));
      cv::rectangle(image, {latency_x, y + 3}, {latency_x + std::max(b50, 2), y + row_h - 3}, colours::kAttraction,
                    cv::FILLED);
      cv::line(image, {latency_x + b95, y + 2}, {latency_x + b95, y + row_h - 2}, colours::kAxis, 2);
      cv::putText(image, formatNumber(p50, 0) + " / " + formatNumber(p95, 0),
                  {latency_x + std::max(b95, b50) + 6, y + 14}, cv::FONT_HERSHEY_SIMPLEX, 0.4, colours::kAxis, 1,
                  cv::LINE_AA);
    }
    y += row_h;
  }
  return image;
}
}  // namespace

std::string RunReport::base64(const std::vector<unsigned char>& bytes)
{
  return biovision_common::PicturePage::base64(bytes);
}

std::vector<std::string> RunReport::write() const
{
  const std::string dir = folder_ + "/";
  std::vector<std::string> written, missing;
  std::ostringstream page;
  nlohmann::json report, fixations, recognition, mission;
  const bool have_report = exists(dir + "report.json"), have_fix = exists(dir + "fixations.json"),
             have_recognition = exists(dir + "recognition.json");
  if (have_report)
    report = readJson(dir + "report.json");
  else
    missing.push_back("report.json");
  if (have_fix)
    fixations = readJson(dir + "fixations.json");
  else
    missing.push_back("fixations.json");
  if (have_recognition)
    recognition = readJson(dir + "recognition.json");
  else
    missing.push_back("recognition.json");
  const bool have_mission = exists(dir + "mission.json");
  if (have_mission)
    mission = readJson(dir + "mission.json");
  if (exists(dir + "path.csv"))
  {
    writePng(dir + "path.png", pathPicture(dir, mission));
    written.push_back(dir + "path.png");
  }

  if (exists(dir + "pan.csv"))
  {
    std::vector<TimeSeriesPlot::Mark> marks;
    if (have_fix)
      for (const auto& f : fixations.value("fixations", nlohmann::json::array()))
        marks.push_back({f.value("t", NAN), f.value("object", std::string("?"))});
    writePng(dir + "pan.png",
             TimeSeriesPlot().render(readHeadCsv(dir + "pan.csv"), marks,
                                     "head pan and tilt [deg] over time, fixations marked", cv::Size(900, 300)));
    written.push_back(dir + "pan.png");
  }
  else
    missing.push_back("pan.csv");
  if (have_report)
  {
    writePng(dir + "rates.png", ratesChart(report));
    written.push_back(dir + "rates.png");
  }

  const std::string title = have_report ? report.value("title", std::string("BioVision run")) : "BioVision run";
  page << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>" << html(title)
       << "</title>\n<style>body{font-family:sans-serif;max-width:1400px;margin:1em auto;padding:0 1em}"
          "table{border-collapse:collapse}td,th{border:1px solid #bbb;padding:2px 8px;text-align:left}"
          "img{max-width:100%;border:1px solid #ccc}.bad{color:#b00}</style></head><body>\n";
  page << "<h1>" << html(title) << "</h1>\n";
  if (have_report)
  {
    const bool ok = report.value("ok", false);
    page << "<p class=\"" << (ok ? "" : "bad") << "\">Topics and tf: <b>" << (ok ? "OK" : "FAILED") << "</b> (listened "
         << formatNumber(report.value("listened_s", 0.0), 1) << " s)";
    // topic_report's window that never opened (its start topic sent nothing) or was cut short: say so, not
    // just "FAILED" or a plain listening time. A field of another type is ignored.
    const auto window = report.find("window");
    if (window != report.end() && window->is_object())
    {
      const auto problem = window->find("problem"), interrupted = window->find("interrupted");
      if (problem != window->end() && problem->is_string())
        page << ": " << html(problem->get<std::string>());
      else if (interrupted != window->end() && interrupted->is_boolean() && interrupted->get<bool>())
        page << ": shut down before its window ended";
    }
    page << "</p>\n";
  }
  if (have_mission)
  {
    const bool ok = mission.value("ok", false);
    page << "<h2>Mission " << html(mission.value("mission", std::string())) << "</h2>\n<p class=\"" << (ok ? "" : "bad")
         << "\">" << (mission.value("success", false) ? "Succeeded" : "Failed") << ": "
         << html(mission.value("message", std::string())) << "</p>\n<table>\n";
    auto row = [&](const std::string& name, const std::string& value) {
      page << "<tr><td>" << html(name) << "</td><td>" << html(value) << "</td></tr>\n";
    };
    auto number = [&](const char* key, int digits) {
      return mission.contains(key) && mission[key].is_number() ? formatNumber(mission[key].get<double>(), digits)
                                                               : std::string("–");
    };
    row("target " + mission.value("target", std::string()) + " found",
        std::string(mission.value("found", false) ? "yes" : "no") + ", after " + number("found_after_s", 1) +
            " s; remembered " + number("target_error_m", 2) + " m from where it is");
    row("returned home", std::string(mission.value("returned", false) ? "yes" : "no") + ", final distance " +
                             number("final_distance_m", 2) + " m");
    row("collisions", std::to_string(mission.value("collisions", nlohmann::json::array()).size()));
    row("path driven", number("path_length_m", 2) + " m in " + number("sim_duration_s", 1) + " s (sim)");
    page << "</table>\n";
  }
  for (const char* picture : {"path.png", "panel.png", "rviz.png", "pan.png", "rates.png"})
  {
    const std::string path = dir + picture;
    std::ifstream f(path, std::ios::binary);
    if (!f)
      continue;
    const std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    page << "<h2>" << picture << "</h2>\n";
    if (std::string(picture) == "path.png")  // what the marks mean: the picture has room for names only
      page << "<p>The long-term memory built on the way (black occupied, grey unknown), the path (start ring, end "
              "disc), home, the target where it is (disc) and where the memory put it (ring), the new obstacle the "
              "mission put on the way home after the target was found, and the other remembered objects (grey "
              "rings).</p>\n";
    page << "<img alt=\"" << picture << "\" src=\"data:image/png;base64," << base64(bytes) << "\">\n";
  }
  if (have_report)
  {
    page << "<h2>Topics</h2>\n<table><tr><th>topic</th><th>messages</th><th>rate [Hz]</th><th>latency since the "
            "stamp, p50 / p95 [ms]</th></tr>\n";
    for (const auto& [name, t] : report.at("topics").items())
    {
      std::string latency = "-";
      double p50, p95;
      if (latencyOf(t, p50, p95))
        latency = formatNumber(p50, 1) + " / " + formatNumber(p95, 1);
      page << "<tr><td><code>" << html(name) << "</code></td><td>" << t.value("messages", 0) << "</td><td>"
           << formatNumber(t.value("rate_hz", 0.0), 2) << "</td><td>" << latency << "</td></tr>\n";
    }
    page << "</table>\n";
    // The tf pairs topic_report checked: which failed and why (the verdict alone did not say).
    const auto frames = report.find("frames");
    if (frames != report.end() && frames->is_array() && !frames->empty())
    {
      page << "<h2>tf</h2>\n<table><tr><th>parent</th><th>child</th><th>resolves</th><th>translation [m] or why "
              "not</th></tr>\n";
      for (const auto& f : *frames)
      {
        if (!f.is_object())
          continue;
        const bool resolved = f.value("ok", false);
        std::string detail;
        const auto translation = f.find("translation");
        if (resolved && translation != f.end() && translation->is_array())
          for (const auto& v : *translation)
            detail += (detail.empty() ? "" : ", ") + (v.is_number() ? formatNumber(v.get<double>(), 3) : "?");
        else if (f.contains("error") && f["error"].is_string())
          detail = f["error"].get<std::string>();
        page << "<tr" << (resolved ? "" : " class=\"bad\"") << "><td><code>" << html(f.value("parent", std::string()))
             << "</code></td><td><code>" << html(f.value("child", std::string())) << "</code></td><td>"
             << (resolved ? "yes" : "NO") << "</td><td>" << html(detail) << "</td></tr>\n";
      }
      page << "</table>\n";
    }
  }
  if (have_fix)
  {
    page << "<h2>Fixations</h2>\n<table><tr><th>t [s]</th><th>object</th><th>pan [deg]</th></tr>\n";
    for (const auto& f : fixations.value("fixations", nlohmann::json::array()))
      page << "<tr><td>" << formatNumber(f.value("t", 0.0), 1) << "</td><td>" << html(f.value("object", ""))
           << "</td><td>" << formatNumber(f.value("pan_deg", 0.0), 1) << "</td></tr>\n";
    page << "</table>\n";
  }
  if (have_recognition)
    page << "<h2>Recognition</h2>\n<p>" << recognition.value("correct", 0) << " right labels, "
         << recognition.value("wrong", 0) << " wrong, " << recognition.value("mislocated", 0) << " mislocated, in "
         << recognition.value("objects_messages", 0) << " objects messages.</p>\n";
  if (!missing.empty())
  {
    page << "<p>Not in this run's folder:";
    for (const auto& m : missing)
      page << " <code>" << html(m) << "</code>";
    page << "</p>\n";
  }
  page << "</body></html>\n";
  biovision_common::writeFileAtomically(dir + "report.html", page.str());
  written.push_back(dir + "report.html");
  return written;
}
}  // namespace biovision_monitor
