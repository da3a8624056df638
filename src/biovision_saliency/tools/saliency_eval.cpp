// saliency_eval: our colour saliency and OpenCV's static saliency methods against human fixation maps
// (MIT1003), in the same run; and a motion check on Middlebury flow (moving vs static pixels).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <opencv2/core/utility.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/saliency.hpp>

#include "biovision_common/eval/middlebury_flow.hpp"
#include "biovision_common/eval/saliency_metrics.hpp"
#include "biovision_saliency/saliency_pipeline.hpp"
#include "biovision_common/tool_arguments.hpp"

using biovision_common::SaliencyMetrics;
using biovision_common::MiddleburyFlow;

using namespace biovision_saliency;
namespace fs = std::filesystem;

namespace
{
const char* kUsage =
    "usage: saliency_eval --stimuli DIR --fixations DIR [--json FILE] [--flow DIR] [--threads N] [--limit N]\n"
    "                     [--final-blur SIGMA]  (our map's final smoothing, reference px; default 16)\n"
    "  For every stimulus with a fixation map of the same name: ours (colour saliency, 160 px working\n"
    "  width), OpenCV StaticSaliencySpectralResidual and StaticSaliencyFineGrained, in the same run.\n"
    "  Metrics against the fixation map: CC, SIM, KL (lower is better), NSS on the map's peaks; median\n"
    "  ms per image with the input at 160x120 and 320x240.\n"
    "  --flow DIR: Middlebury flow root (other-data/<Seq>/frame10,11.png + other-gt-flow/<Seq>/flow10.flo):\n"
    "  mean motion saliency on pixels the ground truth moves (|flow - median| > 1 px) vs static ones.\n";

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

cv::Mat toFloat(const cv::Mat& m)
{
  cv::Mat f;
  m.convertTo(f, CV_32F);
  return f;
}
}  // namespace

