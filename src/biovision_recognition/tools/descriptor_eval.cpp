// Matching performance of the V1 descriptor against OpenCV's ORB, BRISK, AKAZE and SIFT on the same V1
// keypoints of real image pairs with exact correspondence (test part: disjoint from training).

#include <algorithm>
#include <chrono>
#include <cstring>
#include <iomanip>
#include <iostream>
#include <filesystem>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>

#include "biovision_recognition/affine_shape_adaptation.hpp"
#include "biovision_recognition/v1_descriptor.hpp"
#include "correspondence_data.hpp"
#include "biovision_common/eval/roc_metrics.hpp"
#include "biovision_common/tool_options.hpp"

using biovision_common::fpr95;
using biovision_common::fpr95AtThreshold;
using biovision_common::rocArea;
using biovision_common::shareWithin;

using namespace biovision_recognition;

namespace
{
/// The OpenCV descriptors createPeer() makes; all of them run unless --peers says otherwise.
const std::vector<std::string> kPeers{"orb", "brisk", "akaze", "sift"};

struct Options
{
  std::vector<std::string> models;  // each is a method named by its file stem
  std::string stereo, sequence, json_path, part = "test";
  std::vector<int> targets{4, 5, 6};  // 2, 3 are the training part
  PairSampler::Parameters sampling;   // --levels, --pairs
  std::vector<std::string> peers = kPeers;
  std::vector<std::string> shaped_peers;      // default: none
  std::vector<std::string> homography_pairs;  // "A:B:H" triples
  std::vector<std::string> tilt_images;
  std::vector<double> tilts{20, 30, 40, 50, 60, 70};
  std::vector<std::string> images;  // collections: synthetic pairs of their held-out sources
  int per_source = 1;
  std::vector<int> radii;  // Hamming radii to report recall and false-positive rate at (default: none)
  std::string command;     // the options as given, for the results
};

Options parseOptions(int argc, char** argv)
{
  Options o;
  // 500 left the pooled fpr95 to a few hundred pairs of the hardest viewpoint change, and it moved by 0.03
  // between models.
  o.sampling.max_pairs = 2000;
  biovision_common::ToolOptions options(
      "descriptor_eval",
      "Matching performance of the V1 descriptor against OpenCV's ORB, BRISK, AKAZE and SIFT on the same V1 keypoints\n"
      "of real image pairs with exact correspondence (test part: disjoint from training). Every method describes the\n"
      "same keypoints, upright, with the same support (the first model's patch, 8 keypoint wavelengths for the\n"
      "committed ones). Prints a table; --json writes the results.");
  CLI::App& app = options.app();
  app.add_option("--models", o.models, "trained descriptor models, comma-separated")
      ->required()
      ->delimiter(',')
      ->check(CLI::ExistingFile);
  app.add_option("--stereo", o.stereo, "folder of Middlebury scenes");
  app.add_option("--part", o.part,
                 "part of the stereo scenes: test/train alternate in name order (models up to session 4); heldout/dev: "
                 "the split by source (descriptorSplit); fit/validation: the dev part split again (choose a variant "
                 "trained on fit on validation). --images take the same part of the split by source (heldout for "
                 "test/train/all)")
      ->check(CLI::IsMember({"test", "train", "all", "heldout", "dev", "fit", "validation"}));
  app.add_option("--homography-pairs", o.homography_pairs,
                 "real image pairs with a known homography, A:B:H comma-separated (H: OpenCV .xml or 9 numbers), e.g. "
                 "opencv-doc's graf1.png:graf3.png:H1to3p.xml")
      ->delimiter(',');
  app.add_option("--tilt-images", o.tilt_images,
                 "images turned synthetically by each of --tilts about their vertical axis (evaluation material, e.g. "
                 "opencv-doc's samples), comma-separated")
      ->delimiter(',')
      ->check(CLI::ExistingFile);
  app.add_option("--images", o.images,
                 "image collections, comma-separated: one synthetic view (tilt <= 4, photometric change) of up to "
                 "--per-source images of each source in the --part of the split by source (heldout unless "
                 "dev/fit/validation)")
      ->delimiter(',')
      ->check(CLI::ExistingDirectory);
  app.add_option("--per-source", o.per_source, "--images: images per held-out source")
      ->check(biovision_common::kPositive);
  app.add_option("--tilts", o.tilts, "viewpoint changes of --tilt-images [degrees]")
      ->delimiter(',')
      ->check(CLI::Range(0.0, 85.0));
  app.add_option("--sequence", o.sequence, "HPatches (1.ppm, H_1_k) or Oxford (img1.png, H1to2p) sequence");
  app.add_option("--targets", o.targets, "sequence images paired with image 1")
      ->delimiter(',')
      ->check(biovision_common::kPositive);
  app.add_option("--levels", o.sampling.levels, "keypoint pyramid levels")
      ->delimiter(',')
      ->check(biovision_common::kNonNegative);
  app.add_option("--pairs", o.sampling.max_pairs, "pairs of each kind per image pair")
      ->check(biovision_common::kPositive);
  app.add_option("--peers", o.peers, "OpenCV peers, comma-separated")->delimiter(',')->check(CLI::IsMember(kPeers));
  app.add_option("--shaped-peers", o.shaped_peers,
                 "peers also run on patches normalised by our affine shape adaptation (method name + \"+shape\"): is "
                 "the gain the adaptation's or the descriptor's? (default: none)")
      ->delimiter(',')
      ->check(CLI::IsMember(kPeers));
  app.add_option("--radii", o.radii,
                 "also report each binary method's recall and false-positive rate within these Hamming distances "
                 "[bits], comma-separated: the radius a matcher needs with a model (recognition's max_distance); "
                 "compare only codes of one length (ours 128 bits, ORB 256, AKAZE 486, BRISK 512) (default: none)")
      ->delimiter(',')
      ->check(biovision_common::kNonNegative);
  app.add_option("--json", o.json_path, "write the results to this file");
  app.callback([&] {
    if (o.stereo.empty() && o.sequence.empty() && o.homography_pairs.empty() && o.tilt_images.empty() &&
        o.images.empty())
      throw CLI::RequiredError("--stereo, --sequence, --homography-pairs, --tilt-images or --images");
  });
  options.parse(argc, argv);
  o.command = options.command();
  return o;
}

struct Scores
{
  std::vector<float> positive, negative;
  double seconds = 0.0;
  size_t keypoints = 0;
  bool binary = true;
};

/// Per keypoint, its descriptor row (or -1 when the method dropped it).
struct Described
{
  cv::Mat descriptors;
  std::vector<int> row;
};

cv::KeyPoint toCv(const biovision_v1::Keypoint& kp, const std::string& method, int index, float patch_wavelengths)
{
  const float support = patch_wavelengths * kp.wavelength;  // the V1 descriptor's patch side
  cv::KeyPoint k(cv::Point2f(kp.x, kp.y), support, 0.f, kp.strength, 0, index);
  if (method == "orb")
    k.octave = std::clamp(static_cast<int>(std::lround(std::log(support / 31.f) / std::log(1.2f))), 0, 7);
  else if (method == "sift")
    k.size = support / 6.f;  // SIFT's window is ~6 x size wide
  else if (method == "akaze")
  {
    // MLDB's window is ~10 x size wide; class_id must be the scale-space level (sigma = 1.6 * 2^(i/4)).
    // Levels beyond the image's scale space are left to describePeer to drop (akazeLevels).
    const double sigma = support / 10.0 / 1.5;
    const int i = std::max(0, static_cast<int>(std::lround(4 * std::log2(sigma / 1.6))));
    k.class_id = i;
    k.octave = i / 4;
    k.size = static_cast<float>(1.6 * std::pow(2.0, i / 4.0) * 1.5);
  }
  return k;
}

/// Scale-space levels AKAZE builds for an image of `size` (OpenCV 4.6, AKAZE::create's defaults: up to 4
/// octaves of 4 sublevels; octave o > 0 only while the image, halved o times, stays >= 80 x 40 px). A
/// keypoint whose level (class_id) is beyond them fails an assertion in compute(): a model with a larger
/// patch than the committed ones' (e.g. --patch 12) gave such supports on 400 x 300 images.
int akazeLevels(const cv::Size& size)
{
  int octaves = 1;
  while (octaves < 4 && (size.width >> octaves) >= 80 && (size.height >> octaves) >= 40)
    ++octaves;
  return 4 * octaves;
}

cv::Ptr<cv::Feature2D> createPeer(const std::string& method)
{
  cv::Ptr<cv::Feature2D> f;
  if (method == "orb")
    f = cv::ORB::create();
  else if (method == "brisk")
    f = cv::BRISK::create();
  else if (method == "akaze")
    f = cv::AKAZE::create(cv::AKAZE::DESCRIPTOR_MLDB_UPRIGHT);
  else if (method == "sift")
    f = cv::SIFT::create();
  else
    throw std::runtime_error("unknown peer " + method);
  return f;
}

Described describePeer(const std::string& method, const cv::Mat& image, const std::vector<biovision_v1::Keypoint>& kps,
                       float patch_wavelengths, double& seconds)
{
  const cv::Ptr<cv::Feature2D> f = createPeer(method);
  cv::Mat gray;
  cv::cvtColor(image, gray, cv::COLOR_BGR2GRAY);
  // AKAZE: keypoints beyond the image's scale space are dropped, as the other peers drop those at the border
  // (their pairs then count for no method).
  const int levels = method == "akaze" ? akazeLevels(gray.size()) : 0;
  std::vector<cv::KeyPoint> cv_kps;
  std::vector<int> kept;  // per AKAZE keypoint, its index in kps
  for (size_t i = 0; i < kps.size(); ++i)
  {
    const cv::KeyPoint k = toCv(kps[i], method, static_cast<int>(i), patch_wavelengths);
    if (method == "akaze" && k.class_id >= levels)
      continue;
    cv_kps.push_back(k);
    kept.push_back(static_cast<int>(i));
  }
  Described d;
  const auto t0 = std::chrono::steady_clock::now();
  f->compute(gray, cv_kps, d.descriptors);
  seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  d.row.assign(kps.size(), -1);
  if (method == "akaze")
  {
    // AKAZE keeps every keypoint in order (class_id holds its level, not our index).
    if (cv_kps.size() != kept.size())
      throw std::runtime_error("AKAZE dropped keypoints");
    for (size_t r = 0; r < kept.size(); ++r)
      d.row[kept[r]] = static_cast<int>(r);
  }
  else
    for (size_t r = 0; r < cv_kps.size(); ++r)
      d.row[cv_kps[r].class_id] = static_cast<int>(r);
  return d;
}

/// The peer on each keypoint's own patch, resampled so that its affine shape S becomes a circle
/// (patch(q) = image(c + S q)): the peer then sees what our pooling grid sees. Slow (one image per
/// keypoint); its time is not comparable.
Described describeShapedPeer(const std::string& method, const cv::Mat& image,
                             const std::vector<biovision_v1::Keypoint>& kps, const std::vector<cv::Matx22f>& shapes,
                             float patch_wavelengths, double& seconds)
{
  const cv::Ptr<cv::Feature2D> f = createPeer(method);
  cv::Mat gray;
  cv::cvtColor(image, gray, cv::COLOR_BGR2GRAY);
  Described d;
  d.row.assign(kps.size(), -1);
  std::vector<cv::Mat> rows;
  const auto t0 = std::chrono::steady_clock::now();
  for (size_t i = 0; i < kps.size(); ++i)
  {
    const float support = patch_wavelengths * kps[i].wavelength;
    // 4 supports: the peers' borders fit, and AKAZE keeps the octave of the keypoint (>= 80 px wide).
    const int side = 2 * static_cast<int>(std::ceil(2.f * support)) + 1;
    const float half = (side - 1) / 2.f;
    const cv::Matx22f& s = shapes[i];
    const cv::Matx23f to_image(s(0, 0), s(0, 1), kps[i].x - s(0, 0) * half - s(0, 1) * half, s(1, 0), s(1, 1),
                               kps[i].y - s(1, 0) * half - s(1, 1) * half);
    cv::Mat patch;
    cv::warpAffine(gray, patch, cv::Mat(to_image), cv::Size(side, side), cv::INTER_LINEAR | cv::WARP_INVERSE_MAP,
                   cv::BORDER_REFLECT);
    biovision_v1::Keypoint centred = kps[i];
    centred.x = centred.y = half;
    std::vector<cv::KeyPoint> one{toCv(centred, method, 0, patch_wavelengths)};
    if (method == "akaze" && one.front().class_id >= akazeLevels(patch.size()))
      continue;
    cv::Mat descriptor;
    f->compute(patch, one, descriptor);
    if (one.size() == 1 && descriptor.rows == 1)
    {
      d.row[i] = static_cast<int>(rows.size());
      rows.push_back(descriptor);
    }
  }
  seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!rows.empty())
    cv::vconcat(rows, d.descriptors);
  return d;
}

