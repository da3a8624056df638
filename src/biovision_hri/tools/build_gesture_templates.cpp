// Builds the gesture template file for the hri node: the template part of the LinTO frames (their
// earlier recording session; hand box from the annotation) under their gesture labels, plus rejection
// templates ("none") from random patches of the training scenes. Stored as an ObjectMemory
// (StoredFile "BVOBJMEM": checksummed, atomic, tied to the descriptor model). With --posture-out, the
// same regions also train the hand posture SVMs (HandPostureClassifier, StoredFile "BVHRIPOS").

#include <ctime>
#include <filesystem>
#include <iostream>
#include <map>
#include <sstream>
#include <stdexcept>

#include <ros/package.h>

#include "biovision_common/tool_options.hpp"
#include "biovision_hri/gesture_recognizer.hpp"
#include "biovision_recognition/descriptor_model.hpp"
#include "biovision_hri/hand_posture_classifier.hpp"
#include "hri_datasets.hpp"

using namespace biovision_hri;

int main(int argc, char** argv)
{
  std::string out, posture_out, data = hriDataRoot("../shared"), set = "linto", json_path;
  std::string descriptor_model = ros::package::getPath("biovision_recognition") + "/models/" +
                                 biovision_recognition::kDefaultModelFile;
  int rejection = 100, seed = 3;
  // Triesch's postures are ASL letters: B is the open palm, D the raised index, V the V sign, A the fist;
  // renamed to the node's gesture names (the `actions` table reads these). Others keep their letter.
  std::string label_map = "A=fist,B=palm,D=index_up,V=v";
  biovision_common::ToolOptions options("build_gesture_templates",
                                        "Builds the gesture templates of the hri node from the template part of a "
                                        "gesture set\n(LinTO: earlier session; Triesch: first half of the people) "
                                        "plus rejection templates from training scenes.");
  CLI::App& app = options.app();
  app.add_option("--out", out, "template file to write (the node's ~gesture_templates)")->required();
  app.add_option("--posture-out", posture_out,
                 "also train the hand posture SVMs on the same regions and write them (the node's ~posture_model)");
  app.add_option("--set", set, "linto or triesch")->check(CLI::IsMember({"linto", "triesch"}));
  app.add_option("--data", data, "the hri data folder ($BIOVISION_SHARED/data/hri)");
  app.add_option("--descriptor-model", descriptor_model, "biovision_recognition descriptor model");
  app.add_option(
         "--rejection", rejection,
         "rejection templates ('none') from random training-scene patches (100: chosen with gesture_eval --validation)")
      ->check(biovision_common::kNonNegative);
  app.add_option("--seed", seed, "seed of the rejection patches");
  app.add_option("--label-map", label_map,
                 "renames of the set's labels, FROM=TO,... (default: Triesch's ASL letters to the node's names)");
  app.add_option("--json", json_path, "write a summary");
  options.parse(argc, argv);
  try
  {
    // Refuse what would fail half way (after the template file was replaced) before any work.
    namespace fs = std::filesystem;
    if (!posture_out.empty() && fs::absolute(posture_out).lexically_normal() == fs::absolute(out).lexically_normal())
      throw std::invalid_argument("--out and --posture-out name the same file");
    for (const std::string& f : {out, posture_out})
      if (!f.empty())
      {
        const fs::path folder = fs::absolute(f).parent_path();
        if (!fs::is_directory(folder))
          throw std::invalid_argument("no folder " + folder.string() + " for " + f);
      }
    auto descriptor = std::make_shared<const biovision_recognition::V1Descriptor>(
        biovision_recognition::DescriptorModel::load(descriptor_model));
    GestureRecognizer recognizer(descriptor, GestureRecognizer::Parameters());
    HandPostureClassifier posture{FeatureLayout(), HandPostureClassifier::Parameters()};
    const auto samples = set == "linto" ? lintoSamples(data) : trieschSamples(data);
    std::map<std::string, std::string> renames;
    std::stringstream pairs(label_map);
    for (std::string pair; std::getline(pairs, pair, ',');)
    {
      const size_t eq = pair.find('=');
      if (eq == std::string::npos || eq == 0 || eq + 1 == pair.size())
        throw std::invalid_argument("--label-map: expected FROM=TO, got '" + pair + "'");
      renames[pair.substr(0, eq)] = pair.substr(eq + 1);
    }
    auto renamed = [&](const std::string& label) {
      const auto it = renames.find(label);
      return it == renames.end() ? label : it->second;
    };
    nlohmann::ordered_json per_label = nlohmann::ordered_json::object();  // value() refuses a null
    for (const auto& g : samples)
    {
      if (!g.template_part)
        continue;
      cv::Mat image = readGray(g.file);
      cv::Rect box = g.box;
      if (set == "triesch")
      {
        cv::copyMakeBorder(image, image, 20, 20, 20, 20, cv::BORDER_REPLICATE);
        box = cv::Rect(20, 20, image.cols - 40, image.rows - 40);
      }
      const std::string label = renamed(g.label);
      const size_t k = recognizer.addTemplate(image, box, label);
      if (!posture_out.empty())
        posture.addExample(image, box, label);
      per_label[label] = per_label.value(label, 0) + 1;
      std::cerr << "build_gesture_templates: " << label << " <- " << g.file << " (" << k << " keypoints)\n";
    }
    std::vector<cv::Mat> scenes;
    for (const auto& f : splitPart(sceneFiles(data), Split::Train))
      scenes.push_back(readGray(f));
    cv::RNG rng(static_cast<uint64_t>(seed));
    for (const cv::Mat& patch : randomScenePatches(scenes, rejection, rng, 100, 250))
    {
      recognizer.addTemplate(patch, cv::Rect(0, 0, patch.cols, patch.rows), "none");
      if (!posture_out.empty())
        posture.addExample(patch, cv::Rect(0, 0, patch.cols, patch.rows), "none");
    }
    if (!posture_out.empty())
      posture.train();  // before any file is written: a failure leaves both as they were
    recognizer.saveTemplates(out);
    if (!posture_out.empty())
    {
      char date[16];
      const std::time_t now = std::time(nullptr);
      std::strftime(date, sizeof date, "%Y-%m-%d", std::gmtime(&now));
      posture.save(posture_out, options.command() + " | " + set + " template part, " +
                                    std::to_string(posture.exampleCount()) + " augmented examples | " + date);
      std::cerr << "build_gesture_templates: wrote " << posture_out << ": " << posture.labels().size()
                << " classes from " << posture.exampleCount() << " augmented examples\n";
    }
    std::cerr << "build_gesture_templates: wrote " << out << ": " << recognizer.templates().views().size()
              << " templates, " << recognizer.templates().codeCount() << " codes\n";
    if (!json_path.empty())
      biovision_common::writeJsonFile(
          json_path, nlohmann::ordered_json{{"tool", "build_gesture_templates"},
                                            {"command", options.command()},
                                            {"set", set},
                                            {"label_map", label_map},
                                            {"min_matches_default", GestureRecognizer::Parameters().min_matches},
                                            {"templates_per_label", per_label},
                                            {"rejection_templates", rejection},
                                            {"codes", recognizer.templates().codeCount()},
                                            {"out", out},
                                            {"posture_out", posture_out}});
  }
  catch (const std::exception& e)
  {
    std::cerr << "build_gesture_templates: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
