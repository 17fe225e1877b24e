#include "vision/lucas_kanade.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

namespace rtmot::vision {
namespace {

/// A window of `side` x `side` pixels around `centre`, sampled bilinearly from `image` (CV_32F)
/// into `out` row by row; false when the centre itself is outside the image. One sub-pixel offset
/// for the whole window, so the four weights are computed once. Near the border the samples
/// repeat the edge pixels (as OpenCV's tracker does): a person half out of the picture is followed
/// by what is still in it.
bool sample_window(const cv::Mat& image, cv::Point2f centre, int side, float* out) {
  const int half = side / 2;
  if (!(centre.x >= 0.F) || !(centre.y >= 0.F) || !(centre.x <= image.cols - 1.F) ||
      !(centre.y <= image.rows - 1.F))
    return false;
  const float fx = std::floor(centre.x);
  const float fy = std::floor(centre.y);
  const int x0 = static_cast<int>(fx) - half;
  const int y0 = static_cast<int>(fy) - half;
  const float ax = centre.x - fx;
  const float ay = centre.y - fy;
  const float w00 = (1.F - ax) * (1.F - ay);
  const float w01 = ax * (1.F - ay);
  const float w10 = (1.F - ax) * ay;
  const float w11 = ax * ay;
  if (x0 >= 0 && y0 >= 0 && x0 + side < image.cols && y0 + side < image.rows) {
    for (int r = 0; r < side; ++r) {
      const float* top = image.ptr<float>(y0 + r) + x0;
      const float* bottom = image.ptr<float>(y0 + r + 1) + x0;
      float* row = out + r * side;
      for (int c = 0; c < side; ++c) {
        row[c] = w00 * top[c] + w01 * top[c + 1] + w10 * bottom[c] + w11 * bottom[c + 1];
      }
    }
    return true;
  }
  const auto clamp_x = [&](int x) { return std::clamp(x, 0, image.cols - 1); };
  const auto clamp_y = [&](int y) { return std::clamp(y, 0, image.rows - 1); };
  for (int r = 0; r < side; ++r) {
    const float* top = image.ptr<float>(clamp_y(y0 + r));
    const float* bottom = image.ptr<float>(clamp_y(y0 + r + 1));
    float* row = out + r * side;
    for (int c = 0; c < side; ++c) {
      const int left = clamp_x(x0 + c);
      const int right = clamp_x(x0 + c + 1);
      row[c] = w00 * top[left] + w01 * top[right] + w10 * bottom[left] + w11 * bottom[right];
    }
  }
  return true;
}

bool finite(cv::Point2f p) {
  return std::isfinite(p.x) && std::isfinite(p.y);
}

// The window's sums run in kLanes independent float partial sums over a length padded to a
// multiple of kLanes (the padding is zero in the gradient windows, so it adds nothing): a
// compiler vectorises independent lanes, not one running sum, without -ffast-math's reassociation.
// This loop is most of the follower's time (bench/vision_bench.cpp).
constexpr std::size_t kLanes = 8;

std::size_t padded(std::size_t area) {
  return (area + kLanes - 1) / kLanes * kLanes;
}

struct GradientSums {
  float xx, xy, yy;
};

GradientSums gradient_sums(const float* gx, const float* gy, std::size_t length) {
  float xx[kLanes] = {};
  float xy[kLanes] = {};
  float yy[kLanes] = {};
  for (std::size_t p = 0; p < length; p += kLanes) {
    for (std::size_t k = 0; k < kLanes; ++k) {
      xx[k] += gx[p + k] * gx[p + k];
      xy[k] += gx[p + k] * gy[p + k];
      yy[k] += gy[p + k] * gy[p + k];
    }
  }
  GradientSums sums{0.F, 0.F, 0.F};
  for (std::size_t k = 0; k < kLanes; ++k) {
    sums.xx += xx[k];
    sums.xy += xy[k];
    sums.yy += yy[k];
  }
  return sums;
}

// The sums over the window of (I - J) times the gradient, both components.
cv::Point2f mismatch_sums(const float* i, const float* j, const float* gx, const float* gy,
                          std::size_t length) {
  float bx[kLanes] = {};
  float by[kLanes] = {};
  for (std::size_t p = 0; p < length; p += kLanes) {
    for (std::size_t k = 0; k < kLanes; ++k) {
      const float difference = i[p + k] - j[p + k];
      bx[k] += difference * gx[p + k];
      by[k] += difference * gy[p + k];
    }
  }
  cv::Point2f sums(0.F, 0.F);
  for (std::size_t k = 0; k < kLanes; ++k) {
    sums.x += bx[k];
    sums.y += by[k];
  }
  return sums;
}

}  // namespace

void LucasKanadePyramid::build(const cv::Mat& gray, const LucasKanadeConfig& config) {
  const auto wanted = static_cast<std::size_t>(config.levels + 1);
  image_.resize(wanted);
  dx_.resize(wanted);
  dy_.resize(wanted);
  gray.convertTo(image_[0], CV_32F);
  std::size_t built = 1;
  for (; built < wanted; ++built) {
    const cv::Mat& below = image_[built - 1];
    // A level smaller than a few windows adds nothing but border.
    if (below.cols < 4 * config.window || below.rows < 4 * config.window) break;
    cv::pyrDown(below, image_[built]);
  }
  image_.resize(built);  // shrinking keeps the other levels' buffers
  dx_.resize(built);
  dy_.resize(built);
  for (std::size_t level = 0; level < built; ++level) {
    // Scharr's kernel sums to 32 per unit slope: scaled to intensity per pixel.
    cv::Scharr(image_[level], dx_[level], CV_32F, 1, 0, 1.0 / 32.0);
    cv::Scharr(image_[level], dy_[level], CV_32F, 0, 1, 1.0 / 32.0);
  }
}

void track_points(const LucasKanadePyramid& from, const LucasKanadePyramid& to,
                  const std::vector<cv::Point2f>& from_points, std::vector<cv::Point2f>& to_points,
                  std::vector<unsigned char>& status, const LucasKanadeConfig& config,
                  std::vector<float>& window_scratch) {
  const int side = config.window | 1;
  const std::size_t area = static_cast<std::size_t>(side) * static_cast<std::size_t>(side);
  const std::size_t length = padded(area);
  window_scratch.assign(4 * length, 0.F);  // the padding stays zero
  float* const i_window = window_scratch.data();
  float* const gx_window = i_window + length;
  float* const gy_window = gx_window + length;
  float* const j_window = gy_window + length;
  const int top_level = std::min(from.levels(), to.levels()) - 1;
  to_points.resize(from_points.size());
  status.assign(from_points.size(), 0);
  const float converged_squared = config.converged * config.converged;
  for (std::size_t k = 0; k < from_points.size(); ++k) {
    const cv::Point2f start = from_points[k];
    to_points[k] = start;
    if (!finite(start) || top_level < 0) continue;
    cv::Point2f guess(0.F, 0.F);  // the displacement found at coarser levels, this level's pixels
    bool lost = false;
    for (int level = top_level; level >= 0 && !lost; --level) {
      const float scale = 1.F / static_cast<float>(1 << level);
      const cv::Point2f at(start.x * scale, start.y * scale);
      if (!sample_window(from.image(level), at, side, i_window) ||
          !sample_window(from.dx(level), at, side, gx_window) ||
          !sample_window(from.dy(level), at, side, gy_window)) {
        lost = true;
        break;
      }
      const GradientSums g = gradient_sums(gx_window, gy_window, length);
      const double gxx = g.xx;
      const double gxy = g.xy;
      const double gyy = g.yy;
      const double det = gxx * gyy - gxy * gxy;
      const double smaller_eigenvalue =
          0.5 * (gxx + gyy - std::sqrt((gxx - gyy) * (gxx - gyy) + 4.0 * gxy * gxy));
      if (smaller_eigenvalue / static_cast<double>(area) < config.min_eigenvalue || det <= 0.0) {
        lost = true;
        break;
      }
      cv::Point2f step(0.F, 0.F);
      for (int iteration = 0; iteration < config.iterations; ++iteration) {
        const cv::Point2f there = at + guess + step;
        if (!finite(there) || !sample_window(to.image(level), there, side, j_window)) {
          lost = true;
          break;
        }
        const cv::Point2f b = mismatch_sums(i_window, j_window, gx_window, gy_window, length);
        const double bx = b.x;
        const double by = b.y;
        const auto eta_x = static_cast<float>((gyy * bx - gxy * by) / det);
        const auto eta_y = static_cast<float>((gxx * by - gxy * bx) / det);
        step.x += eta_x;
        step.y += eta_y;
        if (eta_x * eta_x + eta_y * eta_y < converged_squared) break;
      }
      if (lost) break;
      guess = level > 0 ? (guess + step) * 2.F : guess + step;
    }
    if (lost || !finite(guess)) continue;
    to_points[k] = start + guess;
    status[k] = 1;
  }
}

}  // namespace rtmot::vision
