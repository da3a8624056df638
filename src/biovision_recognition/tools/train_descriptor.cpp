// Trains the LDAHash projection and thresholds of the V1 descriptor from real correspondences.

#include <chrono>
#include <ctime>
#include <fstream>
#include <iostream>

#include <Eigen/Core>

#include "biovision_recognition/lda_hash_trainer.hpp"
#include "biovision_recognition/pooled_cell_features.hpp"
#include "correspondence_data.hpp"
#include "tool_arguments.hpp"

using namespace biovision_recognition;

namespace
{
const char* kUsage =
    "usage: train_descriptor --out FILE [--stereo DIR] [--sequence DIR] [options]\n"
    "  --stereo DIR          folder of Middlebury scenes (ground-truth disparities give the pairs)\n"
    "  --sequence DIR        HPatches/Oxford sequence (homographies give the pairs)\n"
    "  --part P              train (default), test or all: scenes alternate train/test in name order\n"
    "  --targets LIST        sequence images paired with image 1 (default 2,3: 4,5,6 are the test part)\n"
    "  --all-pairs           every ordered pair of image 1 and the targets (1-2, 2-1, 2-3, ...), not only 1-k\n"
    "  --bits N              64, 128 (default) or 256\n"
    "  --scales LIST         descriptor scales j, lambda = 4 * 2^(j/2) of the 32 px patch (default 0,1,2,3,4,5,6)\n"
    "  --levels LIST         pyramid levels keypoints are detected at (default 0,1,2,3,4)\n"
    "  --patch W             patch side in keypoint wavelengths (default 8: 32 px at lambda 4)\n"
    "  --pooling D,S         pooling disk diameter and step in level px (default 4,2)\n"
    "  --pairs N             pairs of each kind per image pair (default 1500)\n"
    "  --rank N              eigenpairs of Sigma_N kept for the whitening (default 512)\n"
    "  --ridge R             whitening ridge, relative to Sigma_N's largest eigenvalue (default 1e-3)\n"
    "  --threads N           threads for Eigen's products (default 2)\n"

    "  --json FILE           training statistics\n";

using Matrix = LdaHashTrainer::Matrix;

void append(Matrix& m, const cv::Mat& rows)
{
  const Eigen::Index old = m.rows();
  m.conservativeResize(old + rows.rows, rows.cols);
  for (int i = 0; i < rows.rows; ++i)
    m.row(old + i) = Eigen::Map<const Eigen::RowVectorXf>(rows.ptr<float>(i), rows.cols);
}
}  // namespace

int main(int argc, char** argv)
{
  const ToolArguments args(argc, argv, kUsage,
                           {"--out", "--stereo", "--sequence", "--part", "--targets", "--bits", "--scales", "--levels",
                            "--pairs", "--rank", "--ridge", "--threads", "--patch", "--pooling", "--json"},
                           {"--all-pairs"});
  if (!args.has("--out") || (!args.has("--stereo") && !args.has("--sequence")))
  {
    std::cerr << kUsage;
    return 2;
  }
  Eigen::setNbThreads(static_cast<int>(args.number("--threads", 2)));
  const auto t0 = std::chrono::steady_clock::now();
  try
  {
    DescriptorLayout layout;
    layout.scales = args.integers("--scales", layout.scales);
    layout.patch_wavelengths = args.number("--patch", layout.patch_wavelengths);
    const std::vector<int> pooling = args.integers("--pooling", {layout.pooling_diameter, layout.pooling_step});
    if (pooling.size() != 2)
      throw std::invalid_argument("--pooling takes D,S");
    layout.pooling_diameter = pooling[0];
    layout.pooling_step = pooling[1];
    const PooledCellFeatures features(layout);
    PairSampler::Parameters sp;
    sp.levels = args.integers("--levels", sp.levels);
    sp.max_pairs = static_cast<int>(args.number("--pairs", 1500));
    PairSampler sampler(sp);
    V1FeaturePyramid::Parameters pp;
    pp.orientations = layout.orientations;
    pp.pooling_diameter = layout.pooling_diameter;
    V1FeaturePyramid pa(pp), pb(pp);

    auto pairs = loadCorrespondencePairs(args.get("--stereo"), args.get("--part", "train"), args.get("--sequence"),
                                         args.integers("--targets", {2, 3}), args.has("--all-pairs"));

    Matrix xa, xb, ya, yb;
    for (const auto& pair : pairs)
    {
      pa.build(biovision_v1::InputImage(pair.a).gray());
      pb.build(biovision_v1::InputImage(pair.b).gray());
      const auto p = samplePairs(sampler, pair, pa, pb);
      append(xa, features.extract(pa, p.positive_a));
      append(xb, features.extract(pb, p.positive_b));
      append(ya, features.extract(pa, p.negative_a));
      append(yb, features.extract(pb, p.negative_b));
      std::cerr << pair.name << ": " << p.positive_a.size() << " pairs of each kind\n";
    }
    std::cerr << "training on " << xa.rows() << " positive and " << ya.rows() << " negative pairs, "
              << layout.featureCount() << " features\n";
    LdaHashTrainer::Parameters tp;
    tp.bits = static_cast<int>(args.number("--bits", 128));
    tp.whitening_rank = static_cast<int>(args.number("--rank", 512));
    tp.ridge = args.number("--ridge", tp.ridge);
    const LdaHashTrainer trainer(tp);
    DescriptorModel model = trainer.train(xa, xb, ya, yb);
    model.layout = layout;
    const std::time_t now = std::time(nullptr);
    char date[32];
    std::strftime(date, sizeof(date), "%Y-%m-%d", std::gmtime(&now));
    model.provenance = "rosrun biovision_recognition train_descriptor " + args.command() + "  (" +
                       std::to_string(xa.rows()) + " positive / " + std::to_string(ya.rows()) + " negative pairs, " +
                       date + ")";
    model.save(args.get("--out"));
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::cerr << "wrote " << args.get("--out") << " (" << model.id() << ") in " << seconds << " s\n";
    if (args.has("--json"))
    {
      std::ofstream json(args.get("--json"));
      json << "{\n  \"model\": \"" << model.id() << "\",\n  \"features\": " << layout.featureCount()
           << ",\n  \"bits\": " << model.bits() << ",\n  \"positive_pairs\": " << xa.rows()
           << ",\n  \"negative_pairs\": " << ya.rows() << ",\n  \"seconds\": " << seconds << "\n}\n";
    }
  }
  catch (const std::exception& e)
  {
    std::cerr << "train_descriptor: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
