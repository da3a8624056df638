// saliency_eval: our colour saliency and OpenCV's static saliency methods against human fixation maps
// (MIT1003), in the same run; and a motion check on Middlebury flow (moving vs static pixels).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <iostream>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include <opencv2/core/utility.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/saliency.hpp>

#include "biovision_common/eval/middlebury_flow.hpp"
#include "biovision_common/eval/saliency_metrics.hpp"
#include "biovision_saliency/saliency_pipeline.hpp"
#include "biovision_common/tool_options.hpp"

using biovision_common::MiddleburyFlow;
using biovision_common::SaliencyMetrics;

using namespace biovision_saliency;
namespace fs = std::filesystem;

namespace
{
const char* kDescription =
    "For every stimulus with a fixation map of the same name: ours (colour saliency, 160 px working width),\n"
    "OpenCV StaticSaliencySpectralResidual and StaticSaliencyFineGrained, in the same run. Metrics against the\n"
    "fixation map: CC, SIM, KL (lower is better), NSS on the map's peaks; median ms per image with the input at\n"
    "160x120 and 320x240. With --flow, the motion check. Prints a table; --json writes the figures.";

struct Options
{
  std::string stimuli, fixations, json_path, flow_root;
  int threads = 2;
  int limit = 0;  // 0: every stimulus
  double final_blur = SaliencyParameters().final_blur;
};

/// --final-blur as SaliencyParameters accepts it: its bounds are written there only.
const CLI::Validator kFinalBlurCheck(
    [](std::string& value) {
      SaliencyParameters p;
      if (!CLI::detail::lexical_cast(value, p.final_blur))
        return std::string();  // not a number: the type check reports it
      try
      {
        p.validate();
      }
      catch (const std::invalid_argument& e)
      {
        return std::string(e.what());
      }
      return std::string();
    },
    "");

Options parseOptions(int argc, char** argv)
{
  Options o;
  biovision_common::ToolOptions options("saliency_eval", kDescription);
  CLI::App& app = options.app();
  app.add_option("--stimuli", o.stimuli, "folder of stimulus images")->required()->check(CLI::ExistingDirectory);
  app.add_option("--fixations", o.fixations, "folder of fixation maps, named as the stimuli")
      ->required()
      ->check(CLI::ExistingDirectory);
  app.add_option("--json", o.json_path, "write the figures to this file");
  app.add_option("--flow", o.flow_root,
                 "Middlebury flow root (other-data/<Seq>/frame10,11.png + other-gt-flow/<Seq>/flow10.flo): mean motion "
                 "saliency on pixels the ground truth moves (|flow - median| > 1 px) vs static ones")
      ->check(CLI::ExistingDirectory);
  app.add_option("--threads", o.threads, "OpenCV threads")->check(biovision_common::kPositive);
  app.add_option("--limit", o.limit, "at most this many stimuli, in name order (0: all)")
      ->check(biovision_common::kNonNegative);
  app.add_option("--final-blur", o.final_blur, "our map's final smoothing sigma, reference px")->check(kFinalBlurCheck);
  options.parse(argc, argv);
  return o;
}

using Method = std::function<cv::Mat(const cv::Mat&)>;  // BGR in, CV_32F map out (any size)

double medianMs(const std::function<void()>& f, int n = 5)
{
  f();
  std::vector<double> t;
  for (int i = 0; i < n; ++i)
  {
    const auto s = std::chrono::steady_clock::now();
    f();
    t.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - s).count());
  }
  std::nth_element(t.begin(), t.begin() + n / 2, t.end());
  return t[n / 2];
}

