// How far below the peers the model's mandated work alone already is: per scene, in the same run, the
// odd simple cells BioBin's descriptors need (both images, every level, SimpleCellBank's exact FFT
// path) and one finest-level 256-bit Hamming cost volume, against OpenCV SGBM's and StereoBM's whole
// computation. If a stage alone exceeds the peer's whole time, no tuning of the rest meets a
// "no slower than the peer" goal with this model.

#include <chrono>
#include <fstream>
#include <iostream>
#include <sstream>

#include <opencv2/calib3d.hpp>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgproc.hpp>

#include "biovision_stereo/bio_bin_parameters.hpp"
#include "biovision_stereo/hamming.hpp"
#include "biovision_common/eval/middlebury_dataset.hpp"
#include "biovision_stereo/pixel_descriptor.hpp"
#include "biovision_v1/simple_cell_bank.hpp"
#include "biovision_common/tool_arguments.hpp"

using biovision_common::MiddleburyDataset;

using namespace biovision_stereo;

namespace
{
const char* kUsage =
    "usage: stage_floor --dataset DIR [--json FILE] [--threads 2] [--repeats 10]\n"
    "  per scene: sgbm_ms (MODE_SGBM_3WAY, whole), odd_cells_ms (BioBin's odd cells, 2 images, every level),\n"
    "  hamming_ms (finest level's 256-bit cost volume alone), bm_fast_ms (StereoBM at quarter size incl.\n"
    "  resize, whole), fast_cells_ms (the fast mode's odd cells alone, 2 images).\n";

template <class F>
double milliseconds(F&& f, int repeats)
{
  f();  // warm-up: caches, kernel spectra
  const auto t = std::chrono::steady_clock::now();
  for (int i = 0; i < repeats; ++i)
    f();
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count() / repeats;
}

cv::Mat unitGray(const cv::Mat& bgr, cv::Size size)
{
  cv::Mat g, r;
  cv::cvtColor(bgr, g, cv::COLOR_BGR2GRAY);
  cv::resize(g, r, size, 0, 0, cv::INTER_AREA);
  r.convertTo(r, CV_32F, 1.0 / 255.0);
  return r;
}
}  // namespace