float distance(const Described& a, int ia, const Described& b, int ib)
{
  const cv::Mat ra = a.descriptors.row(a.row[ia]), rb = b.descriptors.row(b.row[ib]);
  return static_cast<float>(cv::norm(ra, rb, ra.type() == CV_8U ? cv::NORM_HAMMING : cv::NORM_L2));
}

using Models = std::vector<std::pair<std::string, std::unique_ptr<V1Descriptor>>>;  // (file stem, descriptor)

Models loadModels(const std::vector<std::string>& paths)
{
  Models ours;
  for (const auto& path : paths)
  {
    std::string stem = path.substr(path.find_last_of('/') + 1);
    stem = stem.substr(0, stem.find('.'));
    ours.emplace_back(stem, std::make_unique<V1Descriptor>(DescriptorModel::load(path)));
  }
  return ours;
}

struct Evaluation
{
  std::map<std::string, Scores> scores;                               // method -> every pair's distances
  std::map<std::string, std::map<std::string, double>> per_pair_fpr;  // image pair -> method -> fpr95
  std::map<std::string, SyntheticViewChange> view_changes;            // synthetic image pair -> its change
  std::map<std::string, std::map<std::string, Scores>> by_condition;  // condition -> method -> pooled distances
  std::map<std::string, int> condition_pairs;                         // condition -> image pairs
};