double median(std::vector<double> v)
{
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

cv::Mat toFloat(const cv::Mat& m)
{
  cv::Mat f;
  m.convertTo(f, CV_32F);
  return f;
}

/// Ours at 160 px working width, then OpenCV's two static saliency methods, in the order they are reported.
std::vector<std::pair<std::string, Method>> makeMethods(double final_blur)
{
  auto ours = [final_blur](int width) {
    return [width, final_blur](const cv::Mat& bgr) {
      SaliencyParameters p;
      p.working_width = width;
      p.final_blur = final_blur;
      static thread_local std::map<int, std::unique_ptr<SaliencyPipeline>> pipelines;
      auto& pipeline = pipelines[width];
      if (!pipeline)
        pipeline = std::make_unique<SaliencyPipeline>(p);
      pipeline->reset();  // a still image: colour (no motion, no disparity)
      return pipeline->process(bgr, cv::Mat(), HeadDirection(), 0.0).map;
    };
  };
  const Method spectral = [](const cv::Mat& bgr) {
    auto s = cv::saliency::StaticSaliencySpectralResidual::create();
    cv::Mat m;
    s->computeSaliency(bgr, m);
    return toFloat(m);
  };
  const Method fine = [](const cv::Mat& bgr) {
    auto s = cv::saliency::StaticSaliencyFineGrained::create();
    cv::Mat m;
    s->computeSaliency(bgr, m);
    return toFloat(m);
  };
  return {{"biovision", ours(160)}, {"spectral_residual", spectral}, {"fine_grained", fine}};
}

/// Stimuli with a fixation map of the same name, in name order, at most `limit` (0: all).
std::vector<fs::path> listStimuli(const Options& o)
{
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(o.stimuli))
    if (e.is_regular_file() && fs::exists(fs::path(o.fixations) / e.path().filename()))
      files.push_back(e.path());
  std::sort(files.begin(), files.end());
  if (o.limit > 0 && static_cast<int>(files.size()) > o.limit)
    files.resize(o.limit);
  return files;
}

/// Per method: metrics averaged over the stimuli, and per stimulus the median ms at 160x120 and 320x240.
struct MethodScores
{
  SaliencyMetrics mean;
  std::vector<double> ms160, ms320;
};

/// Throws std::runtime_error when a stimulus or its fixation map cannot be read.
std::map<std::string, MethodScores> scoreMethods(const std::vector<fs::path>& files, const std::string& fixations,
                                                 const std::vector<std::pair<std::string, Method>>& methods)
{
  std::map<std::string, MethodScores> scores;
  for (const auto& file : files)
  {
    const cv::Mat img = cv::imread(file.string(), cv::IMREAD_COLOR);
    cv::Mat fix = cv::imread((fs::path(fixations) / file.filename()).string(), cv::IMREAD_GRAYSCALE);
    if (img.empty() || fix.empty())
      throw std::runtime_error("cannot read " + file.string());
    const cv::Mat fixf = toFloat(fix);
    cv::Mat small160, small320;
    cv::resize(img, small160, cv::Size(160, 120), 0, 0, cv::INTER_AREA);
    cv::resize(img, small320, cv::Size(320, 240), 0, 0, cv::INTER_AREA);
    for (const auto& [name, method] : methods)
    {
      cv::Mat map = method(img), resized;
      cv::resize(map, resized, fixf.size(), 0, 0, cv::INTER_LINEAR);
      const SaliencyMetrics m = SaliencyMetrics::compute(resized, fixf);
      MethodScores& s = scores[name];
      s.mean.cc += m.cc / files.size();
      s.mean.sim += m.sim / files.size();
      s.mean.kl += m.kl / files.size();
      s.mean.nss += m.nss / files.size();
      s.ms160.push_back(medianMs([&] { method(small160); }, 3));
      s.ms320.push_back(medianMs([&] { method(small320); }, 3));
    }
  }
  return scores;
}

/// Motion check: our motion channel on two consecutive frames, ground-truth moving vs static pixels, per
/// sequence of the Middlebury flow root.
nlohmann::ordered_json motionCheck(const std::string& flow_root)
{
  nlohmann::ordered_json motion = nlohmann::ordered_json::object();
  const fs::path data = fs::path(flow_root) / "other-data", gt = fs::path(flow_root) / "other-gt-flow";
  for (const auto& e : fs::directory_iterator(gt))
  {
    const fs::path flo = e.path() / "flow10.flo";
    const fs::path f10 = data / e.path().filename() / "frame10.png", f11 = data / e.path().filename() / "frame11.png";
    if (!fs::exists(flo) || !fs::exists(f10) || !fs::exists(f11))
      continue;
    const cv::Mat flow = MiddleburyFlow::read(flo.string());
    const cv::Mat a = cv::imread(f10.string()), b = cv::imread(f11.string());
    SaliencyParameters p;
    p.colour_weight = 0.0;
    SaliencyPipeline pipeline(p);
    pipeline.process(a, cv::Mat(), HeadDirection(), 0.0);
    const SaliencyResult r = pipeline.process(b, cv::Mat(), HeadDirection(), 0.1);
    cv::Mat m;
    cv::resize(r.motion, m, flow.size(), 0, 0, cv::INTER_LINEAR);
    // Ground-truth moving pixels: flow differing from the scene's median flow by more than 1 px.
    std::vector<float> us, vs;
    for (int y = 0; y < flow.rows; ++y)
      for (int x = 0; x < flow.cols; ++x)
      {
        const cv::Vec2f v = flow.at<cv::Vec2f>(y, x);
        if (v[0] == v[0])
        {
          us.push_back(v[0]);
          vs.push_back(v[1]);
        }
      }
    std::nth_element(us.begin(), us.begin() + us.size() / 2, us.end());
    std::nth_element(vs.begin(), vs.begin() + vs.size() / 2, vs.end());
    double moving_sum = 0, static_sum = 0;
    long moving = 0, still = 0;
    for (int y = 0; y < flow.rows; ++y)
      for (int x = 0; x < flow.cols; ++x)
      {
        const cv::Vec2f v = flow.at<cv::Vec2f>(y, x);
        if (v[0] != v[0])
          continue;
        const bool moves = std::hypot(v[0] - us[us.size() / 2], v[1] - vs[vs.size() / 2]) > 1.0;
        (moves ? moving_sum : static_sum) += m.at<float>(y, x);
        ++(moves ? moving : still);
      }
    const double mean_on_moving = moving ? moving_sum / moving : 0.0, mean_on_static = still ? static_sum / still : 0.0;
    motion[e.path().filename().string()] = {{"moving_fraction", double(moving) / std::max(1L, moving + still)},
                                            {"mean_on_moving", mean_on_moving},
                                            {"mean_on_static", mean_on_static}};
    std::fprintf(stderr, "motion %-12s moving %.1f%%  mean saliency on moving %.3f, on static %.3f\n",
                 e.path().filename().c_str(), 100.0 * moving / std::max(1L, moving + still), mean_on_moving,
                 mean_on_static);
  }
  return motion;
}

