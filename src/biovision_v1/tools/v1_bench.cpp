// v1_bench: V1 simple + complex cells of SimpleCellBank against a direct cv::filter2D bank with the same
// kernels, in the same run, same thread count; plus keypoint time and the accuracy of the fast bank.
#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <iostream>
#include <string>
#include <vector>

#include <opencv2/core/utility.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "biovision_v1/direct_gabor_bank.hpp"
#include "biovision_v1/input_image.hpp"
#include "biovision_v1/simple_cell_bank.hpp"
#include "biovision_common/tool_arguments.hpp"
#include "biovision_v1/v1_pipeline.hpp"

using namespace biovision_v1;

namespace
{
const char* kUsage =
    "usage: v1_bench [--image FILE] [--json FILE] [--threads N] [--repeats N] [--width W --height H]\n"
    "  Simple + complex cells at 8 orientations x lambda {4, 8, 16} on a real image resized to WxH\n"
    "  (default 320x240): SimpleCellBank vs a direct cv::filter2D bank with the same kernels, same run,\n"
    "  same threads (default 2); keypoints on the same scales; max relative error of the fast bank.\n"
    "  Default image: $BIOVISION_SHARED/data/stereo/middlebury-2001-2006/Art/view1.png\n"
    "  (BIOVISION_SHARED defaults to ../shared).\n";

double medianMs(int repeats, const std::function<void()>& f)
{
  f();  // warm-up: plans, caches, thread pool
  std::vector<double> t;
  for (int r = 0; r < repeats; ++r)
  {
    const auto start = std::chrono::steady_clock::now();
    f();
    t.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
  }
  std::nth_element(t.begin(), t.begin() + t.size() / 2, t.end());
  return t[t.size() / 2];
}
}  // namespace

int main(int argc, char** argv)
{
  const char* shared_env = std::getenv("BIOVISION_SHARED");
  const std::string default_image = std::string(shared_env ? shared_env : "../shared") +
                                    "/data/stereo/middlebury-2001-2006/Art/view1.png";
  const biovision_common::ToolArguments args(argc, argv, kUsage, {"--image", "--json", "--threads", "--repeats", "--width", "--height"});
  const std::string image_path = args.get("--image", default_image), json_path = args.get("--json");
  const int threads = static_cast<int>(args.number("--threads", 2));
  const int repeats = std::max(1, static_cast<int>(args.number("--repeats", 30)));
  const int width = static_cast<int>(args.number("--width", 320)), height = static_cast<int>(args.number("--height", 240));
  cv::Mat image = cv::imread(image_path, cv::IMREAD_COLOR);
  if (image.empty())
  {
    std::cerr << "v1_bench: cannot read " << image_path << " (set --image or BIOVISION_SHARED)\n";
    return 2;
  }
  cv::resize(image, image, cv::Size(width, height), 0, 0, cv::INTER_AREA);
  cv::setNumThreads(threads);
  const cv::Mat gray = InputImage(image).gray();

  GaborParameters gabor;  // 8 orientations, lambda {4, 8, 16}
  SimpleCellBank bank(gabor);
  const DirectGaborBank direct(gabor);
  std::vector<ScaleResponses> ours, reference;
  auto complexOf = [](const std::vector<ScaleResponses>& r) {
    size_t n = 0;
    for (const auto& s : r)
      n += s.complexCells().size();
    return n;
  };
  const double ours_ms = medianMs(repeats, [&] {
    ours = bank.compute(gray);
    complexOf(ours);
  });
  const double direct_ms = medianMs(std::max(3, repeats / 5), [&] {
    reference = direct.compute(gray);
    complexOf(reference);
  });
  const double max_rel_err = DirectGaborBank::maxRelativeError(ours, reference);

  V1Pipeline pipeline{V1Pipeline::Parameters()};
  size_t keypoints = 0;
  const double keypoints_ms = medianMs(repeats, [&] { keypoints = pipeline.process(image).keypoints.size(); });

  const double speedup = ours_ms > 0 ? direct_ms / ours_ms : 0.0;
  char json[1024];
  std::snprintf(json, sizeof json,
                "{\n  \"command\": \"rosrun biovision_v1 v1_bench --threads %d --json FILE\",\n"
                "  \"image\": \"%s\",\n  \"width\": %d,\n  \"height\": %d,\n  \"threads\": %d,\n"
                "  \"orientations\": %d,\n  \"wavelengths\": [4, 8, 16],\n"
                "  \"ours_ms\": %.3f,\n  \"filter2d_ms\": %.3f,\n  \"speedup\": %.2f,\n"
                "  \"keypoints_ms\": %.3f,\n  \"keypoints\": %zu,\n  \"max_rel_err\": %.3g\n}\n",
                threads, image_path.substr(image_path.find_last_of('/') + 1).c_str(), width, height, threads,
                gabor.orientations, ours_ms, direct_ms, speedup, keypoints_ms, keypoints, max_rel_err);
  std::cout << json;
  if (!json_path.empty())
  {
    std::ofstream out(json_path);
    out << json;
    if (!out)
    {
      std::cerr << "v1_bench: cannot write " << json_path << "\n";
      return 1;
    }
  }
  return 0;
}