/// The conditions a synthetic pair is pooled under, so that the report says where a method wins or loses:
/// its foreshortening band and whether view B was blurred (the order of the report).
const std::vector<std::string> kConditions{"tilt < 1.5", "tilt 1.5-2.5", "tilt >= 2.5", "sharp", "blurred"};
std::vector<std::string> conditionsOf(const SyntheticViewChange& c)
{
  return {c.tilt < 1.5   ? kConditions[0]
          : c.tilt < 2.5 ? kConditions[1]
                         : kConditions[2],
          c.blur_sigma > 0 ? kConditions[4] : kConditions[3]};
}

/// Every method on the same sampled keypoints of every image pair; only pairs every method described count.
Evaluation evaluate(const Options& o, const Models& ours)
{
  PairSampler sampler(o.sampling);
  auto pairs = loadCorrespondencePairs(o.stereo, o.part, o.sequence, o.targets);
  for (const auto& triple : o.homography_pairs)
  {
    const auto a = triple.find(':'), b = triple.find(':', a == std::string::npos ? a : a + 1);
    if (a == std::string::npos || b == std::string::npos)
      throw std::runtime_error("--homography-pairs: '" + triple + "' is not A:B:H");
    pairs.push_back(loadHomographyPair(triple.substr(0, a), triple.substr(a + 1, b - a - 1), triple.substr(b + 1)));
  }
  if (!o.images.empty())
  {
    std::mt19937 rng(101);
    const std::string part = collectionPart(o.part, "heldout");
    for (const auto& image : listSourceImages(o.images, o.per_source, part))
    {
      const cv::Mat bgr = cv::imread(image.path, cv::IMREAD_COLOR);
      // AKAZE builds an octave only while it stays >= 80 x 40 px; the keypoints' scales need 3 of them.
      if (bgr.empty() || bgr.cols < 400 || bgr.rows < 300)
        continue;
      pairs.push_back(
          syntheticPair(bgr, part + "/" + image.source + "/" + std::filesystem::path(image.path).filename().string(),
                        4.0, true, rng));
    }
  }
  for (const auto& path : o.tilt_images)
  {
    const cv::Mat image = cv::imread(path, cv::IMREAD_COLOR);
    if (image.empty())
      throw std::runtime_error(path + ": cannot read");
    const std::string stem = path.substr(path.find_last_of('/') + 1);
    for (double degrees : o.tilts)
    {
      std::ostringstream name;
      name << "tilt/" << stem.substr(0, stem.find('.')) << "/" << degrees;
      pairs.push_back(tiltPair(image, name.str(), degrees));
    }
  }
  Evaluation evaluation;
  auto& scores = evaluation.scores;
  auto& per_pair_fpr = evaluation.per_pair_fpr;
  // Peers get the first model's support (patch side in keypoint wavelengths).
  const float support = static_cast<float>(ours.front().second->model().layout.patch_wavelengths);
  V1FeaturePyramid::Parameters pyramid_parameters = ours.front().second->pyramidParameters();
  for (const auto& [stem, descriptor] : ours)
    pyramid_parameters.pooling_phases = std::max(pyramid_parameters.pooling_phases, descriptor->model().layout.phases);
  V1FeaturePyramid pa(pyramid_parameters), pb(pyramid_parameters);
  for (const auto& pair : pairs)
  {
    const cv::Mat ga = biovision_v1::InputImage(pair.a).gray(), gb = biovision_v1::InputImage(pair.b).gray();
    pa.build(ga);
    pb.build(gb);
    const auto p = samplePairs(sampler, pair, pa, pb);
    const size_t n = p.positive_a.size();
    // Image B's keypoints: positives then negatives.
    std::vector<biovision_v1::Keypoint> kb = p.positive_b;
    kb.insert(kb.end(), p.negative_b.begin(), p.negative_b.end());

    std::map<std::string, std::pair<Described, Described>> described;
    std::map<std::string, double> seconds;
    for (const auto& [name, descriptor] : ours)
    {
      auto run = [&](const cv::Mat& gray, V1FeaturePyramid& pyr, const std::vector<biovision_v1::Keypoint>& kps) {
        const auto t0 = std::chrono::steady_clock::now();
        pyr.build(gray);  // timed: building the cells is part of describing
        const BinaryCodeSet codes = descriptor->compute(pyr, kps);
        seconds[name] += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        Described d;
        d.descriptors = cv::Mat(static_cast<int>(codes.size()), codes.words() * 8, CV_8U);
        std::memcpy(d.descriptors.data, codes.data(), codes.size() * codes.words() * 8);
        d.row.resize(kps.size());
        for (size_t i = 0; i < kps.size(); ++i)
          d.row[i] = static_cast<int>(i);
        return d;
      };
      described[name] = {run(ga, pa, p.positive_a), run(gb, pb, kb)};
    }
    for (const auto& m : o.peers)
      described[m] = {describePeer(m, pair.a, p.positive_a, support, seconds[m]),
                      describePeer(m, pair.b, kb, support, seconds[m])};
    if (!o.shaped_peers.empty())
    {
      const AffineShapeAdaptation adaptation(ours.front().second->model().layout.shape);
      auto shapesOf = [&](const V1FeaturePyramid& pyr, const std::vector<biovision_v1::Keypoint>& kps) {
        std::vector<cv::Matx22f> shapes;
        for (const auto& k : kps)
          shapes.push_back(adaptation.estimate(pyr, k));
        return shapes;
      };
      const auto shapes_a = shapesOf(pa, p.positive_a), shapes_b = shapesOf(pb, kb);
      for (const auto& m : o.shaped_peers)
        described[m + "+shape"] = {describeShapedPeer(m, pair.a, p.positive_a, shapes_a, support,
                                                      seconds[m + "+shape"]),
                                   describeShapedPeer(m, pair.b, kb, shapes_b, support, seconds[m + "+shape"])};
    }
    // Only pairs every method described.
    std::vector<size_t> kept;
    for (size_t i = 0; i < n; ++i)
    {
      bool all = true;
      for (const auto& [m, d] : described)
        all = all && d.first.row[i] >= 0 && d.second.row[i] >= 0 && d.second.row[n + i] >= 0;
      if (all)
        kept.push_back(i);
    }
    for (auto& [m, d] : described)
    {
      Scores& s = scores[m];
      s.seconds += seconds[m];
      s.keypoints += n + kb.size();
      s.binary = d.first.descriptors.type() == CV_8U;
      Scores local;
      for (size_t i : kept)
      {
        local.positive.push_back(distance(d.first, static_cast<int>(i), d.second, static_cast<int>(i)));
        local.negative.push_back(distance(d.first, static_cast<int>(i), d.second, static_cast<int>(n + i)));
      }
      per_pair_fpr[pair.name][m] = fpr95(local.positive, local.negative);
      if (pair.synthetic)
        for (const std::string& c : conditionsOf(*pair.synthetic))
        {
          Scores& pooled = evaluation.by_condition[c][m];
          pooled.positive.insert(pooled.positive.end(), local.positive.begin(), local.positive.end());
          pooled.negative.insert(pooled.negative.end(), local.negative.begin(), local.negative.end());
        }
      s.positive.insert(s.positive.end(), local.positive.begin(), local.positive.end());
      s.negative.insert(s.negative.end(), local.negative.begin(), local.negative.end());
    }
    if (pair.synthetic)
    {
      evaluation.view_changes[pair.name] = *pair.synthetic;
      for (const std::string& c : conditionsOf(*pair.synthetic))
        ++evaluation.condition_pairs[c];
    }
    std::cerr << pair.name << ": " << kept.size() << " of " << n << " pairs described by every method\n";
  }
  return evaluation;
}

