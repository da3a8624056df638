#include "hri_datasets.hpp"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <stdexcept>

#include <opencv2/imgcodecs.hpp>

#include "biovision_hri/complex_cell_features.hpp"
#include "biovision_hri/non_maximum_suppression.hpp"
#include "biovision_v1/input_image.hpp"

namespace fs = std::filesystem;

namespace biovision_hri
{
const char* toString(Split split)
{
  switch (split)
  {
    case Split::Train:
      return "train";
    case Split::Validation:
      return "validation";
    case Split::Test:
      return "test";
  }
  return "?";
}

Split splitFromString(const std::string& name)
{
  if (name == "train")
    return Split::Train;
  if (name == "validation")
    return Split::Validation;
  if (name == "test")
    return Split::Test;
  throw std::invalid_argument("split must be train, validation or test, got '" + name + "'");
}

std::vector<std::string> listImages(const std::string& folder, const std::vector<std::string>& extensions)
{
  if (!fs::is_directory(folder))
    throw std::runtime_error("data folder missing: " + folder + " (set BIOVISION_SHARED or --data)");
  std::vector<std::string> files;
  for (const auto& entry : fs::directory_iterator(folder))
  {
    std::string ext = entry.path().extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    if (entry.is_regular_file() && std::find(extensions.begin(), extensions.end(), ext) != extensions.end())
      files.push_back(entry.path().string());
  }
  std::sort(files.begin(), files.end());
  if (files.empty())
    throw std::runtime_error("no images in " + folder);
  return files;
}

std::vector<std::string> splitPart(const std::vector<std::string>& files, Split split)
{
  const size_t n = files.size();
  const size_t a = n * 55 / 100, b = n * 70 / 100;
  const size_t first = split == Split::Train ? 0 : split == Split::Validation ? a : b;
  const size_t last = split == Split::Train ? a : split == Split::Validation ? b : n;
  return std::vector<std::string>(files.begin() + first, files.begin() + last);
}

cv::Mat readGray(const std::string& path)
{
  const cv::Mat image = cv::imread(path, cv::IMREAD_GRAYSCALE);
  if (image.empty())
    throw std::runtime_error("cannot read image " + path);
  return biovision_v1::InputImage(image).gray();
}

std::string hriDataRoot(const std::string& fallback)
{
  const char* shared = std::getenv("BIOVISION_SHARED");
  return (shared && *shared ? std::string(shared) : fallback) + "/data/hri";
}

std::vector<LabelledBox> readVocBoxes(const std::string& xml_path)
{
  std::ifstream in(xml_path);
  if (!in)
    throw std::runtime_error("cannot read " + xml_path);
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string text = ss.str();
  std::vector<LabelledBox> boxes;
  const std::regex object("<object>([\\s\\S]*?)</object>");
  auto value = [&](const std::string& block, const std::string& tag) {
    std::smatch m;
    if (!std::regex_search(block, m, std::regex("<" + tag + ">\\s*([^<]*?)\\s*</" + tag + ">")))
      throw std::runtime_error(xml_path + ": object without <" + tag + ">");
    return m[1].str();
  };
  for (auto it = std::sregex_iterator(text.begin(), text.end(), object); it != std::sregex_iterator(); ++it)
  {
    const std::string block = (*it)[1].str();
    LabelledBox b;
    b.label = value(block, "name");
    const int x0 = static_cast<int>(std::stod(value(block, "xmin"))),
              y0 = static_cast<int>(std::stod(value(block, "ymin")));
    const int x1 = static_cast<int>(std::stod(value(block, "xmax"))),
              y1 = static_cast<int>(std::stod(value(block, "ymax")));
    b.box = cv::Rect(x0, y0, x1 - x0, y1 - y0);
    boxes.push_back(b);
  }
  return boxes;
}

AveragePrecision averagePrecision(const std::vector<ScoredBox>& detections_in,
                                  const std::vector<std::vector<cv::Rect2f>>& ground_truth, double iou)
{
  AveragePrecision result;
  std::vector<ScoredBox> detections = detections_in;
  std::stable_sort(detections.begin(), detections.end(),
                   [](const ScoredBox& a, const ScoredBox& b) { return a.score > b.score; });
  std::vector<std::vector<bool>> used(ground_truth.size());
  for (size_t i = 0; i < ground_truth.size(); ++i)
  {
    used[i].assign(ground_truth[i].size(), false);
    result.ground_truth += static_cast<int>(ground_truth[i].size());
  }
  result.detections = static_cast<int>(detections.size());
  if (result.ground_truth == 0)
    return result;
  std::vector<double> precision, recall;
  int tp = 0, fp = 0;
  double best_f1 = -1;
  for (const ScoredBox& d : detections)
  {
    int best = -1;
    double best_iou = iou;
    const auto& gts = ground_truth.at(d.image);
    for (size_t g = 0; g < gts.size(); ++g)
    {
      const double o = intersectionOverUnion(d.box, gts[g]);
      if (!used[d.image][g] && o >= best_iou)
      {
        best_iou = o;
        best = static_cast<int>(g);
      }
    }
    if (best >= 0)
    {
      used[d.image][best] = true;
      ++tp;
    }
    else
      ++fp;
    precision.push_back(static_cast<double>(tp) / (tp + fp));
    recall.push_back(static_cast<double>(tp) / result.ground_truth);
    const double f1 = 2 * precision.back() * recall.back() / (precision.back() + recall.back() + 1e-12);
    if (f1 > best_f1)
    {
      best_f1 = f1;
      result.precision_at_best_f1 = precision.back();
      result.recall_at_best_f1 = recall.back();
    }
  }
  result.max_recall = recall.empty() ? 0.0 : recall.back();
  // All-points interpolation: precision made monotone from the right, summed over recall steps.
  for (int i = static_cast<int>(precision.size()) - 2; i >= 0; --i)
    precision[i] = std::max(precision[i], precision[i + 1]);
  double previous_recall = 0.0;
  for (size_t i = 0; i < precision.size(); ++i)
  {
    result.ap += (recall[i] - previous_recall) * precision[i];
    previous_recall = recall[i];
  }
  return result;
}

double missRateAtFppw(std::vector<float> positive_scores, std::vector<float> negative_scores, double fppw,
                      double* threshold)
{
  if (positive_scores.empty() || negative_scores.empty())
    throw std::invalid_argument("missRateAtFppw: empty score list");
  std::sort(negative_scores.begin(), negative_scores.end(), std::greater<float>());
  const size_t allowed = static_cast<size_t>(fppw * negative_scores.size());
  const float t = allowed >= negative_scores.size() ? negative_scores.back() - 1.f : negative_scores[allowed];
  if (threshold)
    *threshold = t;
  const size_t missed = std::count_if(positive_scores.begin(), positive_scores.end(), [&](float s) { return s <= t; });
  return static_cast<double>(missed) / positive_scores.size();
}

std::vector<std::string> positiveCrops(const std::string& root, const std::string& kind)
{
  if (kind == "face")
    return listImages(root + "/faces/caltech-webfaces-36x36/Caltech_CropFaces", {".jpg", ".png"});
  if (kind == "hand")
    return listImages(root + "/hands/oxford-crops-60x60/pos", {".png", ".jpg"});
  throw std::invalid_argument("kind must be face or hand, got '" + kind + "'");
}

std::vector<std::string> negativeCrops(const std::string& root, const std::string& kind)
{
  if (kind == "hand")
    return listImages(root + "/hands/oxford-crops-60x60/neg", {".png", ".jpg"});
  return {};
}

std::vector<std::string> sceneFiles(const std::string& root)
{
  return listImages(root + "/negatives/scenes", {".jpg", ".png"});
}

std::vector<cv::Mat> randomScenePatches(const std::vector<cv::Mat>& scenes, int count, cv::RNG& rng, int min_side,
                                        int max_side)
{
  std::vector<const cv::Mat*> usable;
  for (const cv::Mat& s : scenes)
    if (std::min(s.cols, s.rows) >= min_side)
      usable.push_back(&s);
  if (usable.empty())
    throw std::runtime_error("no scene is at least " + std::to_string(min_side) + " px on its smaller side");
  std::vector<cv::Mat> patches;
  patches.reserve(count);
  for (int i = 0; i < count; ++i)
  {
    const cv::Mat& s = *usable[rng.uniform(0, static_cast<int>(usable.size()))];
    const int top = std::min({s.cols, s.rows, max_side});
    const int side = rng.uniform(min_side, top + 1);
    const int x = rng.uniform(0, s.cols - side + 1), y = rng.uniform(0, s.rows - side + 1);
    patches.push_back(s(cv::Rect(x, y, side, side)));
  }
  return patches;
}

cv::Mat patchFeatureRows(const FeatureLayout& layout, const std::vector<cv::Mat>& patches, bool mirror)
{
  const int copies = mirror ? 2 : 1;
  cv::Mat rows(static_cast<int>(patches.size()) * copies, layout.featureCount(), CV_32F);
  cv::parallel_for_(cv::Range(0, static_cast<int>(patches.size())), [&](const cv::Range& range) {
    ComplexCellFeatures features(layout);  // one per worker: the Gabor bank caches spectra
    for (int i = range.start; i < range.end; ++i)
    {
      features.patchFeatures(patches[i]).copyTo(rows.row(i * copies));
      if (mirror)
      {
        cv::Mat flipped;
        cv::flip(patches[i], flipped, 1);
        features.patchFeatures(flipped).copyTo(rows.row(i * copies + 1));
      }
    }
  });
  return rows;
}

std::vector<GestureSample> lintoSamples(const std::string& root)
{
  std::vector<GestureSample> samples;
  const std::regex name(R"(([a-z]+)\.[0-9a-f]{8}-[0-9a-f]{4}-([0-9a-f]{4})-.*\.jpg)");
  for (const auto& jpg : listImages(root + "/gestures/linto-train", {".jpg"}))
  {
    std::smatch m;
    const std::string file = fs::path(jpg).filename().string();
    if (!std::regex_match(file, m, name))
      continue;
    const auto boxes = readVocBoxes(fs::path(jpg).replace_extension(".xml").string());
    if (boxes.empty())
      continue;
    GestureSample g;
    g.file = jpg;
    g.label = m[1];
    g.box = boxes.front().box;
    g.group = m[2];
    g.template_part = g.group == "11eb";
    samples.push_back(g);
  }
  if (samples.empty())
    throw std::runtime_error("no LinTO frames in " + root + "/gestures/linto-train");
  return samples;
}

std::vector<GestureSample> trieschSamples(const std::string& root)
{
  const std::string base = root + "/gestures/triesch-postures/handGesture_project/handGesture_project/train";
  if (!fs::is_directory(base))
    throw std::runtime_error("data folder missing: " + base);
  std::vector<GestureSample> samples;
  std::vector<std::string> people;
  for (const auto& dir : fs::directory_iterator(base))
  {
    if (!dir.is_directory())
      continue;
    const std::string label = dir.path().filename().string();
    for (const auto& f : listImages(dir.path().string(), {".bmp"}))
    {
      GestureSample g;
      g.file = f;
      g.label = label;
      const std::string stem = fs::path(f).stem().string();
      g.group = stem.substr(0, stem.size() > 2 ? stem.size() - 2 : 0);  // "<person><posture>1"
      samples.push_back(g);
      people.push_back(g.group);
    }
  }
  std::sort(people.begin(), people.end());
  people.erase(std::unique(people.begin(), people.end()), people.end());
  for (auto& g : samples)
    g.template_part = std::lower_bound(people.begin(), people.end(), g.group) - people.begin() <
                      static_cast<long>(people.size() / 2);
  std::sort(samples.begin(), samples.end(),
            [](const GestureSample& a, const GestureSample& b) { return a.file < b.file; });
  return samples;
}
}  // namespace biovision_hri