int main(int argc, char** argv)
{
  const biovision_common::ToolArguments args(
      argc, argv, kUsage, {"--stimuli", "--fixations", "--json", "--flow", "--threads", "--limit", "--final-blur"});
  const std::string stimuli = args.get("--stimuli"), fixations = args.get("--fixations");
  const std::string json_path = args.get("--json"), flow_root = args.get("--flow");
  const int threads = static_cast<int>(args.number("--threads", 2));
  const int limit = static_cast<int>(args.number("--limit", 0));
  const double final_blur = args.number("--final-blur", SaliencyParameters().final_blur);
  if (stimuli.empty() || fixations.empty() || !fs::is_directory(stimuli) || !fs::is_directory(fixations))
  {
    std::cerr << "saliency_eval: --stimuli and --fixations must be folders\n" << kUsage;
    return 2;
  }
  cv::setNumThreads(threads);

  std::map<std::string, std::pair<int, Method>> methods;  // name -> (working width for ours, method)
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
  const std::vector<std::pair<std::string, Method>> all = {{"biovision", ours(160)}, {"spectral_residual", spectral},
                                                           {"fine_grained", fine}};

  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(stimuli))
    if (e.is_regular_file() && fs::exists(fs::path(fixations) / e.path().filename()))
      files.push_back(e.path());
  std::sort(files.begin(), files.end());
  if (limit > 0 && static_cast<int>(files.size()) > limit)
    files.resize(limit);
  if (files.empty())
  {
    std::cerr << "saliency_eval: no stimulus with a fixation map of the same name\n";
    return 2;
  }

  std::map<std::string, SaliencyMetrics> sum;
  std::map<std::string, std::vector<double>> ms160, ms320;
  for (const auto& file : files)
  {
    const cv::Mat img = cv::imread(file.string(), cv::IMREAD_COLOR);
    cv::Mat fix = cv::imread((fs::path(fixations) / file.filename()).string(), cv::IMREAD_GRAYSCALE);
    if (img.empty() || fix.empty())
    {
      std::cerr << "saliency_eval: cannot read " << file << "\n";
      return 2;
    }
    const cv::Mat fixf = toFloat(fix);
    cv::Mat small160, small320;
    cv::resize(img, small160, cv::Size(160, 120), 0, 0, cv::INTER_AREA);
    cv::resize(img, small320, cv::Size(320, 240), 0, 0, cv::INTER_AREA);
    for (const auto& [name, method] : all)
    {
      cv::Mat map = method(img), resized;
      cv::resize(map, resized, fixf.size(), 0, 0, cv::INTER_LINEAR);
      const SaliencyMetrics m = SaliencyMetrics::compute(resized, fixf);
      sum[name].cc += m.cc / files.size();
      sum[name].sim += m.sim / files.size();
      sum[name].kl += m.kl / files.size();
      sum[name].nss += m.nss / files.size();
      ms160[name].push_back(medianMs([&] { method(small160); }, 3));
      ms320[name].push_back(medianMs([&] { method(small320); }, 3));
    }
  }
  auto median = [](std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
  };
  std::ostringstream out;
  out << "{\n  \"command\": \"rosrun biovision_saliency saliency_eval --stimuli DIR --fixations DIR --json FILE\",\n"
      << "  \"images\": " << files.size() << ",\n  \"threads\": " << threads << ",\n";
  for (const auto& [name, method] : all)
  {
    (void)method;
    const auto& m = sum[name];
    char buf[300];
    std::snprintf(buf, sizeof buf,
                  "  \"%s\": {\"cc\": %.4f, \"sim\": %.4f, \"kl\": %.4f, \"nss\": %.4f, \"ms_160\": %.3f, \"ms_320\": %.3f},\n",
                  name.c_str(), m.cc, m.sim, m.kl, m.nss, median(ms160[name]), median(ms320[name]));
    out << buf;
    std::fprintf(stderr, "%-18s CC %.3f SIM %.3f KL %.3f NSS %.3f  %.2f ms @160  %.2f ms @320\n", name.c_str(), m.cc,
                 m.sim, m.kl, m.nss, median(ms160[name]), median(ms320[name]));
  }
  // Motion check: our motion channel on two consecutive frames, ground-truth moving vs static pixels.
  std::ostringstream motion;
  if (!flow_root.empty())
  {
    const fs::path data = fs::path(flow_root) / "other-data", gt = fs::path(flow_root) / "other-gt-flow";
    motion << "{";
    bool first = true;
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
      char buf[200];
      std::snprintf(buf, sizeof buf, "%s\"%s\": {\"moving_fraction\": %.3f, \"mean_on_moving\": %.4f, \"mean_on_static\": %.4f}",
                    first ? "" : ", ", e.path().filename().c_str(), double(moving) / std::max(1L, moving + still),
                    moving ? moving_sum / moving : 0.0, still ? static_sum / still : 0.0);
      motion << buf;
      std::fprintf(stderr, "motion %-12s moving %.1f%%  mean saliency on moving %.3f, on static %.3f\n",
                   e.path().filename().c_str(), 100.0 * moving / std::max(1L, moving + still),
                   moving ? moving_sum / moving : 0.0, still ? static_sum / still : 0.0);
      first = false;
    }
    motion << "}";
  }
  const auto& o = sum["biovision"];
  char ratios[300];
  std::snprintf(ratios, sizeof ratios,
                "  \"ratio_biovision_vs_fine_grained\": {\"cc\": %.3f, \"nss\": %.3f, \"time_160\": %.3f},\n"
                "  \"ratio_biovision_vs_spectral_residual\": {\"cc\": %.3f, \"nss\": %.3f, \"time_160\": %.3f},\n",
                o.cc / sum["fine_grained"].cc, o.nss / sum["fine_grained"].nss,
                median(ms160["biovision"]) / median(ms160["fine_grained"]), o.cc / sum["spectral_residual"].cc,
                o.nss / sum["spectral_residual"].nss, median(ms160["biovision"]) / median(ms160["spectral_residual"]));
  out << ratios;
  out << "  \"notes\": \"Ratios: ours / peer (cc, nss > 1 = better agreement with human fixations; time < 1 = "
         "faster). Data: MIT1003 (Judd et al. 2009), Middlebury flow (Baker et al. 2011).\"";
  if (!flow_root.empty())
    out << ",\n  \"motion\": " << motion.str();
  out << "\n}\n";
  std::cout << out.str();
  if (!json_path.empty())
  {
    std::ofstream f(json_path);
    f << out.str();
    if (!f)
    {
      std::cerr << "saliency_eval: cannot write " << json_path << "\n";
      return 1;
    }
  }
  return 0;
}
