// stereo_eval: BioBin and the stereo matchers a user would otherwise pick, on Middlebury scenes with
// ground truth, in the same run with the same search range and thread count.
#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <functional>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include <opencv2/calib3d.hpp>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/stereo.hpp>

#include "biovision_common/cpu_features.hpp"
#include "biovision_stereo/bio_bin_matcher.hpp"
#include "biovision_stereo/hamming.hpp"
#include "biovision_stereo/semi_global_aggregation.hpp"
#include "biovision_common/eval/disparity_metrics.hpp"
#include "biovision_common/eval/middlebury_dataset.hpp"
#include "biovision_common/tool_options.hpp"
#include "biovision_v1/fourier_transform.hpp"

using biovision_common::DisparityMetrics;
using biovision_common::MiddleburyDataset;
using biovision_common::StereoScene;

using namespace biovision_stereo;

namespace
{
const char* kDescription =
    "BioBin and the stereo matchers a user would otherwise pick, on Middlebury scenes with ground truth, in the same\n"
    "run with the same search range and thread count. Methods: biobin (the struct's defaults), biobin_thesis\n"
    "(the thesis' iterative filter), biobin_sgm (semi-global aggregation), biobin_filled (defaults with occlusion\n"
    "filling and the 3x3 median), biobin_fast (defaults, one scale, lambda\n"
    "16), biobin_fast_thesis, bm,\n"
    "bm_fast (StereoBM on the quarter-size pair, the fast mode's resolution), sgbm (MODE_SGBM_3WAY), binary_sgbm\n"
    "(contrib). Metrics on the non-occluded mask when there is one: bad0.5/1/2/4 (%, invalid = bad), avgerr over\n"
    "valid estimates, invalid %, seconds per pair (median of --repeats runs, the methods' runs interleaved round by "
    "round, after warm-up runs until the DFT "
    "plans are measured), BioBin's stage\n"
    "times. --split train|report|all picks the scenes by the fixed whole-scene split written in the JSON: tune on\n"
    "train, report on report. Prints the JSON.";

// Whole-scene split of the Middlebury scenes: parameters are chosen on `train` only (the v2 quartet Cones,
// Teddy, Tsukuba, Venus tuned the thesis defaults before, so it is train); every other scene is `report`.
// Scenes of one family (Baby1-3, Cloth1-4, ...) stay on one side. Names compare case-insensitively.
const std::vector<std::string> kTrainScenes{"cones",  "teddy",      "tsukuba",    "venus",  "aloe",   "baby1",
                                            "baby2",  "baby3",      "books",      "cloth1", "cloth2", "cloth3",
                                            "cloth4", "lampshade1", "lampshade2", "barn1",  "barn2"};

std::string lower(std::string s)
{
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

bool isTrainScene(const std::string& name)
{
  return std::find(kTrainScenes.begin(), kTrainScenes.end(), lower(name)) != kTrainScenes.end();
}

/// Overrides of BioBin's parameters from the command line (for tuning on the train split).
struct Overrides
{
  double sgm_p1 = -1, sgm_p2 = -1, sgm_p2_barrier = -1;
  int sgm_paths = 0;
  int fill_occlusions = -1;  // -1: the default; 0 / 1
  double left_right_tolerance = -1;
  int median_filter = -1;  // -1: the default; 0 / 1
  void apply(BioBinParameters& p) const
  {
    if (median_filter >= 0)
      p.median_filter = median_filter == 1;
    if (left_right_tolerance >= 0)
      p.left_right_tolerance = left_right_tolerance;
    if (fill_occlusions >= 0)
      p.fill_occlusions = fill_occlusions == 1;
    if (sgm_p1 >= 0)
      p.sgm_p1 = sgm_p1;
    if (sgm_p2 >= 0)
      p.sgm_p2 = sgm_p2;
    if (sgm_p2_barrier >= 0)
      p.sgm_p2_barrier = sgm_p2_barrier;
    if (sgm_paths > 0)
      p.sgm_paths = sgm_paths;
  }
};
Overrides overrides;
BioBinMatcher::StageTimes last_times;

using Matcher = std::function<cv::Mat(const StereoScene&)>;  // returns CV_32F disparity, < 0 invalid

cv::Mat fromFixedPoint(const cv::Mat& d16, float scale_to_input)
{
  cv::Mat d;
  d16.convertTo(d, CV_32F, scale_to_input / 16.0);
  d.setTo(-1.f, d16 < 0);
  return d;
}

int multipleOf16(int md)
{
  return (md + 1 + 15) / 16 * 16;  // disparities 0..md inclusive
}

cv::Mat grey(const cv::Mat& bgr)
{
  cv::Mat g;
  cv::cvtColor(bgr, g, cv::COLOR_BGR2GRAY);
  return g;
}

std::map<std::string, Matcher> makeMatchers(std::map<std::string, std::unique_ptr<BioBinMatcher>>& keep)
{
  std::map<std::string, Matcher> m;
  const auto biobin = [&keep](const std::string& name, const std::vector<double>& wavelengths,
                              const std::string& aggregation, bool filled = false, CostSimd simd = bestCostSimd()) {
    return [&keep, name, wavelengths, aggregation, filled, simd](const StereoScene& s) {
      auto& matcher = keep[name + ":" + s.name];
      if (!matcher)
      {
        BioBinParameters p;
        p.max_disparity = s.max_disparity;
        if (!wavelengths.empty())
          p.wavelengths = wavelengths;
        if (!aggregation.empty())
          p.aggregation = aggregation;
        if (filled)  // the post-processing chosen on the train scenes, off in the robot's defaults
          p.fill_occlusions = p.median_filter = true;
        overrides.apply(p);
        matcher = std::make_unique<BioBinMatcher>(p);
        matcher->setCostSimd(simd);
      }
      cv::Mat d = matcher->compute(s.left, s.right).disparity;
      last_times = matcher->lastTimes();
      return d;
    };
  };
  m["biobin"] = biobin("biobin", {}, "");
  m["biobin_thesis"] = biobin("biobin_thesis", {}, "iterative");
  // The defaults with the cost-volume loops on the baseline instruction set (the fallback): the same
  // disparities bit for bit, so its time against biobin's is the SIMD path's gain (not in the default list).
  m["biobin_generic"] = biobin("biobin_generic", {}, "", false, CostSimd::kGeneric);
  m["biobin_sgm"] = biobin("biobin_sgm", {}, "semi_global");
  m["biobin_filled"] = biobin("biobin_filled", {}, "", true);
  m["biobin_fast"] = biobin("biobin_fast", {16.0}, "");
  m["biobin_fast_thesis"] = biobin("biobin_fast_thesis", {16.0}, "iterative");
  m["bm"] = [](const StereoScene& s) {
    auto bm = cv::StereoBM::create(multipleOf16(s.max_disparity), 15);
    cv::Mat d16;
    bm->compute(grey(s.left), grey(s.right), d16);
    return fromFixedPoint(d16, 1.f);
  };
  m["bm_fast"] = [](const StereoScene& s) {
    cv::Mat l, r;
    const cv::Size q(std::max(1, s.left.cols / 4), std::max(1, s.left.rows / 4));
    cv::resize(grey(s.left), l, q, 0, 0, cv::INTER_AREA);
    cv::resize(grey(s.right), r, q, 0, 0, cv::INTER_AREA);
    auto bm = cv::StereoBM::create(multipleOf16((s.max_disparity + 3) / 4), 7);
    cv::Mat d16, up;
    bm->compute(l, r, d16);
    cv::resize(fromFixedPoint(d16, float(s.left.cols) / q.width), up, s.left.size(), 0, 0, cv::INTER_NEAREST);
    return up;
  };
  m["sgbm"] = [](const StereoScene& s) {
    const int block = 5;
    auto sgbm = cv::StereoSGBM::create(0, multipleOf16(s.max_disparity), block, 8 * 3 * block * block,
                                       32 * 3 * block * block, 1, 63, 10, 100, 32, cv::StereoSGBM::MODE_SGBM_3WAY);
    cv::Mat d16;
    sgbm->compute(s.left, s.right, d16);
    return fromFixedPoint(d16, 1.f);
  };
  m["binary_sgbm"] = [](const StereoScene& s) {
    auto sgbm = cv::stereo::StereoBinarySGBM::create(0, multipleOf16(s.max_disparity), 9, 100, 1000, 1, 0, 5, 400, 200,
                                                     cv::stereo::StereoBinarySGBM::MODE_SGBM);
    sgbm->setBinaryKernelType(cv::stereo::CV_MODIFIED_CENSUS_TRANSFORM);
    sgbm->setSpekleRemovalTechnique(cv::stereo::CV_SPECKLE_REMOVAL_AVG_ALGORITHM);
    sgbm->setSubPixelInterpolationMethod(cv::stereo::CV_SIMETRICV_INTERPOLATION);
    cv::Mat d;
    sgbm->compute(grey(s.left), grey(s.right), d);
    if (d.type() == CV_16S)
      return fromFixedPoint(d, 1.f);
    cv::Mat f;
    d.convertTo(f, CV_32F);
    return f;
  };
  return m;
}

nlohmann::ordered_json stageJson(const BioBinMatcher::StageTimes& t)
{
  return {{"prepare", t.prepare}, {"cells", t.cells}, {"costs_dog", t.costs}, {"fusion", t.fusion},
          {"spatial", t.spatial}, {"wta", t.wta},     {"total", t.total}};
}

nlohmann::ordered_json metricsJson(const DisparityMetrics& m, double seconds)
{
  return {{"bad0.5", m.bad05},  {"bad1.0", m.bad1},     {"bad2.0", m.bad2},           {"bad4.0", m.bad4},
          {"avgerr", m.avgerr}, {"invalid", m.invalid}, {"seconds_per_pair", seconds}};
}
}  // namespace

int main(int argc, char** argv)
{
  std::map<std::string, std::unique_ptr<BioBinMatcher>> keep;
  const auto matchers = makeMatchers(keep);
  std::vector<std::string> method_names;
  for (const auto& [name, matcher] : matchers)
    method_names.push_back(name);

  std::string dataset, json_path;
  std::vector<std::string> methods{"biobin", "biobin_filled", "biobin_thesis", "biobin_fast", "biobin_fast_thesis",
                                   "bm",     "bm_fast",       "sgbm",          "binary_sgbm"},
      only_scenes;
  std::string split = "all";
  int threads = 2, repeats = 3;
  biovision_common::ToolOptions options("stereo_eval", kDescription);
  CLI::App& app = options.app();
  app.add_option("--dataset", dataset,
                 "one Middlebury scene or a folder of scenes (v3 im0/im1/calib.txt/disp0GT.pfm, v2 quartet, 2001-2006 "
                 "layouts; see MiddleburyDataset)")
      ->required();
  app.add_option("--json", json_path, "also write the results to this file");
  app.add_option("--methods", methods, "methods, comma-separated")->delimiter(',')->check(CLI::IsMember(method_names));
  app.add_option("--threads", threads, "OpenCV threads, every method")->check(biovision_common::kPositive);
  app.add_option("--scenes", only_scenes, "only these scenes, comma-separated (default: all)")->delimiter(',');
  app.add_option("--repeats", repeats, "timed runs per pair (median) after the warm-up")
      ->check(biovision_common::kPositive);
  app.add_option("--split", split, "scenes of this whole-scene split only (train: tuning; report: never tuned on)")
      ->check(CLI::IsMember({"train", "report", "all"}));
  app.add_option("--sgm-p1", overrides.sgm_p1, "override BioBinParameters::sgm_p1 (tuning)");
  app.add_option("--sgm-p2", overrides.sgm_p2, "override BioBinParameters::sgm_p2 (tuning)");
  app.add_option("--sgm-p2-barrier", overrides.sgm_p2_barrier, "override BioBinParameters::sgm_p2_barrier (tuning)");
  app.add_option("--sgm-paths", overrides.sgm_paths, "override BioBinParameters::sgm_paths (tuning)");
  app.add_option("--fill-occlusions", overrides.fill_occlusions,
                 "override BioBinParameters::fill_occlusions: 0 or 1 (tuning)")
      ->check(CLI::Range(0, 1));
  app.add_option("--median-filter", overrides.median_filter,
                 "override BioBinParameters::median_filter: 0 or 1 (tuning)")
      ->check(CLI::Range(0, 1));
  app.add_option("--left-right-tolerance", overrides.left_right_tolerance,
                 "override BioBinParameters::left_right_tolerance (tuning)");
  options.parse(argc, argv);

  cv::setNumThreads(threads);
  std::vector<StereoScene> scenes;
  try
  {
    scenes = MiddleburyDataset::load(dataset);
  }
  catch (const std::exception& e)
  {
    std::cerr << "stereo_eval: " << e.what() << "\n";
    return 2;
  }
  // Scene names as the split writes them (any case); a name that matches no scene is refused, not
  // silently dropped (an empty run would read as a result).
  std::vector<std::string> wanted;
  for (const std::string& name : only_scenes)
    wanted.push_back(lower(name));
  std::string available;
  for (const StereoScene& s : scenes)
    available += (available.empty() ? "" : ", ") + s.name;
  for (size_t i = 0; i < wanted.size(); ++i)
    if (std::none_of(scenes.begin(), scenes.end(), [&](const StereoScene& s) { return lower(s.name) == wanted[i]; }))
    {
      std::cerr << "stereo_eval: --scenes: no scene '" << only_scenes[i] << "' in " << dataset
                << " (it has: " << available << ")\n";
      return 2;
    }
  if (!wanted.empty())
    scenes.erase(std::remove_if(scenes.begin(), scenes.end(),
                                [&](const StereoScene& s) {
                                  return std::find(wanted.begin(), wanted.end(), lower(s.name)) == wanted.end();
                                }),
                 scenes.end());
  if (split != "all")
    scenes.erase(std::remove_if(scenes.begin(), scenes.end(),
                                [&](const StereoScene& s) { return isTrainScene(s.name) != (split == "train"); }),
                 scenes.end());
  if (scenes.empty())
  {
    std::cerr << "stereo_eval: no scene of " << dataset << " is left with --split " << split
              << (wanted.empty() ? "" : " and --scenes") << " (it has: " << available << ")\n";
    return 2;
  }

  std::map<std::string, std::vector<DisparityMetrics>> per_method;
  std::map<std::string, std::vector<double>> seconds;
  std::map<std::string, std::vector<BioBinMatcher::StageTimes>> stages;  // of the last timed run per scene
  nlohmann::ordered_json scenes_json = nlohmann::ordered_json::object();
  for (const StereoScene& s : scenes)
  {
    if (s.ground_truth.empty())
    {
      std::cerr << "stereo_eval: " << s.name << " has no ground truth, skipped\n";
      continue;
    }
    nlohmann::ordered_json& scene_json = scenes_json[s.name];
    scene_json["size"] = {s.left.cols, s.left.rows};
    scene_json["max_disparity"] = s.max_disparity;
    // Every method warmed up first, then the timed runs interleaved round by round (each method once per
    // round): a burst of load on this shared machine then lands on ours and the peers alike, not on
    // whichever method was running (the same-run ratio had moved by +-15% between runs).
    std::map<std::string, cv::Mat> result;
    std::map<std::string, std::vector<double>> t;
    std::map<std::string, BioBinMatcher::StageTimes> times;
    for (const auto& name : methods)
    {
      const Matcher& match = matchers.at(name);
      biovision_v1::FourierTransform::warmUp([&] { result[name] = match(s); });  // until its DFT plans are measured
    }
    for (int r = 0; r < repeats; ++r)
      for (const auto& name : methods)
      {
        const auto start = std::chrono::steady_clock::now();
        result[name] = matchers.at(name)(s);
        t[name].push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
        times[name] = last_times;  // BioBin's stages of this method's last timed run
      }
    for (const auto& name : methods)
    {
      std::vector<double>& runs = t[name];
      std::nth_element(runs.begin(), runs.begin() + runs.size() / 2, runs.end());
      const double sec = runs[runs.size() / 2];
      const DisparityMetrics m = DisparityMetrics::compute(result[name], s.ground_truth, s.nonoccluded);
      per_method[name].push_back(m);
      seconds[name].push_back(sec);
      scene_json[name] = metricsJson(m, sec);
      if (name.rfind("biobin", 0) == 0)
      {
        scene_json[name]["stage_ms"] = stageJson(times[name]);
        stages[name].push_back(times[name]);
      }
      std::fprintf(stderr, "%-12s %-12s bad1.0 %6.2f%%  bad2.0 %6.2f%%  invalid %5.1f%%  avgerr %.3f  %.4f s\n",
                   s.name.c_str(), name.c_str(), m.bad1, m.bad2, m.invalid, m.avgerr, sec);
    }
  }

  std::string command = "rosrun biovision_stereo stereo_eval";
  for (int i = 1; i < argc; ++i)
    command += std::string(" ") + (std::string(argv[i]).find(".json") != std::string::npos ? "FILE" : argv[i]);
  nlohmann::ordered_json results;
  results["command"] = command;
  results["dataset"] = dataset;
  results["threads"] = threads;
  results["scenes_evaluated"] = per_method.empty() ? 0 : per_method.begin()->second.size();
  results["split"] = {{"name", split},
                      {"train_scenes", kTrainScenes},
                      {"rule", "whole scenes; parameters tuned on train only; report scenes never tuned on"}};
  results["simd"] = {{"cpu", biovision_common::CpuFeatures::host().describe()},
                     {"hamming", "byte windows in the cost-volume clone"},
                     {"cost_volume", costSimdName(bestCostSimd())},
                     {"semi_global_aggregation", SemiGlobalAggregation::name(SemiGlobalAggregation::bestSimd())}};
  std::map<std::string, DisparityMetrics> means;
  std::map<std::string, double> mean_seconds;
  nlohmann::ordered_json stage_means = nlohmann::ordered_json::object();  // BioBin's stages [ms], mean
  for (const auto& name : methods)
  {
    const auto& ms = per_method[name];
    DisparityMetrics mean;
    double sec = 0;
    for (size_t i = 0; i < ms.size(); ++i)
    {
      mean.bad05 += ms[i].bad05 / ms.size();
      mean.bad1 += ms[i].bad1 / ms.size();
      mean.bad2 += ms[i].bad2 / ms.size();
      mean.bad4 += ms[i].bad4 / ms.size();
      mean.avgerr += ms[i].avgerr / ms.size();
      mean.invalid += ms[i].invalid / ms.size();
      sec += seconds[name][i] / ms.size();
    }
    results[name] = metricsJson(mean, sec);
    if (!stages[name].empty())
    {
      BioBinMatcher::StageTimes m;
      const double n = static_cast<double>(stages[name].size());
      for (const auto& t : stages[name])
      {
        m.prepare += t.prepare / n;
        m.cells += t.cells / n;
        m.costs += t.costs / n;
        m.fusion += t.fusion / n;
        m.spatial += t.spatial / n;
        m.wta += t.wta / n;
        m.total += t.total / n;
      }
      stage_means["stage_ms_" + name] = stageJson(m);
    }
    means[name] = mean;
    mean_seconds[name] = sec;
  }
  for (const auto& [key, value] : stage_means.items())  // after the methods: one per-stage table
    results[key] = value;
  results["notes"] =
      "biobin = BioBinParameters defaults (semi-global aggregation of the finest level, beyond the thesis), "
      "biobin_filled = the defaults plus occlusion filling and a 3x3 median (chosen on the train scenes; off in the "
      "robot's defaults: on its tabletop bag they turn invalid pixels into wrong ones), "
      "biobin_thesis = the thesis' iterative spatial filter; *_fast = one scale (lambda 16, quarter size). "
      "seconds_per_pair = the median of the timed runs (every method warmed up, then the methods' runs interleaved "
      "round by round, so that a burst of load on the machine lands on all of them), mean over scenes. "
      "stage_ms_* = BioBin's stage times [ms] (lastTimes() of the last timed run, mean over scenes; prepare = each "
      "level's "
      "area averaging and colour conversions; costs_dog = the costs and the DoG along disparity, computed together one "
      "image row at a time). split: "
      "parameters were tuned on the train scenes only; with split report, none of the scenes was tuned on. "
      "Ratios: ours / peer, same run (time < 1 = faster, bad1.0 < 1 = fewer errors). Data: Middlebury "
      "(Scharstein & Szeliski 2002/2003, Scharstein & Pal 2007, Hirschmueller & Scharstein 2007).";
  // Ratios against the peers, same run: time (ours / peer, < 1 = faster) and bad 1.0 (ours / peer).
  auto ratio = [&](const std::string& ours, const std::string& peer) {
    if (!means.count(ours) || !means.count(peer) || mean_seconds[peer] <= 0 || means[peer].bad1 <= 0)
      return;
    results["ratio_" + ours + "_vs_" + peer] = {{"time", mean_seconds[ours] / mean_seconds[peer]},
                                                {"bad1.0", means[ours].bad1 / means[peer].bad1}};
  };
  for (const char* ours : {"biobin", "biobin_filled", "biobin_thesis", "biobin_sgm"})
  {
    ratio(ours, "sgbm");
    ratio(ours, "binary_sgbm");
  }
  for (const char* ours : {"biobin_fast", "biobin_fast_thesis"})
  {
    ratio(ours, "bm_fast");
    ratio(ours, "bm");
  }
  results["scenes"] = scenes_json;
  std::cout << results.dump(2) << "\n";
  if (!options.writeJson(json_path, results))
    return 1;
  return 0;
}
