#include "biovision_saliency/saliency_pipeline.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>

namespace biovision_saliency
{
namespace
{
constexpr int kFlowWindow = 9;  // Farneback averaging window; DIS patches are smaller
constexpr int kFlowHalfWindow = kFlowWindow / 2 + 1;

std::vector<double> workingSigmas(const SaliencyParameters& p)
{
  std::vector<double> s;
  for (double sigma : p.blob_sigmas)
    s.push_back(sigma * p.working_width / p.reference_width);
  return s;
}

cv::Mat normalised(const cv::Mat& channel, double floor)
{
  double mx = 0;
  cv::minMaxLoc(channel, nullptr, &mx);
  return channel / std::max(mx, floor);
}

// Median of one flow component over a subsampled grid: the dominant (global) motion.
float medianComponent(const cv::Mat& flow, int c)
{
  std::vector<float> v;
  v.reserve(size_t(flow.rows / 2 + 1) * (flow.cols / 2 + 1));
  for (int y = 0; y < flow.rows; y += 2)
    for (int x = 0; x < flow.cols; x += 2)
      v.push_back(flow.at<cv::Vec2f>(y, x)[c]);
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}
}  // namespace

SaliencyPipeline::SaliencyPipeline(const SaliencyParameters& parameters)
  : parameters_(parameters),
    blobs_(workingSigmas(parameters), parameters.blob_pyramid_sigma),
    ior_(parameters.ior_radius, parameters.ior_decay_time)
{
  parameters_.validate();
  if (parameters_.use_dis_flow)
    flow_ = cv::DISOpticalFlow::create(cv::DISOpticalFlow::PRESET_FAST);
  else
    flow_ = cv::FarnebackOpticalFlow::create(3, 0.5, false, kFlowWindow, 3, 5, 1.1);
}

SaliencyPipeline::~SaliencyPipeline() = default;

void SaliencyPipeline::reset()
{
  previous_gray_.release();
  ior_.reset();
  last_attend_time_ = -1e300;
}

cv::Mat SaliencyPipeline::colourChannel(const cv::Mat& bgr_working) const
{
  // CIE L*a*b*, each channel scaled to about [-1, 1]; white/black, red/green and yellow/blue are the
  // on and off parts of the DoG responses of L, a and b (the thesis' 6 maps and their complements).
  cv::Mat f, lab;
  bgr_working.convertTo(f, CV_32F, 1.0 / 255.0);
  cv::cvtColor(f, lab, cv::COLOR_BGR2Lab);
  std::vector<cv::Mat> planes;
  cv::split(lab, planes);
  planes[0] *= 1.0 / 100.0;
  planes[1] *= 1.0 / 127.0;
  planes[2] *= 1.0 / 127.0;
  cv::Mat sum = cv::Mat::zeros(bgr_working.size(), CV_32F), on, off;
  for (const cv::Mat& p : planes)
  {
    blobs_.positiveAndNegative(p, on, off);
    sum += on;
    sum += off;
  }
  return sum;
}

cv::Mat SaliencyPipeline::disparityChannel(const cv::Mat& d, double max_disparity) const
{
  cv::Mat layer(d.size(), CV_32F, cv::Scalar(0));
  const auto& p = parameters_;
  for (int y = 0; y < d.rows; ++y)
  {
    const float* in = d.ptr<float>(y);
    float* out = layer.ptr<float>(y);
    for (int x = 0; x < d.cols; ++x)
    {
      const float v = in[x];
      if (!(std::isfinite(v) && v >= 0))
        continue;
      if (p.preferred_disparity_mode)
        out[x] = static_cast<float>(std::max(0.0, 1.0 - std::abs(v - p.preferred_disparity) / p.preferred_width));
      else if (max_disparity > 0 && v >= p.near_fraction * max_disparity)
        out[x] = static_cast<float>(v / max_disparity);  // nearer = stronger
    }
  }
  return blobs_.positive(layer);
}

cv::Mat SaliencyPipeline::motionChannel(const cv::Mat& gray, const cv::Point2f& predicted, cv::Point2f* global)
{
  cv::Mat channel = cv::Mat::zeros(gray.size(), CV_32F);
  if (global)
    *global = cv::Point2f();
  if (previous_gray_.empty() || previous_gray_.size() != gray.size())
  {
    previous_gray_ = gray.clone();
    return channel;  // first frame: no flow yet
  }
  cv::Mat flow;
  flow_->calc(previous_gray_, gray, flow);
  previous_gray_ = gray.clone();
  if (parameters_.compensate_ego_motion)
  {
    // Remove what the head's own rotation predicts, then the dominant remaining motion (base motion,
    // prediction error): what is left moves relative to the scene.
    flow -= cv::Scalar(predicted.x, predicted.y);
    const cv::Point2f g(medianComponent(flow, 0), medianComponent(flow, 1));
    flow -= cv::Scalar(g.x, g.y);
    if (global)
      *global = g + predicted;
  }
  // Flow is unreliable where the flow window leaves the image and where content entered the frame
  // during the motion: ignore a border band of half the window plus the image motion.
  const cv::Point2f total = parameters_.compensate_ego_motion ? (global ? *global : predicted) : cv::Point2f();
  const int band = kFlowHalfWindow + static_cast<int>(std::ceil(std::max(std::abs(total.x), std::abs(total.y))));
  // 3 speed maps and 8 direction maps: a pixel's value is its speed where it falls in the map's bin.
  const auto& e = parameters_.speed_edges;
  std::vector<cv::Mat> maps(11);
  for (auto& m : maps)
    m = cv::Mat::zeros(gray.size(), CV_32F);
  for (int y = band; y < flow.rows - band; ++y)
    for (int x = band; x < flow.cols - band; ++x)
    {
      const cv::Vec2f v = flow.at<cv::Vec2f>(y, x);
      const float speed = std::hypot(v[0], v[1]);
      if (speed < e[0])
        continue;
      const int speed_bin = speed < e[1] ? 0 : (speed < e[2] ? 1 : 2);
      maps[speed_bin].at<float>(y, x) = speed;
      const double angle = std::atan2(v[1], v[0]);  // image coordinates
      const int direction_bin = (static_cast<int>(std::lround(angle / (M_PI / 4))) + 8) % 8;
      maps[3 + direction_bin].at<float>(y, x) = speed;
    }
  for (const cv::Mat& m : maps)
    channel += blobs_.positive(m);
  return channel;
}

cv::Mat SaliencyPipeline::priorMap(cv::Size working, double scale, const HeadDirection& head) const
{
  const auto& p = parameters_;
  if (p.prior == PriorMode::none)
    return cv::Mat(working, CV_32F, cv::Scalar(1));
  // Separable: a column profile (vertical) times a row profile (horizontal, 1 for the horizon band), so
  // a frame costs width + height exponentials. Working-pixel centres in full-resolution px: (x + 0.5) scale.
  const double sx = p.prior_sigma * working.width * scale, sy = p.prior_sigma * working.height * scale;
  const double centre_row = p.prior == PriorMode::centre ? head.principal.y
                                                         : head.principal.y - head.focal * std::tan(head.tilt);
  cv::Mat column(working.height, 1, CV_32F), row(1, working.width, CV_32F, cv::Scalar(1));
  for (int y = 0; y < working.height; ++y)
  {
    const double d = ((y + 0.5) * scale - centre_row) / sy;
    column.at<float>(y) = static_cast<float>(std::exp(-0.5 * d * d));
  }
  if (p.prior == PriorMode::centre)
    for (int x = 0; x < working.width; ++x)
    {
      const double d = ((x + 0.5) * scale - head.principal.x) / sx;
      row.at<float>(x) = static_cast<float>(std::exp(-0.5 * d * d));
    }
  return column * row;
}

std::vector<SalientRegion> SaliencyPipeline::extractRegions(const cv::Mat& map, double scale, cv::Size full,
                                                            const HeadDirection& head, double t)
{
  std::vector<SalientRegion> regions;
  cv::Mat mask = map >= static_cast<float>(parameters_.threshold);
  cv::Mat labels, stats, centroids;
  const int n = cv::connectedComponentsWithStats(mask, labels, stats, centroids, 8, CV_32S);
  const double area_scale = (parameters_.reference_width / parameters_.working_width) *
                            (parameters_.reference_width / parameters_.working_width);
  const cv::Rect image(0, 0, full.width, full.height);
  for (int i = 1; i < n; ++i)
  {
    const int area = stats.at<int>(i, cv::CC_STAT_AREA);
    if (area * area_scale < parameters_.min_area)
      continue;
    const cv::Rect r(stats.at<int>(i, cv::CC_STAT_LEFT), stats.at<int>(i, cv::CC_STAT_TOP),
                     stats.at<int>(i, cv::CC_STAT_WIDTH), stats.at<int>(i, cv::CC_STAT_HEIGHT));
    cv::Mat inside = labels(r) == i;
    double peak = 0;
    cv::Point peak_at;
    cv::minMaxLoc(map(r), nullptr, &peak, nullptr, &peak_at, inside);
    SalientRegion region;
    region.peak = static_cast<float>(peak);
    region.mean = static_cast<float>(cv::mean(map(r), inside)[0]);
    region.area = static_cast<int>(std::lround(area * scale * scale));
    region.centre = cv::Point2f(static_cast<float>((r.x + peak_at.x + 0.5) * scale),
                                static_cast<float>((r.y + peak_at.y + 0.5) * scale));
    const int m = static_cast<int>(std::lround(parameters_.margin));
    cv::Rect box(static_cast<int>(std::floor(r.x * scale)) - m, static_cast<int>(std::floor(r.y * scale)) - m,
                 static_cast<int>(std::ceil(r.width * scale)) + 2 * m,
                 static_cast<int>(std::ceil(r.height * scale)) + 2 * m);
    region.box = box & image;
    const cv::Point2d dir = head.directionOf(region.centre);
    region.pan = static_cast<float>(dir.x);
    region.tilt = static_cast<float>(dir.y);
    region.inhibition = static_cast<float>(ior_.inhibition(dir, t));
    region.priority = region.peak * (1.f - region.inhibition);
    regions.push_back(region);
  }
  // Focus-of-Attention order: priority, then peak.
  std::sort(regions.begin(), regions.end(), [](const SalientRegion& a, const SalientRegion& b) {
    return a.priority != b.priority ? a.priority > b.priority : a.peak > b.peak;
  });
  if (static_cast<int>(regions.size()) > parameters_.max_regions)
    regions.resize(parameters_.max_regions);
  // The region attended now inhibits its direction for the next frames.
  if (!regions.empty() && parameters_.attend_period > 0 && t - last_attend_time_ >= parameters_.attend_period)
  {
    ior_.attend(cv::Point2d(regions.front().pan, regions.front().tilt), t);
    last_attend_time_ = t;
  }
  return regions;
}

SaliencyResult SaliencyPipeline::process(const cv::Mat& input, const cv::Mat& disparity, const HeadDirection& head_in,
                                         double t)
{
  if (input.empty())
    throw std::invalid_argument("saliency: empty image");
  if (input.depth() != CV_8U || (input.channels() != 1 && input.channels() != 3))
    throw std::invalid_argument("saliency: image must be 8-bit grey or BGR");
  if (input.cols < 16 || input.rows < 16)
    throw std::invalid_argument("saliency: image " + std::to_string(input.cols) + "x" + std::to_string(input.rows) +
                                " is smaller than 16x16");
  cv::Mat bgr;
  if (input.channels() == 1)
    cv::cvtColor(input, bgr, cv::COLOR_GRAY2BGR);
  else
    bgr = input;
  SaliencyResult result;
  const int ww = std::min(parameters_.working_width, bgr.cols);
  const cv::Size working(ww, std::max(8, static_cast<int>(std::lround(double(bgr.rows) * ww / bgr.cols))));
  result.scale = double(bgr.cols) / working.width;
  HeadDirection head = head_in;
  if (!(head.focal > 0))
  {
    head.focal = 0.5 * bgr.cols / std::tan(0.5 * parameters_.horizontal_fov);
    head.principal = cv::Point2d(0.5 * (bgr.cols - 1), 0.5 * (bgr.rows - 1));
  }

  cv::Mat small, gray;
  cv::resize(bgr, small, working, 0, 0, cv::INTER_AREA);
  cv::cvtColor(small, gray, cv::COLOR_BGR2GRAY);

  result.colour = normalised(colourChannel(small), parameters_.colour_floor);
  double weight = parameters_.colour_weight;
  cv::Mat fused = parameters_.colour_weight * result.colour;

  if (!disparity.empty())
  {
    if (disparity.type() != CV_32FC1)
      throw std::invalid_argument("saliency: disparity must be CV_32FC1");
    const double aspect_in = double(bgr.cols) / bgr.rows, aspect_d = double(disparity.cols) / disparity.rows;
    if (std::abs(aspect_in - aspect_d) > 0.02 * aspect_in)
      throw std::invalid_argument("saliency: disparity " + std::to_string(disparity.cols) + "x" +
                                  std::to_string(disparity.rows) + " does not have the image's aspect");
    // Nearest neighbour keeps invalid pixels invalid; values to full-resolution px are kept as given.
    cv::Mat d;
    cv::resize(disparity, d, working, 0, 0, cv::INTER_NEAREST);
    d *= double(bgr.cols) / disparity.cols;  // disparity measured at another resolution
    double max_d = 0;
    cv::Mat valid = (d >= 0) & (d == d);
    cv::minMaxLoc(d, nullptr, &max_d, nullptr, nullptr, valid);
    result.disparity = normalised(disparityChannel(d, max_d), parameters_.disparity_floor);
    fused += parameters_.disparity_weight * result.disparity;
    weight += parameters_.disparity_weight;
  }

  // Predicted image motion of the head's own rotation since the last frame [working px/frame]:
  // panning left (+) moves the scene right, tilting down (+) moves it up.
  const double f_working = head.focal / result.scale;
  const cv::Point2f predicted(static_cast<float>(f_working * (head.pan - previous_head_.pan)),
                              static_cast<float>(-f_working * (head.tilt - previous_head_.tilt)));
  const bool had_previous = !previous_gray_.empty() && previous_gray_.size() == gray.size();
  cv::Mat motion = motionChannel(gray, had_previous ? predicted : cv::Point2f(), &result.global_flow);
  previous_head_ = head;
  if (had_previous)
  {
    result.motion = normalised(motion, parameters_.motion_floor);
    fused += parameters_.motion_weight * result.motion;
    weight += parameters_.motion_weight;
  }
  fused /= weight;
  if (parameters_.final_blur > 0)
  {
    const double sigma = parameters_.final_blur * working.width / parameters_.reference_width;
    cv::GaussianBlur(fused, fused, cv::Size(), sigma, sigma, cv::BORDER_REPLICATE);
  }
  if (parameters_.prior != PriorMode::none && parameters_.prior_weight > 0)
  {
    const cv::Mat prior = priorMap(working, result.scale, head);
    fused = fused.mul((1.0 - parameters_.prior_weight) + parameters_.prior_weight * prior);
  }
  // Final map on [0, 1] relative to its own maximum, so the threshold is "2/3 of the maximum" -- but
  // never stretched from below min_saliency, so that a featureless frame yields no region.
  double mx = 0;
  cv::minMaxLoc(fused, nullptr, &mx);
  result.map = fused / std::max(mx, parameters_.min_saliency);
  result.thresholded = result.map >= static_cast<float>(parameters_.threshold);
  result.regions = extractRegions(result.map, result.scale, bgr.size(), head, t);
  return result;
}
}  // namespace biovision_saliency
