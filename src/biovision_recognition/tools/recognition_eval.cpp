// Object recognition on COIL-style folders (objN__ANGLE.png): library from the views at multiples of
// the template step, queries = the other views, plus distractor images that must give no label. Ours
// (V1 keypoints + LDAHash + Hamming + geometric verification) against ORB + BFMatcher + the same RANSAC
// verification, in the same run.

#include <chrono>
#include <iomanip>
#include <iostream>
#include <map>
#include <regex>

#include <opencv2/features2d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "biovision_recognition/object_recognizer.hpp"
#include "biovision_v1/input_image.hpp"
#include "biovision_common/tool_options.hpp"

using namespace biovision_recognition;
using biovision_common::listDirectory;

namespace
{
const char* kDescription =
    "Object recognition on COIL-style folders (objN__ANGLE.png): library from the views at multiples of the template\n"
    "step, queries = the other views, plus distractor images that must give no label. Ours (V1 keypoints + LDAHash +\n"
    "Hamming + geometric verification) against ORB + BFMatcher + the same RANSAC verification, in the same run.\n"
    "Prints a table; --json writes the results.";

struct View
{
  std::string label;
  int angle = 0;
  cv::Mat image;
};

cv::Mat load(const std::string& path, double upscale)
{
  cv::Mat img = cv::imread(path, cv::IMREAD_COLOR);
  if (img.empty())
    throw std::runtime_error(path + ": cannot read");
  if (upscale != 1.0)
    cv::resize(img, img, cv::Size(), upscale, upscale, cv::INTER_LINEAR);
  return img;
}

struct Outcome
{
  int correct = 0, wrong = 0, silent = 0, distractor_hits = 0, queries = 0, distractors = 0;
  double seconds = 0.0;
  size_t library_codes = 0;
};

/// ORB + BFMatcher + the same geometric verification: the baseline a ROS user would assemble.
class OrbBaseline
{
public:
  explicit OrbBaseline(const GeometricVerifier::Parameters& verifier) : orb_(cv::ORB::create(500)), verifier_(verifier)
  {
  }
  void learn(const cv::Mat& image, const std::string& label)
  {
    Entry e;
    e.label = label;
    orb_->detectAndCompute(image, cv::noArray(), e.keypoints, e.descriptors);
    if (!e.keypoints.empty())
      entries_.push_back(e);
  }
  std::string recognize(const cv::Mat& image)
  {
    std::vector<cv::KeyPoint> kps;
    cv::Mat desc;
    orb_->detectAndCompute(image, cv::noArray(), kps, desc);
    if (kps.empty())
      return "";
    std::string best;
    int best_inliers = 0;
    for (const auto& e : entries_)
    {
      std::vector<std::vector<cv::DMatch>> m;
      matcher_.knnMatch(desc, e.descriptors, m, 2);
      std::vector<cv::Point2f> from, to;
      for (const auto& q : m)  // Lowe's ratio test, as ORB users do
        if (!q.empty() && q[0].distance <= kMaxDistance && (q.size() < 2 || q[0].distance < kRatio * q[1].distance))
        {
          from.push_back(e.keypoints[q[0].trainIdx].pt);
          to.push_back(kps[q[0].queryIdx].pt);
        }
      const auto r = verifier_.verify(from, to);
      if (r.accepted && r.inliers > best_inliers)
      {
        best_inliers = r.inliers;
        best = e.label;
      }
    }
    return best;
  }
  size_t codes() const
  {
    size_t n = 0;
    for (const auto& e : entries_)
      n += e.keypoints.size();
    return n;
  }

private:
  static constexpr float kMaxDistance = 64.f;  // of 256 bits: the 25% our radius is of 128
  static constexpr float kRatio = 0.8f;
  struct Entry
  {
    std::string label;
    std::vector<cv::KeyPoint> keypoints;
    cv::Mat descriptors;
  };
  cv::Ptr<cv::ORB> orb_;
  cv::BFMatcher matcher_{cv::NORM_HAMMING};
  GeometricVerifier verifier_;
  std::vector<Entry> entries_;
};

/// Prints one method's row and returns its figures.
nlohmann::ordered_json outcomeJson(const std::string& name, const Outcome& o)
{
  const double n = std::max(1, o.queries);
  const double distractor_fp = o.distractors ? double(o.distractor_hits) / o.distractors : 0.0;
  const double ms_per_query = 1e3 * o.seconds / std::max(1, o.queries + o.distractors);
  std::cout << std::left << std::setw(8) << name << " recognised " << std::setw(9) << o.correct / n << " wrong "
            << std::setw(9) << o.wrong / n << " distractor FP " << std::setw(9) << distractor_fp << " ms/query "
            << ms_per_query << "\n";
  return {{"recognition_rate", o.correct / n},
          {"wrong_label_rate", o.wrong / n},
          {"no_label_rate", o.silent / n},
          {"distractor_false_positive_rate", distractor_fp},
          {"false_positive_rate", double(o.wrong + o.distractor_hits) / std::max(1, o.queries + o.distractors)},
          {"ms_per_query", ms_per_query},
          {"library_codes", o.library_codes}};
}
}  // namespace

