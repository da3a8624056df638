// How far below the peers the model's mandated work alone already is: per scene, in the same run, the
// odd simple cells BioBin's descriptors need (both images, every level, SimpleCellBank's exact FFT
// path) and one finest-level 256-bit Hamming cost volume, against OpenCV SGBM's and StereoBM's whole
// computation. If a stage alone exceeds the peer's whole time, no tuning of the rest meets a
// "no slower than the peer" goal with this model.

#include <chrono>
#include <iostream>
#include <map>

#include <opencv2/calib3d.hpp>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgproc.hpp>

#include "biovision_stereo/bio_bin_parameters.hpp"
#include "biovision_stereo/cost_simd.hpp"
#include "biovision_stereo/hamming.hpp"
#include "biovision_common/eval/middlebury_dataset.hpp"
#include "biovision_stereo/pixel_descriptor.hpp"
#include "biovision_v1/simple_cell_bank.hpp"
#include "biovision_common/tool_options.hpp"
#include "biovision_stereo/bio_bin_matcher.hpp"
#include "biovision_stereo/semi_global_aggregation.hpp"
#include "biovision_v1/fourier_transform.hpp"

using biovision_common::MiddleburyDataset;

using namespace biovision_stereo;

namespace
{
const char* kDescription =
    "Per scene, same run: sgbm_ms (MODE_SGBM_3WAY, whole), odd_cells_ms (BioBin's odd cells, 2 images, every level),\n"
    "hamming_ms (finest level's Hamming costs alone as BioBin computes them: window sums of comparison bytes;\n"
    "hamming_ms_<path>: from formed 256-bit codes on every Hamming path this CPU runs), sgm_ms_<path> (the finest "
    "level's semi-global aggregation alone, 8 paths, on\n"
    "every SIMD path this CPU runs), bm_fast_ms (StereoBM at quarter size incl. resize,\n"
    "whole), fast_cells_ms (the fast mode's odd cells alone, 2 images). Prints the JSON.";

template <class F>
double milliseconds(F&& f, int repeats)
{
  biovision_v1::FourierTransform::warmUp(f);  // caches, kernel spectra, DFT plans measured
  const auto t = std::chrono::steady_clock::now();
  for (int i = 0; i < repeats; ++i)
    f();
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count() / repeats;
}

/// One scene's (or the mean) milliseconds per stage, in the JSON's order.
nlohmann::ordered_json stageTimes(double sgbm, double odd_cells, double hamming, double bm_fast, double fast_cells)
{
  return {{"sgbm_ms", sgbm},
          {"odd_cells_ms", odd_cells},
          {"hamming_ms", hamming},
          {"bm_fast_ms", bm_fast},
          {"fast_cells_ms", fast_cells}};
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
  std::string dataset, json_path;
  int threads = 2, repeats = 10;
  biovision_common::ToolOptions options("stage_floor", kDescription);
  CLI::App& app = options.app();
  app.add_option("--dataset", dataset, "one Middlebury scene or a folder of scenes (see MiddleburyDataset)")
      ->required();
  app.add_option("--json", json_path, "also write the figures to this file");
  app.add_option("--threads", threads, "OpenCV threads")->check(biovision_common::kPositive);
  app.add_option("--repeats", repeats, "timed runs per stage (mean; StereoBM 5x) after one warm-up")
      ->check(biovision_common::kPositive);
  options.parse(argc, argv);
  cv::setNumThreads(threads);
  const BioBinParameters defaults;
  nlohmann::ordered_json scenes = nlohmann::ordered_json::object();
  double sum_sgbm = 0, sum_cells = 0, sum_ham = 0, sum_codes = 0, sum_bm = 0, sum_fast = 0;
  std::map<std::string, double> sum_ham_by_path, sum_sgm_by_path;
  int n = 0;
  try
  {
    for (const auto& s : MiddleburyDataset::load(dataset))
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
      // The volume on every Hamming path this CPU runs; hamming_ms is the one BioBin uses (the best).
      nlohmann::ordered_json by_path = nlohmann::ordered_json::object();
      double t_ham = 0, t_codes = 0;  // byte windows (BioBin's way), codes on the best path
      for (const auto path : biovision_common::availableHammingPaths())
      {
        const double t = milliseconds(
            [&] {
              cv::parallel_for_(cv::Range(0, gl.rows), [&](const cv::Range& rows) {
                std::vector<float> out(gl.cols);
                for (int y = rows.start; y < rows.end; ++y)
                  for (int k = 0; k < nd; ++k)
                    Hamming::row(codes_l.row(y), codes_r.row(y), gl.cols, k, 256.f, out.data(), path);
              });
            },
            repeats);
        by_path[biovision_common::toString(path)] = t;
        sum_ham_by_path[biovision_common::toString(path)] += t;
        if (path == biovision_common::bestHammingPath())
          t_codes = t;
      }
      // The same costs as BioBin computes them: from the comparison bytes, no codes formed.
      t_ham = milliseconds(
          [&] {
            cv::parallel_for_(cv::Range(0, gl.rows), [&](const cv::Range& rows) {
              std::vector<float> out(gl.cols);
              for (int y = rows.start; y < rows.end; ++y)
                for (int k = 0; k < nd; ++k)
                  Hamming::windowRow(codes_l, codes_r, y, k, 256.f, out.data());
            });
          },
          repeats);
      by_path["byte_windows"] = t_ham;
      sum_ham_by_path["byte_windows"] += t_ham;
      sum_codes += t_codes;
      // The finest level's semi-global aggregation on BioBin's own costs, on every SIMD path.
      BioBinMatcher matcher(defaults);
      const CostVolume costs = matcher.levelCosts(0, s.left, s.right, nd + 1, nullptr);
      std::vector<std::uint16_t> pixel_major, forward, backward;
      SemiGlobalAggregation::toPixelMajor(costs, costs.min(), float(BioBinParameters::kSgmCostScale), pixel_major);
      const auto units = [](double v) { return static_cast<int>(std::lround(v * BioBinParameters::kSgmCostScale)); };
      const SemiGlobalAggregation sgm(units(defaults.sgm_p1), std::max(units(defaults.sgm_p1), units(defaults.sgm_p2)),
                                      units(defaults.sgm_p2_barrier), defaults.sgm_paths);
      nlohmann::ordered_json sgm_by_path = nlohmann::ordered_json::object();
      for (const auto path : SemiGlobalAggregation::availableSimds())
      {
        const double t = milliseconds(
            [&] { sgm.aggregate(pixel_major, gl.cols, gl.rows, nd + 1, cv::Mat(), forward, backward, path); }, repeats);
        sgm_by_path[SemiGlobalAggregation::name(path)] = t;
        sum_sgm_by_path[SemiGlobalAggregation::name(path)] += t;
      }
      scenes[s.name] = stageTimes(t_sgbm, t_cells, t_ham, t_bm, t_fast);
      scenes[s.name]["hamming_ms_by_path"] = by_path;
      scenes[s.name]["sgm_ms_by_path"] = sgm_by_path;
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
    std::cerr << "stage_floor: no scenes in " << dataset << "\n";
    return 1;
  }
  nlohmann::ordered_json figures;
  figures["command"] = "rosrun biovision_stereo stage_floor " + options.command();
  figures["mean"] = stageTimes(sum_sgbm / n, sum_cells / n, sum_ham / n, sum_bm / n, sum_fast / n);
  figures["hamming_path"] = "byte windows (" + costSimdName(bestCostSimd()) + " clone); codes: " + Hamming::pathName();
  for (const auto& [path, sum] : sum_ham_by_path)
    figures["mean"]["hamming_ms_" + path] = sum / n;
  figures["sgm_path"] = SemiGlobalAggregation::name(SemiGlobalAggregation::bestSimd());
  for (const auto& [path, sum] : sum_sgm_by_path)
    figures["mean"]["sgm_ms_" + path] = sum / n;
  figures["ratios"] = {{"odd_cells_vs_sgbm", sum_cells / sum_sgbm}, {"fast_cells_vs_bm_fast", sum_fast / sum_bm}};
  if (sum_sgm_by_path.count("avx2"))
    figures["ratios"]["sgm_avx2_vs_generic"] = sum_sgm_by_path["avx2"] / sum_sgm_by_path["generic"];
  if (sum_ham_by_path.count("popcnt"))
    figures["ratios"]["hamming_best_vs_popcnt"] = sum_codes / sum_ham_by_path["popcnt"];
  figures["ratios"]["byte_windows_vs_best_codes"] = sum_ham / sum_codes;
  figures["notes"] = "Ratios > 1: the mandated stage alone takes longer than the peer's whole computation.";
  figures["scenes"] = scenes;
  std::cout << figures.dump(2) << "\n";
  if (!options.writeJson(json_path, figures))
    return 1;
  return 0;
}