/// Ours against a peer: cc and nss (> 1 = better agreement) and time at 160x120 (< 1 = faster).
nlohmann::ordered_json ratioAgainst(const MethodScores& ours, const MethodScores& peer)
{
  return {{"cc", ours.mean.cc / peer.mean.cc},
          {"nss", ours.mean.nss / peer.mean.nss},
          {"time_160", median(ours.ms160) / median(peer.ms160)}};
}
}  // namespace

int main(int argc, char** argv)
{
  const Options o = parseOptions(argc, argv);
  cv::setNumThreads(o.threads);
  const auto methods = makeMethods(o.final_blur);
  const std::vector<fs::path> files = listStimuli(o);
  if (files.empty())
  {
    std::cerr << "saliency_eval: no stimulus with a fixation map of the same name\n";
    return 2;
  }
  std::map<std::string, MethodScores> scores;
  try
  {
    scores = scoreMethods(files, o.fixations, methods);
  }
  catch (const std::runtime_error& e)
  {
    std::cerr << "saliency_eval: " << e.what() << "\n";
    return 2;
  }

  nlohmann::ordered_json figures;
  figures["command"] = "rosrun biovision_saliency saliency_eval --stimuli DIR --fixations DIR --json FILE";
  figures["images"] = files.size();
  figures["threads"] = o.threads;
  for (const auto& method : methods)
  {
    const std::string& name = method.first;
    const MethodScores& s = scores[name];
    const double ms_160 = median(s.ms160), ms_320 = median(s.ms320);
    figures[name] = {{"cc", s.mean.cc},   {"sim", s.mean.sim}, {"kl", s.mean.kl},
                     {"nss", s.mean.nss}, {"ms_160", ms_160},  {"ms_320", ms_320}};
    std::fprintf(stderr, "%-18s CC %.3f SIM %.3f KL %.3f NSS %.3f  %.2f ms @160  %.2f ms @320\n", name.c_str(),
                 s.mean.cc, s.mean.sim, s.mean.kl, s.mean.nss, ms_160, ms_320);
  }
  figures["ratio_biovision_vs_fine_grained"] = ratioAgainst(scores["biovision"], scores["fine_grained"]);
  figures["ratio_biovision_vs_spectral_residual"] = ratioAgainst(scores["biovision"], scores["spectral_residual"]);
  figures["notes"] =
      "Ratios: ours / peer (cc, nss > 1 = better agreement with human fixations; time < 1 = faster). "
      "Data: MIT1003 (Judd et al. 2009), Middlebury flow (Baker et al. 2011).";
  if (!o.flow_root.empty())
    figures["motion"] = motionCheck(o.flow_root);
  std::cout << figures.dump(2) << "\n";
  if (!o.json_path.empty())
  {
    try
    {
      biovision_common::writeJsonFile(o.json_path, figures);
    }
    catch (const biovision_common::FileError& e)
    {
      std::cerr << "saliency_eval: " << e.what() << "\n";
      return 1;
    }
  }
  return 0;
}
