// Gesture recognition on held-out data: LinTO frames of the later recording session against templates of
// the earlier one, or Triesch postures of the second half of the people against templates of the first
// half. Three methods: V1 keypoint templates (thesis §2.4, GestureRecognizer), the hand region's
// complex-cell HOG classified by linear SVMs (HandPostureClassifier, ours), and both (keypoints when they
// verify a gesture, else the SVMs). The hand region is the annotated box (the detector's job is measured
// by detector_eval). Reports accuracy, the confusion matrix, and false gestures on gesture-free regions
// (random patches of held-out scenes) with and without the rejection class.

#include <chrono>
#include <functional>
#include <iostream>
#include <map>
#include <set>

#include <ros/package.h>

#include "biovision_common/tool_options.hpp"
#include "biovision_hri/gesture_recognizer.hpp"
#include "biovision_recognition/descriptor_model.hpp"
#include "biovision_hri/hand_gesture_reader.hpp"
#include "biovision_hri/hand_posture_classifier.hpp"
#include "hri_datasets.hpp"

using namespace biovision_hri;

int main(int argc, char** argv)
{
  std::string data = hriDataRoot("../shared"), set = "linto", json_path;
  std::string descriptor_model = ros::package::getPath("biovision_recognition") + "/models/" +
                                 biovision_recognition::kDefaultModelFile;
  int rejection = 100, free_regions = 200, seed = 3;
  bool validation = false;
  GestureRecognizer::Parameters p;
  HandPostureClassifier::Parameters posture;
  biovision_common::ToolOptions options("gesture_eval",
                                        "Evaluates gesture recognition (V1 keypoint templates, hand posture SVMs, "
                                        "both) on held-out frames "
                                        "(LinTO: later session;\nTriesch: other people), with false gestures on "
                                        "gesture-free regions of held-out scenes.");
  CLI::App& app = options.app();
  app.add_option("--set", set, "linto or triesch")->check(CLI::IsMember({"linto", "triesch"}));
  app.add_option("--data", data, "the hri data folder ($BIOVISION_SHARED/data/hri)");
  app.add_option("--descriptor-model", descriptor_model, "biovision_recognition descriptor model");
  app.add_option("--rejection", rejection,
                 "rejection templates from random training-scene patches (100: chosen with --validation, README)")
      ->check(biovision_common::kNonNegative);
  app.add_option("--free-regions", free_regions, "gesture-free test regions from held-out scenes")
      ->check(biovision_common::kNonNegative);
  app.add_option("--max-distance", p.max_distance, "Hamming radius [bits] (thesis: < 30)");
  app.add_option("--min-matches", p.min_matches,
                 "verified matches for a gesture (thesis: >= 4; default chosen on validation)");
  app.add_option("--posture-C", posture.C, "hand posture SVMs: soft-margin cost");
  app.add_option("--posture-rotation", posture.rotation, "hand posture SVMs: augmentation rotation [deg]");
  app.add_option("--posture-margin", posture.margin, "hand posture SVMs: context around the box");
  app.add_option("--posture-min-score", posture.min_score, "hand posture SVMs: score needed for a gesture");
  app.add_option("--seed", seed, "seed of the random patches");
  app.add_option("--validation", validation,
                 "for parameter choices: split the template part itself (first half of its people / frames "
                 "gives templates, the rest is tested) and take gesture-free regions from validation scenes; "
                 "the held-out part is not read");
  app.add_option("--json", json_path, "write the results");
  options.parse(argc, argv);
  try
  {
    const auto start = std::chrono::steady_clock::now();
    auto descriptor = std::make_shared<const biovision_recognition::V1Descriptor>(
        biovision_recognition::DescriptorModel::load(descriptor_model));
    auto samples = set == "linto" ? lintoSamples(data) : trieschSamples(data);
    if (validation)
    {
      // Keep the template part only and split it again: Triesch by person, LinTO by frame order per gesture.
      std::vector<GestureSample> part;
      std::copy_if(samples.begin(), samples.end(), std::back_inserter(part),
                   [](const GestureSample& g) { return g.template_part; });
      std::vector<std::string> groups;
      for (const auto& g : part)
        groups.push_back(g.group);
      std::sort(groups.begin(), groups.end());
      groups.erase(std::unique(groups.begin(), groups.end()), groups.end());
      std::map<std::string, int> seen;
      for (auto& g : part)
        g.template_part = set == "triesch" ? std::lower_bound(groups.begin(), groups.end(), g.group) - groups.begin() <
                                                 static_cast<long>(groups.size() / 2)
                                           : seen[g.label]++ == 0;
      samples = part;
    }
    auto load = [&](const GestureSample& g, cv::Rect& box) {
      cv::Mat image = readGray(g.file);
      box = g.box;
      if (set == "triesch")
      {
        cv::copyMakeBorder(image, image, 20, 20, 20, 20, cv::BORDER_REPLICATE);
        box = cv::Rect(20, 20, image.cols - 40, image.rows - 40);
      }
      return image;
    };
    std::vector<cv::Mat> train_scenes, test_scenes;
    for (const auto& f : splitPart(sceneFiles(data), Split::Train))
      train_scenes.push_back(readGray(f));
    for (const auto& f : splitPart(sceneFiles(data), validation ? Split::Validation : Split::Test))
      test_scenes.push_back(readGray(f));
    cv::RNG rng(static_cast<uint64_t>(seed));
    const auto rejection_patches = randomScenePatches(train_scenes, rejection, rng, 100, 250);
    const int free_side = set == "linto" ? 100 : 60;
    const auto free_patches = randomScenePatches(test_scenes, free_regions, rng, free_side, free_side * 5 / 2);

    nlohmann::ordered_json runs = nlohmann::ordered_json::object(), confusions = nlohmann::ordered_json::object();
    std::set<std::string> labels;
    int templates = 0;
    for (const auto& g : samples)
      if (g.template_part)
      {
        labels.insert(g.label);
        ++templates;
      }
    // Runs one method on the tested regions and the gesture-free regions.
    using Classify = std::function<GestureResult(const cv::Mat&, const cv::Rect&)>;
    auto evaluate = [&](const std::string& method, const std::string& run, const Classify& classify) {
      std::map<std::string, std::map<std::string, int>> confusion;
      int correct = 0, tested = 0, unrecognised = 0;
      std::vector<double> ms;
      for (const auto& g : samples)
      {
        if (g.template_part)
          continue;
        cv::Rect box;
        const cv::Mat image = load(g, box);
        const auto t0 = std::chrono::steady_clock::now();
        const GestureResult r = classify(image, box);
        ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
        const std::string predicted = r.label.empty() ? "(none)" : r.label;
        ++confusion[g.label][predicted];
        correct += predicted == g.label;
        unrecognised += r.label.empty();
        ++tested;
      }
      int false_gestures = 0;
      for (const cv::Mat& patch : free_patches)
        false_gestures += !classify(patch, cv::Rect(0, 0, patch.cols, patch.rows)).label.empty();
      std::sort(ms.begin(), ms.end());
      const double accuracy = tested ? static_cast<double>(correct) / tested : 0.0;
      const double false_rate = free_patches.empty() ? 0.0 : static_cast<double>(false_gestures) / free_patches.size();
      const bool with_rejection = run == "with_rejection_class";
      confusions[method][run] = confusion;
      runs[method][run] = {{"labels", labels.size()},
                           {"templates", templates},
                           {"rejection_templates", with_rejection ? rejection : 0},
                           {"tested", tested},
                           {"accuracy", accuracy},
                           {"no_gesture_on_gesture_frames", tested ? static_cast<double>(unrecognised) / tested : 0.0},
                           {"gesture_free_regions", free_patches.size()},
                           {"false_gesture_rate", false_rate},
                           {"median_ms_per_region", ms.empty() ? 0.0 : ms[ms.size() / 2]}};
      std::cerr << "gesture_eval: " << set << " " << method << (with_rejection ? " with" : " without")
                << " rejection class: accuracy " << accuracy << " (" << correct << "/" << tested
                << "), false gestures on " << free_patches.size() << " gesture-free regions " << false_rate << ", "
                << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() << " s\n";
    };
    for (const bool with_rejection : {false, true})
    {
      const std::string run = with_rejection ? "with_rejection_class" : "without_rejection_class";
      GestureRecognizer recognizer(descriptor, p);
      HandPostureClassifier classifier{FeatureLayout(), posture};
      for (const auto& g : samples)
        if (g.template_part)
        {
          cv::Rect box;
          const cv::Mat image = load(g, box);
          recognizer.addTemplate(image, box, g.label);
          classifier.addExample(image, box, g.label);
        }
      if (with_rejection)
        for (const cv::Mat& patch : rejection_patches)
        {
          recognizer.addTemplate(patch, cv::Rect(0, 0, patch.cols, patch.rows), "none");
          classifier.addExample(patch, cv::Rect(0, 0, patch.cols, patch.rows), "none");
        }
      classifier.train();
      auto keypoints = [&](const cv::Mat& image, const cv::Rect& box) {
        return recognizer.recognize(image, {box}).front();
      };
      auto appearance = [&](const cv::Mat& image, const cv::Rect& box) {
        return classifier.classify(image, {box}).front();
      };
      const HandGestureReader node_rule(&recognizer, &classifier);
      evaluate("keypoints", run, keypoints);
      evaluate("posture_svm", run, appearance);
      evaluate("keypoints_then_posture_svm", run, [&](const cv::Mat& image, const cv::Rect& box) {
        return node_rule.read(image, {box}, {box}).front().result;
      });
    }
    if (!json_path.empty())
    {
      nlohmann::ordered_json doc;
      doc["tool"] = "gesture_eval";
      doc["command"] = options.command();
      doc["set"] = set;
      doc["reported_on"] = validation ? "validation (the template part split again)" : "test";
      doc["split"] = set == "linto" ? "templates: LinTO session 11eb (earlier); tested: session 11ec (later)"
                                    : "templates: first half of the people by name; tested: the other half";
      doc["hand_regions"] = "annotated boxes (LinTO) / whole crops padded by 20 px (Triesch)";
      doc["max_distance"] = p.max_distance;
      doc["min_matches"] = p.min_matches;
      doc["posture_svm"] = {{"C", posture.C},
                            {"rotation_deg", posture.rotation},
                            {"mirror", posture.mirror},
                            {"margin", posture.margin},
                            {"min_score", posture.min_score}};
      doc["runs"] = runs;
      doc["confusion"] = confusions;
      doc["notes"] = std::string("Held out: ") + doc["split"].get<std::string>() +
                     ". Gesture-free regions: random patches of the test part of the negative scenes. Data: " +
                     (set == "linto" ? "LinTO multi-hand-gesture dataset."
                                     : "Triesch & von der Malsburg hand postures.");
      biovision_common::writeJsonFile(json_path, doc);
    }
  }
  catch (const std::exception& e)
  {
    std::cerr << "gesture_eval: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
