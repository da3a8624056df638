// Trains the LDAHash projection and thresholds of the V1 descriptor from real correspondences.

#include <array>
#include <chrono>
#include <ctime>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include <Eigen/Core>

#include "biovision_recognition/lda_hash_statistics.hpp"
#include "biovision_recognition/lda_hash_trainer.hpp"
#include "biovision_recognition/pooled_cell_features.hpp"
#include "correspondence_data.hpp"
#include "biovision_common/tool_options.hpp"

using namespace biovision_recognition;

namespace
{
/// What the command line sets; every default is the trainer's own unless given here.
struct Options
{
  std::string out, stereo, sequence, json_path, part = "train";
  std::vector<int> targets{2, 3};  // 4, 5, 6 are the test part
  bool all_pairs = false;
  DescriptorLayout layout;
  PairSampler::Parameters sampling;
  int warps = 0;
  double max_tilt = 2.5;
  int warp_pairs = 500;
  std::vector<std::string> images;  // collections: synthetic pairs of their dev sources
  int per_source = 4, synthetic = 2, synthetic_pairs = 150;
  double synthetic_tilt = 4.0;
  bool photometric = true;
  LdaHashTrainer::Parameters training;
  std::vector<int> ranks{LdaHashTrainer::Parameters().whitening_rank};
  std::vector<int> iterations{LdaHashTrainer::Parameters().power_iterations};
  int threshold_pairs = 20000;  // moves a threshold's quantile by ~1/sqrt(20000) = 0.7%; 4.1 GB at 12,832 inputs
  int threads = 2;
  std::string command;  // the options as given, for the model's provenance
};

Options parseOptions(int argc, char** argv)
{
  Options o;
  o.sampling.max_pairs = 1500;  // --pairs: this tool's default, not the sampler's
  std::array<int, 2> pooling{o.layout.pooling_diameter, o.layout.pooling_step};
  const auto& d = o.layout.shape;
  std::tuple<int, double, int, double> shape{d.iterations, d.window_wavelengths, d.level_offset, d.max_anisotropy};
  std::ostringstream shape_default;  // CLI11 cannot print a tuple's default itself
  shape_default << "[" << d.iterations << "," << d.window_wavelengths << "," << d.level_offset << ","
                << d.max_anisotropy << "]";

  biovision_common::ToolOptions options(
      "train_descriptor",
      "Trains the LDAHash projection and thresholds of the V1 descriptor from real correspondences.");
  CLI::App& app = options.app();
  app.add_option("--out", o.out, "model file to write")->required();
  app.add_option("--stereo", o.stereo, "folder of Middlebury scenes (ground-truth disparities give the pairs)");
  app.add_option("--sequence", o.sequence, "HPatches/Oxford sequence (homographies give the pairs)");
  app.add_option("--part", o.part,
                 "stereo scenes: train/test alternate in name order (models up to session 4); dev/heldout: the split "
                 "by source (descriptorSplit); fit/validation: the dev part split again by source (train a variant on "
                 "fit, compare on validation). --images take the same part of the split by source (dev for train/test)")
      ->check(CLI::IsMember({"train", "test", "all", "dev", "heldout", "fit", "validation"}));
  app.add_option("--images", o.images,
                 "image collections, comma-separated (a file = one source, a subfolder = one source): synthetic "
                 "pairs of their sources in --part (never opencv-doc)")
      ->delimiter(',')
      ->check(CLI::ExistingDirectory);
  app.add_option("--per-source", o.per_source, "--images: at most this many images per source, evenly spaced")
      ->check(biovision_common::kPositive);
  app.add_option("--synthetic", o.synthetic, "--images: synthetic views per image")->check(biovision_common::kPositive);
  app.add_option("--synthetic-pairs", o.synthetic_pairs, "--images: pairs of each kind per synthetic view")
      ->check(biovision_common::kPositive);
  app.add_option("--synthetic-tilt", o.synthetic_tilt, "--images: largest camera tilt (ASIFT: 4 = 75.5 degrees)")
      ->check(CLI::Range(1.0, 8.0));
  app.add_option("--photometric", o.photometric, "--images: gain, gamma, offset, blur and noise on the second view");
  app.add_option("--targets", o.targets, "sequence images paired with image 1")
      ->delimiter(',')
      ->check(biovision_common::kPositive);
  app.add_flag("--all-pairs", o.all_pairs,
               "every ordered pair of image 1 and the targets (1-2, 2-1, 2-3, ...), not only 1-k");
  app.add_option("--bits", o.training.bits, "code length")->check(CLI::IsMember({64, 128, 256}));
  app.add_option("--scales", o.layout.scales, "descriptor scales j, lambda = 4 * 2^(j/2) of the 32 px patch")
      ->delimiter(',');
  app.add_option("--levels", o.sampling.levels, "pyramid levels keypoints are detected at")
      ->delimiter(',')
      ->check(biovision_common::kNonNegative);
  app.add_option("--patch", o.layout.patch_wavelengths, "patch side in keypoint wavelengths (8: 32 px at lambda 4)");
  app.add_option("--pooling", pooling, "pooling disk diameter and step in level px (D,S)")->delimiter(',');
  app.add_option("--phases", o.layout.phases, "4: even, odd, -even, -odd maxima; 2: signed even, odd maxima only");
  app.add_option("--shape", shape,
                 "affine shape adaptation of the pooling grid (I,W,L,A): iterations (0: square grid), window sigma "
                 "[wavelengths], gradient level offset, largest anisotropy")
      ->delimiter(',')
      ->default_str(shape_default.str());
  app.add_option("--warps", o.warps, "add N synthetic camera tilts of every training image (ASIFT model)")
      ->check(biovision_common::kNonNegative);
  app.add_option("--max-tilt", o.max_tilt, "largest synthetic tilt")->check(biovision_common::kPositive);
  app.add_option("--warp-pairs", o.warp_pairs, "pairs per warp")->check(biovision_common::kPositive);
  app.add_option("--pairs", o.sampling.max_pairs, "pairs of each kind per image pair")
      ->check(biovision_common::kPositive);
  app.add_option(
         "--rank", o.ranks,
         "eigenpairs of Sigma_N kept for the whitening; several (comma-separated): one model each from the same "
         "pairs (with --power-iterations: every combination), written as <out stem>_rank<R>_it<I><ext>")
      ->delimiter(',')
      ->check(biovision_common::kPositive);
  app.add_option("--power-iterations", o.iterations,
                 "randomised subspace iterations for Sigma_N's leading eigenpairs (more: closer to the exact ones); "
                 "several: one model each")
      ->delimiter(',')
      ->check(biovision_common::kNonNegative);
  app.add_option("--ridge", o.training.ridge, "whitening ridge, relative to Sigma_N's largest eigenvalue")
      ->check(biovision_common::kPositive);
  app.add_option("--threshold-pairs", o.threshold_pairs,
                 "pairs of each kind the thresholds are chosen on (a uniform sample of all pairs; memory: 4 x this x "
                 "features floats)")
      ->check(biovision_common::kPositive);
  app.add_option("--threads", o.threads, "threads for Eigen's products")->check(biovision_common::kPositive);
  app.add_option("--json", o.json_path, "write the training statistics to this file");
  app.callback([&] {
    if (o.stereo.empty() && o.sequence.empty() && o.images.empty())
      throw CLI::RequiredError("--stereo, --sequence or --images");
    for (const int rank : o.ranks)
      if (rank < o.training.bits)  // checked before any model is trained, not after the first is written
        throw CLI::ValidationError("--rank " + std::to_string(rank) + " is below --bits " +
                                   std::to_string(o.training.bits));
    o.layout.pooling_diameter = pooling[0];
    o.layout.pooling_step = pooling[1];
    auto& adaptation = o.layout.shape;
    std::tie(adaptation.iterations, adaptation.window_wavelengths, adaptation.level_offset,
             adaptation.max_anisotropy) = shape;
    try
    {
      o.layout.validate();  // the layout's bounds are written there only
    }
    catch (const std::invalid_argument& e)
    {
      throw CLI::ValidationError(e.what());
    }
  });
  options.parse(argc, argv);
  o.command = options.command();
  return o;
}

}  // namespace

