// Trains a face or hand window classifier: complex-cell HOG-like features (thesis §2.3) + a LIBLINEAR
// linear SVM (C = 0.01), positives from the training part of the crops (with mirror images), random
// negative patches of the training scenes, then hard-negative mining rounds (thesis: one) on the same
// training scenes. Writes a versioned, checksummed model (LinearDetectorModel, StoredFile "BVHRIDET").

#include <chrono>
#include <ctime>
#include <iostream>

#include "biovision_common/tool_options.hpp"
#include "biovision_hri/linear_svm_trainer.hpp"
#include "biovision_hri/sliding_window_detector.hpp"
#include "hri_datasets.hpp"

using namespace biovision_hri;

namespace
{
double secondsSince(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void append(cv::Mat& samples, std::vector<int>& labels, const cv::Mat& rows, int label)
{
  if (rows.empty())
    return;
  samples.push_back(rows);
  labels.insert(labels.end(), rows.rows, label);
}

/// Fraction of rows whose score has the label's sign.
double accuracy(const LinearDetectorModel& model, const cv::Mat& samples, const std::vector<int>& labels)
{
  int correct = 0;
  for (int i = 0; i < samples.rows; ++i)
    correct += (model.score(samples.ptr<float>(i)) > 0) == (labels[i] > 0);
  return samples.rows ? static_cast<double>(correct) / samples.rows : 0.0;
}
}  // namespace

int main(int argc, char** argv)
{
  std::string kind = "face", out, json_path, data = hriDataRoot("../shared"), split_name = "train";
  int max_positives = 0, random_negatives = 10000, hard_rounds = 1, hard_per_image = 100, seed = 1;
  double positive_weight = 0.0;
  std::string hard_features = "dense";
  double min_size = 42, max_size = 300;
  FeatureLayout layout;
  LinearSvmTrainer::Parameters svm;
  biovision_common::ToolOptions options(
      "train_detector",
      "Trains the face or hand detector of biovision_hri (thesis ch. 2): V1 complex-cell HOG-like features,\n"
      "LIBLINEAR linear SVM, random + hard negatives. Uses only the chosen part of the data (default: train;\n"
      "see README 'Data and splits'). Progress on stderr.");
  CLI::App& app = options.app();
  app.add_option("--kind", kind, "face or hand")->check(CLI::IsMember({"face", "hand"}));
  app.add_option("--out", out, "model file to write (atomically)")->required();
  app.add_option("--data", data, "the hri data folder ($BIOVISION_SHARED/data/hri)");
  app.add_option("--split", split_name, "data part to train on: train (the committed models) or validation")
      ->check(CLI::IsMember({"train", "validation"}));
  app.add_option("--max-positives", max_positives, "use at most this many positive crops (0 = all of the part)")
      ->check(biovision_common::kNonNegative);
  app.add_option("--negatives", random_negatives, "random negative patches from the part's scenes")
      ->check(biovision_common::kNonNegative);
  app.add_option("--hard-rounds", hard_rounds, "hard-negative mining rounds (thesis: 1)")
      ->check(biovision_common::kNonNegative);
  app.add_option("--hard-per-image", hard_per_image, "at most this many hard negatives per scene and round")
      ->check(biovision_common::kPositive);
  app.add_option("--hard-features", hard_features,
                 "hard negatives' features: dense (read from the scan's block maps, what was scored; default) or "
                 "crop (the window re-cropped and extracted alone, its borders reflected: the first version)")
      ->check(CLI::IsMember({"dense", "crop"}));
  app.add_option("--min-size", min_size, "smallest window scanned while mining [px]")
      ->check(biovision_common::kPositive);
  app.add_option("--max-size", max_size, "largest window scanned while mining [px]")
      ->check(biovision_common::kPositive);
  app.add_option("--C", svm.C, "LIBLINEAR cost (thesis: 0.01)")->check(biovision_common::kPositive);
  app.add_option("--solver", svm.solver,
                 "LIBLINEAR solver_type (1 = L2R_L2LOSS_SVC_DUAL, 2 = primal, 3 = L1-loss dual)");
  app.add_option("--bias", svm.bias, "LIBLINEAR bias feature value (<= 0: none)");
  app.add_option("--positive-weight", positive_weight,
                 "C multiplier of the positive class (LIBLINEAR -w1); 0 = negatives / positives of each round, so "
                 "both classes weigh the same (the thesis' sets were about balanced; ours are not)")
      ->check(biovision_common::kNonNegative);
  app.add_option("--wavelength", layout.wavelength, "Gabor wavelength lambda [px] (thesis: 4 best)");
  app.add_option("--orientations", layout.orientations, "N_theta");
  app.add_option("--aspect-ratio", layout.aspect_ratio, "Gabor envelope gamma (1 = isotropic)");
  app.add_option("--epsilon", layout.epsilon, "L2 block normalisation epsilon per pixel");
  app.add_option("--clip", layout.clip, "L2-Hys clipping of normalised block values (0 = plain L2, the thesis)");
  app.add_option("--grid-step", layout.grid_step, "Gabor response grid step (1 = full resolution, 2 = half)");
  app.add_option("--cell-size", layout.cell_size, "pooling cell side at the base scale [px] (thesis: 6)");
  app.add_option("--seed", seed, "random negatives' seed");
  app.add_option("--json", json_path, "write a summary (counts, accuracies, time)");
  options.parse(argc, argv);

  try
  {
    layout.validate();
    const auto start = std::chrono::steady_clock::now();
    const Split split = splitFromString(split_name);
    std::vector<std::string> positives = splitPart(positiveCrops(data, kind), split);
    if (max_positives > 0 && static_cast<int>(positives.size()) > max_positives)
    {
      // Evenly spread over the part, not its first files (those come from few web photos).
      std::vector<std::string> subset;
      for (int i = 0; i < max_positives; ++i)
        subset.push_back(positives[static_cast<size_t>(i) * positives.size() / max_positives]);
      positives = subset;
    }
    const std::vector<std::string> negative_crops = splitPart(negativeCrops(data, kind), split);
    const std::vector<std::string> scene_files = splitPart(sceneFiles(data), split);
    std::vector<cv::Mat> scenes;
    for (const auto& f : scene_files)
      scenes.push_back(readGray(f));

    std::vector<cv::Mat> patches;
    for (const auto& f : positives)
      patches.push_back(readGray(f));
    cv::Mat samples;
    std::vector<int> labels;
    append(samples, labels, patchFeatureRows(layout, patches, true), 1);
    const int positive_rows = samples.rows;
    std::cerr << "train_detector: " << kind << ": " << positive_rows << " positive windows (" << positives.size()
              << " crops + mirrors), " << secondsSince(start) << " s\n";
    patches.clear();
    for (const auto& f : negative_crops)
      patches.push_back(readGray(f));
    cv::RNG rng(static_cast<uint64_t>(seed));
    const std::vector<cv::Mat> random = randomScenePatches(scenes, random_negatives, rng, 42, 300);
    patches.insert(patches.end(), random.begin(), random.end());
    append(samples, labels, patchFeatureRows(layout, patches, false), -1);
    std::cerr << "train_detector: " << samples.rows - positive_rows << " negative windows (" << negative_crops.size()
              << " crops, " << random.size() << " random scene patches from " << scenes.size() << " scenes), "
              << secondsSince(start) << " s\n";

    LinearDetectorModel model;
    model.kind = kind;
    model.layout = layout;
    auto fit = [&]() {
      svm.positive_weight = positive_weight > 0 ? positive_weight
                                                : static_cast<double>(samples.rows - positive_rows) / positive_rows;
      const auto result = LinearSvmTrainer::train(samples, labels, svm);
      model.weights = result.weights;
      model.bias = result.bias;
    };
    fit();
    nlohmann::ordered_json rounds = nlohmann::ordered_json::array();
    rounds.push_back(
        {{"round", 0}, {"samples", samples.rows}, {"training_accuracy", accuracy(model, samples, labels)}});
    std::cerr << "train_detector: round 0: training accuracy " << accuracy(model, samples, labels) << ", "
              << secondsSince(start) << " s\n";

    for (int round = 1; round <= hard_rounds; ++round)
    {
      SlidingWindowDetector::Parameters scan;
      scan.min_size = min_size;
      scan.max_size = max_size;
      scan.threshold = 0.0;
      scan.nms_overlap = 0.7;
      scan.max_detections = hard_per_image;
      SlidingWindowDetector detector(model, scan);
      std::vector<cv::Mat> hard;
      cv::Mat hard_rows;
      long windows = 0;
      for (size_t s = 0; s < scenes.size(); ++s)
      {
        SlidingWindowDetector::Statistics stats;
        for (const Detection& d : detector.detect(scenes[s], cv::Rect(), &stats))
        {
          if (hard_features == "dense")
          {
            cv::Mat row(1, layout.featureCount(), CV_32F);
            detector.lastFeatures(d, row.ptr<float>());
            hard_rows.push_back(row);
            hard.push_back(cv::Mat());
            continue;
          }
          const cv::Rect box = cv::Rect(d.box) & cv::Rect(0, 0, scenes[s].cols, scenes[s].rows);
          if (box.width >= 8 && box.height >= 8)
            hard.push_back(scenes[s](box));
        }
        windows += stats.windows;
        if ((s + 1) % 10 == 0 || s + 1 == scenes.size())
          std::cerr << "train_detector: round " << round << ": scene " << s + 1 << "/" << scenes.size() << ", "
                    << hard.size() << " hard negatives, " << secondsSince(start) << " s\n";
      }
      append(samples, labels, hard_features == "dense" ? hard_rows : patchFeatureRows(layout, hard, false), -1);
      fit();
      rounds.push_back({{"round", round},
                        {"windows_scanned", windows},
                        {"hard_negatives", hard.size()},
                        {"samples", samples.rows},
                        {"training_accuracy", accuracy(model, samples, labels)}});
      std::cerr << "train_detector: round " << round << ": " << hard.size() << " hard negatives of " << windows
                << " windows, training accuracy " << accuracy(model, samples, labels) << ", " << secondsSince(start)
                << " s\n";
    }

    const std::time_t now = std::time(nullptr);
    char date[32];
    std::strftime(date, sizeof date, "%Y-%m-%d", std::gmtime(&now));
    model.provenance = "train_detector " + options.command() + " | part: " + split_name + " | " +
                       std::to_string(positive_rows) + " positive, " + std::to_string(samples.rows - positive_rows) +
                       " negative windows | " + date;
    model.save(out);
    std::cerr << "train_detector: wrote " << out << " (" << secondsSince(start) << " s)\n";
    if (!json_path.empty())
    {
      nlohmann::ordered_json doc;
      doc["tool"] = "train_detector";
      doc["command"] = options.command();
      doc["kind"] = kind;
      doc["trained_on"] = split_name;
      doc["positive_crops"] = positives.size();
      doc["positive_windows"] = positive_rows;
      doc["negative_windows"] = samples.rows - positive_rows;
      doc["scenes"] = scenes.size();
      doc["C"] = svm.C;
      doc["solver"] = svm.solver;
      doc["bias"] = svm.bias;
      doc["positive_weight"] = svm.positive_weight;
      doc["features"] = layout.featureCount();
      doc["layout"] = {{"wavelength", layout.wavelength},
                       {"orientations", layout.orientations},
                       {"cell_size", layout.cell_size},
                       {"epsilon", layout.epsilon},
                       {"clip", layout.clip},
                       {"grid_step", layout.grid_step}};
      doc["rounds"] = rounds;
      doc["hard_features"] = hard_features;
      doc["hard_rounds"] = hard_rounds;
      doc["seconds"] = secondsSince(start);
      doc["model"] = out;
      biovision_common::writeJsonFile(json_path, doc);
    }
  }
  catch (const std::exception& e)
  {
    std::cerr << "train_detector: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
