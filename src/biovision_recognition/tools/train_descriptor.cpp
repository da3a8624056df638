// Trains the LDAHash projection and thresholds of the V1 descriptor from real correspondences.

#include <chrono>
#include <ctime>
#include <fstream>
#include <iostream>

#include <Eigen/Core>

#include "biovision_recognition/lda_hash_trainer.hpp"
#include "biovision_recognition/pooled_cell_features.hpp"
#include "correspondence_data.hpp"
#include "biovision_common/tool_arguments.hpp"

using namespace biovision_recognition;
using biovision_common::ToolArguments;

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
    "  --phases N            4 (default): even, odd, -even, -odd maxima; 2: signed even, odd maxima only\n"
    "  --shape I,W,L,A       affine shape adaptation of the pooling grid: iterations (0: square grid), window\n"
    "                        sigma [wavelengths], gradient level offset, largest anisotropy (default 4,1.5,1,4)\n"
    "  --warps N             add N synthetic camera tilts of every training image (ASIFT model)\n"
    "  --max-tilt T          largest synthetic tilt (default 2.5);  --warp-pairs N: pairs per warp (default 500)\n"
    "  --pairs N             pairs of each kind per image pair (default 1500)\n"
    "  --rank N              eigenpairs of Sigma_N kept for the whitening (default 512)\n"
    "  --ridge R             whitening ridge, relative to Sigma_N's largest eigenvalue (default 1e-3)\n"
    "  --threads N           threads for Eigen's products (default 2)\n"

    "  --json FILE           training statistics\n";

using Matrix = LdaHashTrainer::Matrix;

/// The blocks stacked into one matrix; each block is released once copied, so the peak is one matrix
/// plus what is left of the blocks (growing a matrix block by block would copy it every time).
Matrix stack(std::vector<cv::Mat>& blocks, int cols)
{
  Eigen::Index rows = 0;
  for (const auto& b : blocks)
    rows += b.rows;
  Matrix m(rows, cols);
  Eigen::Index at = 0;
  for (auto& b : blocks)
  {
    for (int i = 0; i < b.rows; ++i)
      m.row(at++) = Eigen::Map<const Eigen::RowVectorXf>(b.ptr<float>(i), cols);
    b.release();
  }
  return m;
}
}  // namespace

int main(int argc, char** argv)
{
  const ToolArguments args(argc, argv, kUsage,
                           {"--out", "--shape", "--stereo", "--sequence", "--part", "--targets", "--bits", "--scales", "--levels",
                            "--pairs", "--rank", "--ridge", "--threads", "--patch", "--pooling", "--json", "--phases", "--warps", "--max-tilt", "--warp-pairs"},
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
    layout.phases = static_cast<int>(args.number("--phases", layout.phases));
    if (args.has("--shape"))
    {
      const auto shape = args.strings("--shape");
      if (shape.size() != 4)
        throw std::invalid_argument("--shape takes I,W,L,A");
      layout.shape.iterations = std::stoi(shape[0]);
      layout.shape.window_wavelengths = std::stod(shape[1]);
      layout.shape.level_offset = std::stoi(shape[2]);
      layout.shape.max_anisotropy = std::stod(shape[3]);
    }
    const PooledCellFeatures features(layout);
    PairSampler::Parameters sp;
    sp.levels = args.integers("--levels", sp.levels);
    sp.max_pairs = static_cast<int>(args.number("--pairs", 1500));
    PairSampler sampler(sp);
    V1FeaturePyramid::Parameters pp;
    pp.orientations = layout.orientations;
    pp.pooling_diameter = layout.pooling_diameter;
    pp.pooling_phases = layout.phases;
    V1FeaturePyramid pa(pp), pb(pp);

    auto pairs = loadCorrespondencePairs(args.get("--stereo"), args.get("--part", "train"), args.get("--sequence"),
                                         args.integers("--targets", {2, 3}), args.has("--all-pairs"));
    const size_t real_pairs = pairs.size();
    if (args.has("--warps"))
    {
      const auto warps = syntheticViewpoints(pairs, static_cast<int>(args.number("--warps", 0)),
                                             args.number("--max-tilt", 2.5), 11);
      pairs.insert(pairs.end(), warps.begin(), warps.end());
    }
    PairSampler::Parameters wp = sp;
    wp.max_pairs = static_cast<int>(args.number("--warp-pairs", 500));
    PairSampler warp_sampler(wp);

    // One side of each pair and the pair differences: four matrices, not six, for large training sets.
    std::vector<cv::Mat> xa, dx, ya, dy;
    for (size_t i = 0; i < pairs.size(); ++i)
    {
      const CorrespondencePair& pair = pairs[i];
      pa.build(biovision_v1::InputImage(pair.a).gray());
      pb.build(biovision_v1::InputImage(pair.b).gray());
      const auto p = samplePairs(i < real_pairs ? sampler : warp_sampler, pair, pa, pb);
      xa.push_back(features.extract(pa, p.positive_a));
      dx.push_back(xa.back() - features.extract(pb, p.positive_b));
      ya.push_back(features.extract(pa, p.negative_a));
      dy.push_back(ya.back() - features.extract(pb, p.negative_b));
      std::cerr << pair.name << ": " << p.positive_a.size() << " pairs of each kind\n";
    }
    const int n = layout.featureCount();
    const Matrix positive_a = stack(xa, n), positive_difference = stack(dx, n);
    const Matrix negative_a = stack(ya, n), negative_difference = stack(dy, n);
    std::cerr << "training on " << positive_a.rows() << " positive and " << negative_a.rows() << " negative pairs, "
              << layout.featureCount() << " features\n";
    LdaHashTrainer::Parameters tp;
    tp.bits = static_cast<int>(args.number("--bits", 128));
    tp.whitening_rank = static_cast<int>(args.number("--rank", 512));
    tp.ridge = args.number("--ridge", tp.ridge);
    const LdaHashTrainer trainer(tp);
    DescriptorModel model = trainer.trainOnDifferences(positive_a, positive_difference, negative_a, negative_difference);
    model.layout = layout;
    const std::time_t now = std::time(nullptr);
    char date[32];
    std::strftime(date, sizeof(date), "%Y-%m-%d", std::gmtime(&now));
    model.provenance = "rosrun biovision_recognition train_descriptor " + args.command() + "  (" +
                       std::to_string(positive_a.rows()) + " positive / " + std::to_string(negative_a.rows()) + " negative pairs, " +
                       date + ")";
    model.save(args.get("--out"));
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::cerr << "wrote " << args.get("--out") << " (" << model.id() << ") in " << seconds << " s\n";
    if (args.has("--json"))
    {
      std::ofstream json(args.get("--json"));
      json << "{\n  \"model\": \"" << model.id() << "\",\n  \"features\": " << layout.featureCount()
           << ",\n  \"bits\": " << model.bits() << ",\n  \"positive_pairs\": " << positive_a.rows()
           << ",\n  \"negative_pairs\": " << negative_a.rows() << ",\n  \"seconds\": " << seconds << "\n}\n";
    }
  }
  catch (const std::exception& e)
  {
    std::cerr << "train_descriptor: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