/// Prints the table of methods and returns the results document.
nlohmann::ordered_json report(const Options& o, const Evaluation& evaluation)
{
  nlohmann::ordered_json results;
  results["command"] = "rosrun biovision_recognition descriptor_eval " + o.command;
  std::cout << std::left << std::setw(22) << "method" << std::setw(10) << "fpr95" << std::setw(12) << "fpr95_at_t"
            << std::setw(10) << "roc_auc" << std::setw(14) << "us/keypoint"
            << "pairs\n";
  for (const auto& [m, s] : evaluation.scores)
  {
    const double f = fpr95(s.positive, s.negative), auc = rocArea(s.positive, s.negative);
    const double f_at_t = fpr95AtThreshold(s.positive, s.negative);
    const double us = 1e6 * s.seconds / std::max<size_t>(1, s.keypoints);
    std::cout << std::setw(22) << m << std::setw(10) << f << std::setw(12) << f_at_t << std::setw(10) << auc
              << std::setw(14) << us << s.positive.size() << "\n";
    results[m] = {{"fpr95", f},
                  {"fpr95_at_threshold", f_at_t},
                  {"roc_auc", auc},
                  {"us_per_keypoint", us},
                  {"pairs", s.positive.size()},
                  {"binary", s.binary}};
    if (s.binary && !o.radii.empty() && !s.positive.empty() && !s.negative.empty())
    {
      std::cout << std::setw(22) << ""
                << "within radius:";
      for (int r : o.radii)
      {
        const double recall = shareWithin(s.positive, r), false_positive = shareWithin(s.negative, r);
        // Beside the methods' flat rows, so the report renders it as a table of its own.
        results["within_radius"][m]["recall_" + std::to_string(r)] = recall;
        results["within_radius"][m]["fpr_" + std::to_string(r)] = false_positive;
        std::cout << " " << r << ": recall " << recall << " fpr " << false_positive << ";";
      }
      std::cout << "\n";
    }
  }
  std::string notes =
      "fpr95 = false-positive rate at exactly 95% recall (ties at the threshold distance shared in proportion, i.e. "
      "the ROC curve interpolated); fpr95_at_threshold = at the first distance whose recall reaches 95%, whole tie "
      "charged; lower is better. Goal: the lowest fpr95 of the binary descriptors (sift is float, for reference).";
  if (!o.stereo.empty() && o.part == "heldout")
    notes +=
        " Stereo scenes: the held-out part of the split by source (none trained on by the models made with "
        "--part dev; the session-4 models trained on the even scenes in name order, so some held-out scenes "
        "were theirs).";
  else if (!o.stereo.empty() && o.part == "validation")
    notes += " Stereo scenes: the validation part of the dev scenes (fold 0 of " + std::to_string(kValidationFolds) +
             " by source; the models compared on it trained with --part fit, the other folds).";
  else if (!o.stereo.empty() && o.part == "test")
    notes += " Stereo scenes: the odd scenes in name order (the session-4 models trained on the even ones).";
  const std::string images_part = collectionPart(o.part, "heldout");
  if (!o.images.empty())
    notes +=
        " Image collections: one synthetic view (ASIFT tilt <= 4 with perspective, photometric change) of "
        "images of their " +
        images_part + " sources" +
        (images_part == "heldout" ? " (never trained on by models made with --part dev)." : ".");
  if (!o.shaped_peers.empty())
    notes +=
        " +shape rows: the peer run on each keypoint's patch resampled by our affine shape adaptation (a hybrid made "
        "to ask whether a gain is the adaptation's or the descriptor's, not the peer as OpenCV ships it; its time "
        "includes one warp and one image per keypoint).";
  results["notes"] = notes;
  if (isSourcePart(o.part))
  {
    std::vector<std::string> scenes;
    if (!o.stereo.empty())
      for (const auto& e : std::filesystem::directory_iterator(o.stereo))
        if (e.is_directory())
          scenes.push_back(e.path().filename().string());
    std::sort(scenes.begin(), scenes.end());
    results["split"] = descriptorSplit().describe(scenes);
    results["split"]["part"] = o.part;
    if (o.part == "fit" || o.part == "validation")
    {
      results["split"]["validation_folds"] = kValidationFolds;
      for (const char* part : {"fit", "validation"})
      {
        results["split"][part] = nlohmann::ordered_json::array();
        for (const auto& scene : scenes)
          if (inSourcePart(scene, part))
            results["split"][part].push_back(scene);
      }
    }
  }
  if (!evaluation.by_condition.empty())
  {
    // Pooled per condition (not the mean of per-pair figures): the same reading as the whole table's.
    nlohmann::ordered_json& conditions = results["by_condition"] = nlohmann::ordered_json::object();
    std::cout << "fpr95 pooled by the synthetic pairs' condition:\n";
    for (const std::string& c : kConditions)
    {
      const auto found = evaluation.by_condition.find(c);
      if (found == evaluation.by_condition.end())
        continue;
      nlohmann::ordered_json& row = conditions[c];
      row["image_pairs"] = evaluation.condition_pairs.at(c);
      row["keypoint_pairs"] = found->second.begin()->second.positive.size();
      std::cout << "  " << std::setw(14) << c << " (" << evaluation.condition_pairs.at(c) << " image pairs)";
      for (const auto& [m, s] : found->second)
      {
        row[m] = fpr95(s.positive, s.negative);
        std::cout << " " << m << " " << row[m].get<double>();
      }
      std::cout << "\n";
    }
  }
  nlohmann::ordered_json& scenes = results["scenes"] = nlohmann::ordered_json::object();
  for (const auto& [name, fprs] : evaluation.per_pair_fpr)
  {
    for (const auto& [m, v] : fprs)
      scenes[name][m] = v;
    const auto change = evaluation.view_changes.find(name);
    if (change != evaluation.view_changes.end())
      scenes[name]["view_change"] = {{"tilt", change->second.tilt},
                                     {"scale", change->second.scale},
                                     {"blur_sigma", change->second.blur_sigma},
                                     {"noise", change->second.noise}};
  }
  // Per image pair: which binary method has the lowest fpr95 (ties: each tied method counts).
  std::map<std::string, int> lowest;
  for (const auto& [name, fprs] : evaluation.per_pair_fpr)
  {
    double low = 2.0;
    for (const auto& [m, v] : fprs)
      if (evaluation.scores.at(m).binary)
        low = std::min(low, v);
    for (const auto& [m, v] : fprs)
      if (evaluation.scores.at(m).binary && v <= low)
        ++lowest[m];
  }
  nlohmann::ordered_json& won = results["pairs_lowest_binary"] = nlohmann::ordered_json::object();
  won["image_pairs"] = evaluation.per_pair_fpr.size();
  for (const auto& [m, count] : lowest)
    won[m] = count;
  std::cout << "image pairs where a binary method has the lowest fpr95 (of " << evaluation.per_pair_fpr.size() << "):";
  for (const auto& [m, count] : lowest)
    std::cout << " " << m << " " << count;
  std::cout << "\n";
  return results;
}
}  // namespace

int main(int argc, char** argv)
{
  const Options o = parseOptions(argc, argv);
  try
  {
    const Models ours = loadModels(o.models);
    const nlohmann::ordered_json results = report(o, evaluate(o, ours));
    if (!o.json_path.empty())
      biovision_common::writeJsonFile(o.json_path, results);
  }
  catch (const std::exception& e)
  {
    std::cerr << "descriptor_eval: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