int main(int argc, char** argv)
{
  std::string objects, model, distractors_dir, json_path;
  int step = 20, limit = 60;
  double upscale = 1.0;
  ObjectRecognizer::Parameters recognizer_parameters;
  biovision_common::ToolOptions options("recognition_eval", kDescription);
  CLI::App& app = options.app();
  app.add_option("--objects", objects, "objN__ANGLE.png views (COIL-100 naming)")
      ->required()
      ->check(CLI::ExistingDirectory);
  app.add_option("--model", model, "trained descriptor model")->required()->check(CLI::ExistingFile);
  app.add_option("--template-step", step, "library = views at multiples of this [deg]; queries = the others")
      ->check(biovision_common::kPositive);
  app.add_option("--distractors", distractors_dir,
                 "images that contain none of the objects: any label is a false positive")
      ->check(CLI::ExistingDirectory);
  app.add_option("--upscale", upscale, "resize every image by this factor first")->check(biovision_common::kPositive);
  app.add_option("--limit", limit, "at most this many distractors")->check(biovision_common::kNonNegative);
  app.add_option("--min-view-keypoints", recognizer_parameters.min_view_keypoints,
                 "templates with fewer keypoints are not learned (the node's learn_object rule)")
      ->check(CLI::Range(1, 1000));
  app.add_option("--json", json_path, "write the results to this file");
  options.parse(argc, argv);
  try
  {
    const std::regex name_re(R"((.+)__(\d+)\.png)");
    std::vector<View> templates, queries;
    for (const auto& f : listDirectory(objects))
    {
      std::smatch m;
      if (!std::regex_match(f, m, name_re))
        continue;
      View v{m[1], std::stoi(m[2]), load(objects + "/" + f, upscale)};
      (v.angle % step == 0 ? templates : queries).push_back(v);
    }
    std::vector<cv::Mat> distractors;
    if (!distractors_dir.empty())
      for (const auto& f : listDirectory(distractors_dir))
        if (static_cast<int>(distractors.size()) < limit)
        {
          cv::Mat img = cv::imread(distractors_dir + "/" + f, cv::IMREAD_COLOR);
          if (img.empty())
            continue;
          // Same apparent size as the object images.
          const double s = double(templates.empty() ? 128 : templates[0].image.cols) / std::max(img.cols, img.rows);
          cv::resize(img, img, cv::Size(), s * 1.5, s * 1.5, cv::INTER_AREA);
          distractors.push_back(img);
        }
    if (templates.empty() || queries.empty())
      throw std::runtime_error("no templates or no queries in " + objects);

    auto descriptor = std::make_shared<const V1Descriptor>(DescriptorModel::load(model));
    ObjectRecognizer recognizer(descriptor, recognizer_parameters);
    ObjectMemory memory(descriptor->model().bits(), descriptor->model().id());
    OrbBaseline orb(recognizer.parameters().verifier);
    int refused = 0;  // views the node's learn_object would refuse (ObjectRecognizer::learnProblem)
    for (const auto& t : templates)
    {
      ObjectView view = recognizer.describe(biovision_v1::InputImage(t.image).gray(), cv::Rect(), t.label);
      if (recognizer.learnProblem(view).empty())
        memory.addView(std::move(view));
      else
        ++refused;
      cv::Mat gray;
      cv::cvtColor(t.image, gray, cv::COLOR_BGR2GRAY);
      orb.learn(gray, t.label);
    }
    Outcome ours, base;
    ours.library_codes = memory.codeCount();
    base.library_codes = orb.codes();
    auto score = [](Outcome& o, const std::string& got, const std::string& truth) {
      if (truth.empty())
      {
        ++o.distractors;
        o.distractor_hits += !got.empty();
        return;
      }
      ++o.queries;
      if (got == truth)
        ++o.correct;
      else if (got.empty())
        ++o.silent;
      else
        ++o.wrong;
    };
    auto run = [&](const cv::Mat& image, const std::string& truth) {
      const cv::Mat gray32 = biovision_v1::InputImage(image).gray();
      auto t0 = std::chrono::steady_clock::now();
      const auto found = recognizer.recognize(gray32, {}, memory);
      ours.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      score(ours, found.empty() ? "" : found.front().label, truth);
      cv::Mat gray;
      cv::cvtColor(image, gray, cv::COLOR_BGR2GRAY);
      t0 = std::chrono::steady_clock::now();
      const std::string orb_label = orb.recognize(gray);
      base.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      score(base, orb_label, truth);
    };
    for (const auto& q : queries)
      run(q.image, q.label);
    for (const auto& d : distractors)
      run(d, "");
    nlohmann::ordered_json results;
    results["command"] = "rosrun biovision_recognition recognition_eval " + options.command();
    results["templates"] = templates.size();
    results["min_view_keypoints"] = recognizer_parameters.min_view_keypoints;
    results["templates_refused"] = refused;  // under min_view_keypoints: not learned by us (ORB learns all)
    results["queries"] = queries.size();
    results["distractors"] = distractors.size();
    results["v1"] = outcomeJson("v1", ours);
    results["orb"] = outcomeJson("orb", base);
    results["notes"] =
        "goal: >= 95% recognised with <= 2% false positives (issue #22), ahead of ORB + BFMatcher (ratio test 0.8) "
        "+ the same RANSAC verification. Split: nothing here was tuned on these images, and the descriptor models "
        "never trained on them (COIL objects and MIT1003 stimuli are not in train_descriptor's corpus); the library "
        "holds the template views, queries are the other views of the same objects.";
    if (!json_path.empty())
      biovision_common::writeJsonFile(json_path, results);
  }
  catch (const std::exception& e)
  {
    std::cerr << "recognition_eval: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
