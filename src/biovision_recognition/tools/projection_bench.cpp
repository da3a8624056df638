// The descriptor's projection y = x P^T (PackedProjection) on every path this CPU runs, against the GEMMs a
// user would otherwise call: cv::gemm and Eigen's product, same data, same thread count, same run.

#include <iomanip>
#include <iostream>
#include <random>

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <ros/package.h>

#include "best_seconds.hpp"
#include "biovision_common/cpu_features.hpp"
#include "biovision_common/tool_options.hpp"
#include "biovision_recognition/descriptor_model.hpp"
#include "biovision_recognition/packed_projection.hpp"

using namespace biovision_recognition;

namespace
{
const char* kDescription =
    "Projects --rows feature rows (random, the model's length) with the descriptor model's P: ours\n"
    "(PackedProjection) on every kernel path this CPU runs, cv::gemm (GEMM_2_T) and Eigen (x * P^T) with --threads\n"
    "OpenCV threads (Eigen: its own OpenMP threads); best of --repeats. 400 rows = the recogniser's\n"
    "max_keypoints per region. Prints a table; --json writes the figures.";
}  // namespace

int main(int argc, char** argv)
{
  std::string model_path = ros::package::getPath("biovision_recognition") + "/models/" + kDefaultModelFile;
  std::string json_path;
  int rows = 400, threads = 2, repeats = 7;
  biovision_common::ToolOptions options("projection_bench", kDescription);
  CLI::App& app = options.app();
  app.add_option("--model", model_path, "descriptor model whose P is used")->check(CLI::ExistingFile);
  app.add_option("--rows", rows, "feature rows (keypoints) per call")->check(biovision_common::kPositive);
  app.add_option("--threads", threads, "OpenCV threads, ours and cv::gemm")->check(biovision_common::kPositive);
  app.add_option("--repeats", repeats, "timed runs (best)")->check(biovision_common::kPositive);
  app.add_option("--json", json_path, "write the figures to this file");
  options.parse(argc, argv);

  const DescriptorModel model = DescriptorModel::load(model_path);
  const int outputs = static_cast<int>(model.projection.rows()), inputs = static_cast<int>(model.projection.cols());
  cv::setNumThreads(threads);
  cv::Mat x(rows, inputs, CV_32F);
  cv::randn(x, 0.0, 1.0);
  const cv::Mat p(outputs, inputs, CV_32F, const_cast<float*>(model.projection.data()));
  const double flops = 2.0 * rows * inputs * outputs;

  cv::Mat y_cv;
  const double cv_s = bestSeconds(repeats, [&] { cv::gemm(x, p, 1.0, cv::noArray(), 0.0, y_cv, cv::GEMM_2_T); });
  using RowMajor = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  const Eigen::Map<const RowMajor> x_e(x.ptr<float>(), rows, inputs);
  RowMajor y_e(rows, outputs);
  const double eigen_s = bestSeconds(repeats, [&] { y_e.noalias() = x_e * model.projection.transpose(); });

  nlohmann::ordered_json figures;
  figures["command"] = "rosrun biovision_recognition projection_bench " + options.command();
  figures["cpu"] = biovision_common::CpuFeatures::host().describe();
  figures["rows"] = rows;
  figures["inputs"] = inputs;
  figures["outputs"] = outputs;
  figures["threads"] = threads;
  figures["cv_gemm_ms"] = cv_s * 1e3;
  figures["eigen_ms"] = eigen_s * 1e3;
  figures["default_path"] = toString(bestProjectionPath());
  std::cout << std::fixed << std::setprecision(2) << "cv::gemm: " << cv_s * 1e3 << " ms (" << flops / cv_s / 1e9
            << " GFLOP/s); Eigen: " << eigen_s * 1e3 << " ms (" << flops / eigen_s / 1e9 << " GFLOP/s)\n";
  const PackedProjection packed(model.projection.data(), outputs, inputs);
  double worst_difference = 0.0;
  for (ProjectionPath path : availableProjectionPaths())
  {
    cv::Mat y(rows, outputs, CV_32F);
    const double s = bestSeconds(repeats, [&] { packed.project(x.ptr<float>(), rows, y.ptr<float>(), path); });
    worst_difference = std::max(worst_difference, cv::norm(y, y_cv, cv::NORM_INF) / cv::norm(y_cv, cv::NORM_INF));
    const std::string name = toString(path);
    figures["ours_" + name + "_ms"] = s * 1e3;
    figures["ours_" + name + "_gflops"] = flops / s / 1e9;
    figures["ours_" + name + "_vs_cv_gemm"] = cv_s / s;
    figures["ours_" + name + "_vs_eigen"] = eigen_s / s;
    std::cout << "ours " << std::setw(8) << name << ": " << s * 1e3 << " ms (" << flops / s / 1e9 << " GFLOP/s), "
              << cv_s / s << "x cv::gemm, " << eigen_s / s << "x Eigen\n";
  }
  figures["worst_relative_difference_vs_cv_gemm"] = worst_difference;
  figures["notes"] =
      "x = random rows, P = the committed model's projection; ratios = peer time / ours (> 1: "
      "faster); the paths below the default one are what a CPU without its extension would run";
  if (!options.writeJson(json_path, figures))
    return 1;
  return worst_difference < 1e-4 ? 0 : 1;
}