int main(int argc, char** argv)
{
  const Options o = parseOptions(argc, argv);
  Eigen::setNbThreads(o.threads);
  const auto t0 = std::chrono::steady_clock::now();
  try
  {
    const DescriptorLayout& layout = o.layout;
    const PooledCellFeatures features(layout);
    PairSampler sampler(o.sampling);
    V1FeaturePyramid::Parameters pp;
    pp.orientations = layout.orientations;
    pp.pooling_diameter = layout.pooling_diameter;
    pp.pooling_phases = layout.phases;
    V1FeaturePyramid pa(pp), pb(pp);

    auto pairs = loadCorrespondencePairs(o.stereo, o.part, o.sequence, o.targets, o.all_pairs);
    const size_t real_pairs = pairs.size();
    if (o.warps > 0)
    {
      const auto warps = syntheticViewpoints(pairs, o.warps, o.max_tilt, 11);
      pairs.insert(pairs.end(), warps.begin(), warps.end());
    }
    PairSampler::Parameters wp = o.sampling;
    wp.max_pairs = o.warp_pairs;
    PairSampler warp_sampler(wp);
    const size_t warped_pairs = pairs.size();
    std::vector<std::string> sources;
    if (!o.images.empty())
    {
      const std::string part = collectionPart(o.part, "dev");
      const auto images = listSourceImages(o.images, o.per_source, part);
      std::mt19937 rng(23);
      for (const auto& image : images)
      {
        const cv::Mat bgr = cv::imread(image.path, cv::IMREAD_COLOR);
        if (bgr.empty() || std::min(bgr.cols, bgr.rows) < 128)
          continue;  // unreadable or too small for keypoints at 8 wavelengths
        if (std::find(sources.begin(), sources.end(), image.source) == sources.end())
          sources.push_back(image.source);
        for (int k = 0; k < o.synthetic; ++k)
          pairs.push_back(syntheticPair(bgr,
                                        "synthetic/" + image.source + "/" +
                                            std::filesystem::path(image.path).filename().string() + "/" +
                                            std::to_string(k),
                                        o.synthetic_tilt, o.photometric, rng));
      }
      std::cerr << "synthetic pairs: " << pairs.size() - warped_pairs << " from " << images.size() << " images of "
                << sources.size() << " " << part << " sources\n";
    }
    PairSampler::Parameters sp = o.sampling;
    sp.max_pairs = o.synthetic_pairs;
    PairSampler synthetic_sampler(sp);

    // Folded into second moments image pair by image pair: memory is bounded by the feature count and the
    // threshold sample, not by the number of pairs.
    using Kind = LdaHashStatistics::Kind;
    LdaHashStatistics statistics(layout.featureCount(), o.threshold_pairs, o.training.seed);
    for (size_t i = 0; i < pairs.size(); ++i)
    {
      const CorrespondencePair& pair = pairs[i];
      pa.build(biovision_v1::InputImage(pair.a).gray());
      pb.build(biovision_v1::InputImage(pair.b).gray());
      const auto p = samplePairs(i < real_pairs ? sampler : (i < warped_pairs ? warp_sampler : synthetic_sampler), pair,
                                 pa, pb);
      if (p.positive_a.empty() || p.negative_a.empty())
      {
        std::cerr << "[" << i + 1 << "/" << pairs.size() << "] " << pair.name << ": no pairs (skipped)\n";
        continue;  // e.g. a flat synthetic image: no keypoint
      }
      auto add = [&](Kind kind, const auto& keypoints_a, const auto& keypoints_b) {
        const cv::Mat xa = features.extract(pa, keypoints_a), xb = features.extract(pb, keypoints_b);
        const Eigen::Map<const LdaHashStatistics::Matrix> a(xa.ptr<float>(), xa.rows, xa.cols),
            b(xb.ptr<float>(), xb.rows, xb.cols);
        statistics.add(kind, a, a - b);
      };
      add(Kind::positive, p.positive_a, p.positive_b);
      add(Kind::negative, p.negative_a, p.negative_b);
      std::cerr << "[" << i + 1 << "/" << pairs.size() << "] " << pair.name << ": " << p.positive_a.size()
                << " pairs of each kind\n";
    }
    const long positives = statistics.pairs(Kind::positive), negatives = statistics.pairs(Kind::negative);
    std::cerr << "training on " << positives << " positive and " << negatives << " negative pairs, "
              << layout.featureCount() << " features\n";
    const std::time_t now = std::time(nullptr);
    char date[32];
    std::strftime(date, sizeof(date), "%Y-%m-%d", std::gmtime(&now));
    nlohmann::ordered_json report, models = nlohmann::ordered_json::array();
    // Several ranks and iteration counts share one pass over the images (the costly part): one model each.
    const bool several = o.ranks.size() * o.iterations.size() > 1;
    for (const int rank : o.ranks)
      for (const int iterations : o.iterations)
      {
        LdaHashTrainer::Parameters training = o.training;
        training.whitening_rank = rank;
        training.power_iterations = iterations;
        DescriptorModel model = LdaHashTrainer(training).train(statistics);
        model.layout = layout;
        std::string out = o.out;
        if (several)
        {
          const std::string variant = "_rank" + std::to_string(rank) + "_it" + std::to_string(iterations);
          const std::filesystem::path path(o.out);
          out = (path.parent_path() / (path.stem().string() + variant + path.extension().string())).string();
        }
        model.provenance = "rosrun biovision_recognition train_descriptor " + o.command + "  (" +
                           (several ? "this model: rank " + std::to_string(rank) + ", " + std::to_string(iterations) +
                                          " power iterations, "
                                    : "") +
                           std::to_string(positives) + " positive / " + std::to_string(negatives) +
                           " negative pairs, " + date + ")";
        model.save(out);
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        std::cerr << "wrote " << out << " (" << model.id() << ", rank " << rank << ", " << iterations
                  << " power iterations) at " << seconds << " s\n";
        models.push_back({{"file", out}, {"model", model.id()}, {"rank", rank}, {"power_iterations", iterations}});
        if (report.empty())
          report["model"] = model.id();  // the first, as before
      }
    if (!o.json_path.empty())
    {
      report["models"] = models;
      report["features"] = layout.featureCount();
      report["bits"] = o.training.bits;
      report["positive_pairs"] = positives;
      report["negative_pairs"] = negatives;
      report["threshold_pairs"] = o.threshold_pairs;
      report["seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      report["image_pairs"] = pairs.size();
      report["synthetic_sources"] = sources;
      biovision_common::writeJsonFile(o.json_path, report);
    }
  }
  catch (const std::exception& e)
  {
    std::cerr << "train_descriptor: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
