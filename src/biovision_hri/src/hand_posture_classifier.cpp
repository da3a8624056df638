#include "biovision_hri/hand_posture_classifier.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

#include "biovision_common/payload_reader.hpp"
#include "biovision_common/payload_writer.hpp"
#include "biovision_common/stored_file.hpp"
#include "biovision_hri/linear_svm_trainer.hpp"

namespace biovision_hri
{
namespace
{
const char* const kMagic = "BVHRIPOS";
constexpr uint32_t kVersion = 1;
constexpr size_t kMaxLabels = 256;       // classes in a model
constexpr size_t kMaxLabelLength = 256;  // characters of a label (and of the rejection label)
constexpr size_t kMaxProvenance = 1u << 16;
// A region whose square is this many times the image's larger side is no hand region (its patch would
// hold the whole image in less than a pixel).
constexpr double kMaxRegionToImage = 8.0;
// A region whose larger side is below this [px] holds no posture: blown up to the 42 px window it is
// interpolation alone (a helper's 1x1 box on noise read as a gesture). The node's hands are >= 42 px.
constexpr int kMinRegionSide = 8;

bool usableRegion(const cv::Mat& gray, const cv::Rect& box)
{
  const double side = std::max(double(box.width), double(box.height));
  return box.width > 0 && box.height > 0 && side >= kMinRegionSide &&
         (box & cv::Rect(0, 0, gray.cols, gray.rows)).area() > 0 &&
         side <= kMaxRegionToImage * std::max(gray.cols, gray.rows);
}

void checkLabel(const std::string& label, const char* what)
{
  if (label.empty() || label.size() > kMaxLabelLength)
    throw std::invalid_argument(std::string("HandPostureClassifier: ") + what + " must have 1-" +
                                std::to_string(kMaxLabelLength) + " characters, got " + std::to_string(label.size()));
}

bool allFinite(const cv::Mat& m)
{
  return cv::checkRange(m);
}

void check(bool ok, const std::string& message)
{
  if (!ok)
    throw std::invalid_argument("HandPostureClassifier::Parameters: " + message);
}

void checkImage(const cv::Mat& gray, const char* what)
{
  if (gray.empty() || gray.type() != CV_32FC1)
    throw std::invalid_argument(std::string("HandPostureClassifier::") + what +
                                ": expected a non-empty CV_32FC1 image");
}
}  // namespace

void HandPostureClassifier::Parameters::validate() const
{
  check(std::isfinite(C) && C >= 1e-6 && C <= 1e6, "C must be in [1e-6, 1e6], got " + std::to_string(C));
  check(!rejection_label.empty() && rejection_label.size() <= kMaxLabelLength,
        "rejection_label must have 1-" + std::to_string(kMaxLabelLength) + " characters");
  check(std::isfinite(rotation) && rotation >= 0 && rotation <= 45,
        "rotation must be in [0, 45] deg, got " + std::to_string(rotation));
  check(std::isfinite(margin) && margin >= 0 && margin <= 1, "margin must be in [0, 1], got " + std::to_string(margin));
  check(std::isfinite(min_score) && min_score >= -10 && min_score <= 10,
        "min_score must be in [-10, 10], got " + std::to_string(min_score));
}

HandPostureClassifier::HandPostureClassifier(const FeatureLayout& layout, const Parameters& parameters)
  : features_(layout), parameters_(parameters)
{
  parameters_.validate();
}

void HandPostureClassifier::setParameters(const Parameters& parameters)
{
  parameters.validate();
  parameters_ = parameters;
}

cv::Mat HandPostureClassifier::regionPatch(const cv::Mat& gray, const cv::Rect& box, double degrees) const
{
  const int out = layout().windowSide(layout().cell_size);
  const double side = std::max(box.width, box.height) * (1.0 + 2.0 * parameters_.margin);
  const cv::Point2f centre(box.x + 0.5f * box.width, box.y + 0.5f * box.height);
  // One warp crops, rotates about the box centre and scales the square to the window (area-like
  // averaging comes from INTER_AREA only in resize, so shrink large regions first).
  cv::Mat source = gray;
  double scale = out / side;
  cv::Point2f c = centre;
  if (scale < 0.5)
  {
    const double f = 2.0 * scale;  // leave the last factor 2 to the warp
    cv::resize(gray, source, cv::Size(), f, f, cv::INTER_AREA);
    c = cv::Point2f(static_cast<float>(centre.x * f), static_cast<float>(centre.y * f));
    scale = 0.5;
  }
  cv::Mat m = cv::getRotationMatrix2D(c, degrees, scale);
  m.at<double>(0, 2) += out / 2.0 - c.x;
  m.at<double>(1, 2) += out / 2.0 - c.y;
  cv::Mat patch;
  cv::warpAffine(source, patch, m, cv::Size(out, out), cv::INTER_LINEAR, cv::BORDER_REPLICATE);
  return patch;
}

void HandPostureClassifier::addExample(const cv::Mat& gray, const cv::Rect& box, const std::string& label)
{
  checkImage(gray, "addExample");
  checkLabel(label, "a label");
  if (!usableRegion(gray, box))
    throw std::invalid_argument(
        "HandPostureClassifier::addExample: the box is empty, outside the image or more "
        "than 8 times its size");
  std::vector<double> angles{0.0};
  if (parameters_.rotation > 0)
    angles = {-parameters_.rotation, 0.0, parameters_.rotation};
  std::vector<cv::Mat> rows;
  for (double a : angles)
  {
    const cv::Mat patch = regionPatch(gray, box, a);
    rows.push_back(features_.patchFeatures(patch).clone());
    if (parameters_.mirror)
    {
      cv::Mat mirrored;
      cv::flip(patch, mirrored, 1);
      rows.push_back(features_.patchFeatures(mirrored).clone());
    }
  }
  // One NaN would make every SVM weight NaN: refuse the example, keep the others.
  for (const cv::Mat& r : rows)
    if (!allFinite(r))
      throw std::invalid_argument("HandPostureClassifier::addExample: the region has non-finite pixels");
  for (cv::Mat& r : rows)
  {
    examples_.push_back(r);
    example_labels_.push_back(label);
  }
}

void HandPostureClassifier::train()
{
  std::vector<std::string> labels = example_labels_;
  std::sort(labels.begin(), labels.end());
  labels.erase(std::unique(labels.begin(), labels.end()), labels.end());
  const bool has_gesture = std::any_of(labels.begin(), labels.end(),
                                       [&](const std::string& l) { return l != parameters_.rejection_label; });
  if (labels.size() < 2 || !has_gesture || labels.size() > kMaxLabels)
    throw std::logic_error("HandPostureClassifier::train: needs examples of 2-" + std::to_string(kMaxLabels) +
                           " labels, one of them a gesture; got " + std::to_string(labels.size()));
  cv::Mat samples;
  cv::vconcat(examples_, samples);
  LinearSvmTrainer::Parameters p;
  p.C = parameters_.C;
  cv::Mat weights(static_cast<int>(labels.size()), samples.cols, CV_32F);
  std::vector<float> biases;
  for (size_t k = 0; k < labels.size(); ++k)
  {
    std::vector<int> y(example_labels_.size());
    for (size_t i = 0; i < y.size(); ++i)
      y[i] = example_labels_[i] == labels[k] ? 1 : -1;
    const auto r = LinearSvmTrainer::train(samples, y, p);
    if (!std::all_of(r.weights.begin(), r.weights.end(), [](float v) { return std::isfinite(v); }) ||
        !std::isfinite(r.bias))
      throw std::logic_error("HandPostureClassifier::train: LIBLINEAR gave non-finite weights for '" + labels[k] + "'");
    std::copy(r.weights.begin(), r.weights.end(), weights.ptr<float>(static_cast<int>(k)));
    biases.push_back(r.bias);
  }
  labels_ = std::move(labels);
  weights_ = weights;
  biases_ = std::move(biases);
}

std::vector<GestureResult> HandPostureClassifier::classify(const cv::Mat& gray, const std::vector<cv::Rect>& hand_boxes)
{
  if (!trained())
    throw std::logic_error("HandPostureClassifier::classify: not trained or loaded");
  checkImage(gray, "classify");
  std::vector<GestureResult> results;
  for (const cv::Rect& box : hand_boxes)
  {
    GestureResult r;
    r.box = box;
    if (usableRegion(gray, box))
    {
      const cv::Mat f = features_.patchFeatures(regionPatch(gray, box, 0.0));
      // A textureless region has all-zero features, so the biases alone would pick a class; non-finite
      // pixels give non-finite features. Neither is a gesture.
      if (!allFinite(f) || cv::norm(f, cv::NORM_L2) < kMinFeatureNorm)
      {
        results.push_back(r);
        continue;
      }
      float best = -std::numeric_limits<float>::infinity();
      for (int k = 0; k < weights_.rows; ++k)
      {
        const float s = static_cast<float>(f.dot(weights_.row(k))) + biases_[k];
        if (s > best)
        {
          best = s;
          r.best_label = labels_[k];
        }
      }
      // Weights that load (finite) may still overflow a score (a crafted file of 1e38s): no gesture then.
      if (!std::isfinite(best))
      {
        r.best_label.clear();
        results.push_back(r);
        continue;
      }
      r.score = best;
      if (r.best_label != parameters_.rejection_label && best >= parameters_.min_score)
        r.label = r.best_label;
    }
    results.push_back(r);
  }
  return results;
}

void HandPostureClassifier::save(const std::string& path, const std::string& provenance) const
{
  if (!trained())
    throw std::logic_error("HandPostureClassifier::save: not trained");
  // What load() would refuse is not written.
  for (const auto& l : labels_)
    checkLabel(l, "a label");
  checkLabel(parameters_.rejection_label, "the rejection label");
  if (provenance.size() > kMaxProvenance)
    throw std::invalid_argument("HandPostureClassifier::save: provenance longer than " +
                                std::to_string(kMaxProvenance) + " characters");
  biovision_common::PayloadWriter w;
  layout().write(w);
  w.putString(parameters_.rejection_label);
  w.put<uint64_t>(labels_.size());
  for (int k = 0; k < weights_.rows; ++k)
  {
    w.putString(labels_[k]);
    w.putArray(weights_.ptr<float>(k), static_cast<size_t>(weights_.cols));
    w.put<float>(biases_[k]);
  }
  w.putString(provenance);
  biovision_common::StoredFile::write(path, kMagic, kVersion, w.bytes());
}

void HandPostureClassifier::load(const std::string& path)
{
  struct Stored
  {
    FeatureLayout layout;
    std::string rejection_label;
    std::vector<std::string> labels;
    cv::Mat weights;
    std::vector<float> biases;
  };
  const Stored s = biovision_common::StoredFile::load<Stored>(
      path, kMagic, kVersion, "hand posture model", [](biovision_common::PayloadReader& r) {
        Stored m;
        m.layout = FeatureLayout::read(r);
        m.rejection_label = r.getString(kMaxLabelLength);
        const auto count = r.get<uint64_t>();
        if (count < 2 || count > kMaxLabels)
          throw std::runtime_error(std::to_string(count) + " classes (2-" + std::to_string(kMaxLabels) + ")");
        m.weights.create(static_cast<int>(count), m.layout.featureCount(), CV_32F);
        for (uint64_t k = 0; k < count; ++k)
        {
          m.labels.push_back(r.getString(kMaxLabelLength));
          if (std::count(m.labels.begin(), m.labels.end(), m.labels.back()) > 1)
            throw std::runtime_error("class '" + m.labels.back() + "' twice");
          const auto w = r.getArray<float>(1u << 20);
          const float b = r.get<float>();
          if (m.labels.back().empty() || static_cast<int>(w.size()) != m.layout.featureCount())
            throw std::runtime_error("class " + std::to_string(k) + ": empty label or " + std::to_string(w.size()) +
                                     " weights for " + std::to_string(m.layout.featureCount()) + " features");
          if (!std::all_of(w.begin(), w.end(), [](float v) { return std::isfinite(v); }) || !std::isfinite(b))
            throw std::runtime_error("class " + std::to_string(k) + ": a weight is not finite");
          std::copy(w.begin(), w.end(), m.weights.ptr<float>(static_cast<int>(k)));
          m.biases.push_back(b);
        }
        r.getString(kMaxProvenance);  // provenance: for people reading the file
        return m;
      });
  features_ = ComplexCellFeatures(s.layout);
  parameters_.rejection_label = s.rejection_label;
  labels_ = s.labels;
  weights_ = s.weights;
  biases_ = s.biases;
  examples_.clear();
  example_labels_.clear();
}
}  // namespace biovision_hri
