#include "vision/colour_signature.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

namespace rtmot::vision {
namespace {

using tracker::Appearance;

// The core: the middle half of the box's width; the torso from 12 % to 50 % of its height, the
// legs from 50 % to 85 % (a standing person: the head above, the feet and ground below).
constexpr float kCoreLeft = 0.25F;
constexpr float kCoreRight = 0.75F;
constexpr float kTorsoTop = 0.12F;
constexpr float kWaist = 0.5F;
constexpr float kLegsBottom = 0.85F;

// Per part: 8 hues x 2 saturations for coloured pixels, 8 brightness bins for the rest.
constexpr int kHueBins = 8;
constexpr int kSaturationBins = 2;
constexpr int kBrightnessBins = 8;
constexpr int kPartBins = kHueBins * kSaturationBins + kBrightnessBins;
static_assert(2 * kPartBins == Appearance::kBins, "two parts fill the tracker's histogram");
// OpenCV's 8-bit HSV: hue 0..179, saturation and value 0..255. Below these a pixel's hue is noise.
constexpr int kMinSaturation = 50;
constexpr int kMinValue = 40;
constexpr int kHighSaturation = 140;
// A part with fewer pixels says little (a person 10 px tall).
constexpr int kMinPartPixels = 12;

cv::Rect part_rect(const tracker::Box& box, float top, float bottom, const cv::Size& frame) {
  const auto x0 = static_cast<int>(std::floor(box.x + kCoreLeft * box.w));
  const auto x1 = static_cast<int>(std::ceil(box.x + kCoreRight * box.w));
  const auto y0 = static_cast<int>(std::floor(box.y + top * box.h));
  const auto y1 = static_cast<int>(std::ceil(box.y + bottom * box.h));
  return cv::Rect(x0, y0, x1 - x0, y1 - y0) & cv::Rect(0, 0, frame.width, frame.height);
}

// Fills bins[0..kPartBins) with the part's histogram, summing to `share`; false if too small.
bool histogram(const cv::Mat& hsv, float* bins, float share) {
  std::fill(bins, bins + kPartBins, 0.F);
  for (int row = 0; row < hsv.rows; ++row) {
    const auto* pixel = hsv.ptr<cv::Vec3b>(row);
    for (int col = 0; col < hsv.cols; ++col) {
      const int hue = pixel[col][0];
      const int saturation = pixel[col][1];
      const int value = pixel[col][2];
      if (saturation < kMinSaturation || value < kMinValue) {
        bins[kHueBins * kSaturationBins + value * kBrightnessBins / 256] += 1.F;
      } else {
        const int h = std::min(hue * kHueBins / 180, kHueBins - 1);
        const int s = saturation < kHighSaturation ? 0 : 1;
        bins[h * kSaturationBins + s] += 1.F;
      }
    }
  }
  const int pixels = hsv.rows * hsv.cols;
  if (pixels < kMinPartPixels) return false;
  const float scale = share / static_cast<float>(pixels);
  for (int i = 0; i < kPartBins; ++i) bins[i] *= scale;
  return true;
}

}  // namespace

void ColourSignature::measure(const cv::Mat& frame, const tracker::Box& box,
                              tracker::Appearance& out) {
  out.valid = false;
  if (frame.empty() || frame.type() != CV_8UC3) return;
  if (hsv_.size() != frame.size()) hsv_.create(frame.size(), CV_8UC3);
  const cv::Rect parts[] = {part_rect(box, kTorsoTop, kWaist, frame.size()),
                            part_rect(box, kWaist, kLegsBottom, frame.size())};
  for (int part = 0; part < 2; ++part) {
    const cv::Rect& r = parts[part];
    if (r.width <= 0 || r.height <= 0) return;
    cv::Mat hsv = hsv_(r);  // a header: cvtColor writes in place, hsv_ keeps its buffer
    cv::cvtColor(frame(r), hsv, cv::COLOR_BGR2HSV);
    if (!histogram(hsv, out.bins.data() + part * kPartBins, 0.5F)) return;
  }
  out.valid = true;
}

}  // namespace rtmot::vision