int main(int argc, char** argv)
{
  const biovision_common::ToolArguments args(argc, argv, kUsage, {"--dataset", "--json", "--threads", "--repeats"});
  if (!args.has("--dataset"))
  {
    std::cerr << kUsage;
    return 2;
  }
  cv::setNumThreads(static_cast<int>(args.number("--threads", 2)));
  const int repeats = std::max(1, static_cast<int>(args.number("--repeats", 10)));
  const BioBinParameters defaults;
  std::ostringstream scenes;
  double sum_sgbm = 0, sum_cells = 0, sum_ham = 0, sum_bm = 0, sum_fast = 0;
  int n = 0;
  try
  {
    for (const auto& s : MiddleburyDataset::load(args.get("--dataset")))
    {
      const int nd = s.max_disparity;
      cv::Mat d, gl, gr;
      auto sgbm = cv::StereoSGBM::create(0, (nd + 15) / 16 * 16, 5, 600, 2400, 1, 63, 10, 100, 32,
                                         cv::StereoSGBM::MODE_SGBM_3WAY);
      const double t_sgbm = milliseconds([&] { sgbm->compute(s.left, s.right, d); }, repeats);
      cv::cvtColor(s.left, gl, cv::COLOR_BGR2GRAY);
      cv::cvtColor(s.right, gr, cv::COLOR_BGR2GRAY);
      const cv::Size quarter(gl.cols / 4, gl.rows / 4);
      auto bm = cv::StereoBM::create(((nd + 3) / 4 + 15) / 16 * 16, 7);
      cv::Mat ql, qr;
      const double t_bm = milliseconds(
          [&] {
            cv::resize(gl, ql, quarter, 0, 0, cv::INTER_AREA);
            cv::resize(gr, qr, quarter, 0, 0, cv::INTER_AREA);
            bm->compute(ql, qr, d);
          },
          5 * repeats);

      biovision_v1::GaborParameters gabor;
      gabor.wavelengths = {defaults.base_wavelength};
      gabor.orientations = 8;
      gabor.min_grid_wavelength = 0.0;  // as BioBinMatcher: full resolution for the descriptor
      double t_cells = 0, t_fast = 0;
      for (double lambda : {4.0, 8.0, 16.0})
      {
        const double sf = lambda / defaults.base_wavelength;
        const cv::Size size(static_cast<int>(std::lround(gl.cols / sf)), static_cast<int>(std::lround(gl.rows / sf)));
        const cv::Mat l = unitGray(s.left, size), r = unitGray(s.right, size);
        biovision_v1::SimpleCellBank bank(gabor);
        const double t = milliseconds(
            [&] {
              bank.computeOdd(l);
              bank.computeOdd(r);
            },
            repeats);
        t_cells += t;
        if (lambda == 16.0)
          t_fast = t;  // the fast mode's one level
      }
      biovision_v1::SimpleCellBank bank(gabor);
      const auto codes_l = PixelDescriptorImage::compute(bank.computeOdd(unitGray(s.left, gl.size()))[0]);
      const auto codes_r = PixelDescriptorImage::compute(bank.computeOdd(unitGray(s.right, gl.size()))[0]);
      const double t_ham = milliseconds(
          [&] {
            cv::parallel_for_(cv::Range(0, gl.rows), [&](const cv::Range& rows) {
              std::vector<float> out(gl.cols);
              for (int y = rows.start; y < rows.end; ++y)
                for (int k = 0; k < nd; ++k)
                  Hamming::row(codes_l.row(y), codes_r.row(y), gl.cols, k, 256.f, out.data());
            });
          },
          repeats);
      scenes << (n ? ",\n" : "\n") << "    \"" << s.name << "\": {\"sgbm_ms\": " << t_sgbm << ", \"odd_cells_ms\": " << t_cells
             << ", \"hamming_ms\": " << t_ham << ", \"bm_fast_ms\": " << t_bm << ", \"fast_cells_ms\": " << t_fast << "}";
      std::cerr << s.name << ": sgbm " << t_sgbm << " ms, odd cells " << t_cells << " ms, hamming " << t_ham
                << " ms | bm_fast " << t_bm << " ms, fast-mode cells " << t_fast << " ms\n";
      sum_sgbm += t_sgbm, sum_cells += t_cells, sum_ham += t_ham, sum_bm += t_bm, sum_fast += t_fast;
      ++n;
    }
  }
  catch (const std::exception& e)
  {
    std::cerr << "stage_floor: " << e.what() << "\n";
    return 1;
  }
  if (n == 0)
  {
    std::cerr << "stage_floor: no scenes in " << args.get("--dataset") << "\n";
    return 1;
  }
  std::ostringstream json;
  json << "{\n  \"command\": \"rosrun biovision_stereo stage_floor " << args.command() << "\",\n"
       << "  \"mean\": {\"sgbm_ms\": " << sum_sgbm / n << ", \"odd_cells_ms\": " << sum_cells / n
       << ", \"hamming_ms\": " << sum_ham / n << ", \"bm_fast_ms\": " << sum_bm / n
       << ", \"fast_cells_ms\": " << sum_fast / n << "},\n"
       << "  \"ratios\": {\"odd_cells_vs_sgbm\": " << sum_cells / sum_sgbm
       << ", \"fast_cells_vs_bm_fast\": " << sum_fast / sum_bm << "},\n"
       << "  \"notes\": \"Ratios > 1: the mandated stage alone takes longer than the peer's whole computation.\",\n"
       << "  \"scenes\": {" << scenes.str() << "\n  }\n}\n";
  std::cout << json.str();
  if (args.has("--json"))
    std::ofstream(args.get("--json")) << json.str();
  return 0;
}
