#include "vision/lucas_kanade.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <opencv2/imgproc.hpp>

namespace rtmot::vision {
namespace {

// Four floats in one SIMD register (SSE, NEON; GCC's and Clang's vector extension), with
// element-wise arithmetic: each element is computed by the same expression, in the same order,
// as the scalar loop it replaces, so the results are the same bits, four at a time (checked
// against the scalar loops on x86-64 and on aarch64, where GCC fuses multiply-adds in both alike).
// Written out because the compilers vectorise the 9-wide window rows poorly on their own (they
// unroll a 9-iteration loop into scalar code, or wrap it in run-time alias and remainder checks):
// the follower took twice the time (bench/vision_bench.cpp).
using Float4 = float __attribute__((vector_size(16)));

Float4 load4(const float* from) {
  Float4 v;
  std::memcpy(&v, from, sizeof v);  // unaligned: one movups / ldr q
  return v;
}

void store4(float* to, Float4 v) {
  std::memcpy(to, &v, sizeof v);
}

Float4 splat(float x) {
  return Float4{x, x, x, x};
}

/// Where a window of `side` x `side` pixels around a sub-pixel centre is sampled bilinearly: its
/// top-left pixel and the four weights, one set for the whole window (one sub-pixel offset).
struct WindowAt {
  int x0, y0;
  float w00, w01, w10, w11;
};

/// False when the centre itself is outside `size`.
bool locate(cv::Size size, cv::Point2f centre, int side, WindowAt& at) {
  if (!(centre.x >= 0.F) || !(centre.y >= 0.F) || !(centre.x <= size.width - 1.F) ||
      !(centre.y <= size.height - 1.F))
    return false;
  const int half = side / 2;
  const float fx = std::floor(centre.x);
  const float fy = std::floor(centre.y);
  const float ax = centre.x - fx;
  const float ay = centre.y - fy;
  at.x0 = static_cast<int>(fx) - half;
  at.y0 = static_cast<int>(fy) - half;
  at.w00 = (1.F - ax) * (1.F - ay);
  at.w01 = ax * (1.F - ay);
  at.w10 = (1.F - ax) * ay;
  at.w11 = ax * ay;
  return true;
}

/// Whether the window and the row and column after it (the bilinear neighbours) are in `size`.
bool wholly_inside(cv::Size size, const WindowAt& at, int side) {
  return at.x0 >= 0 && at.y0 >= 0 && at.x0 + side < size.width && at.y0 + side < size.height;
}

/// The window of `image` (CV_32F) at `at` into `out`, row by row. kSide: the side when known at
/// compile time (the loops then unroll), 0 when `side` says it. Near the border the samples repeat
/// the edge pixels (as OpenCV's tracker does): a person half out of the picture is followed by
/// what is still in it.
template <int kSide>
void sample_window(const cv::Mat& image, const WindowAt& at, int side_at_run_time, float* out) {
  const int side = kSide > 0 ? kSide : side_at_run_time;
  const float w00 = at.w00;
  const float w01 = at.w01;
  const float w10 = at.w10;
  const float w11 = at.w11;
  if (wholly_inside(image.size(), at, side)) {
    const std::size_t stride = image.step[0] / sizeof(float);  // step1() is not inlined
    const float* top = image.ptr<float>(at.y0) + at.x0;
    const Float4 v00 = splat(w00);
    const Float4 v01 = splat(w01);
    const Float4 v10 = splat(w10);
    const Float4 v11 = splat(w11);
    for (int r = 0; r < side; ++r, top += stride) {
      const float* bottom = top + stride;
      float* row = out + r * side;
      int c = 0;
      for (; c + 4 <= side; c += 4) {
        store4(row + c, v00 * load4(top + c) + v01 * load4(top + c + 1) + v10 * load4(bottom + c) +
                            v11 * load4(bottom + c + 1));
      }
      for (; c < side; ++c) {
        row[c] = w00 * top[c] + w01 * top[c + 1] + w10 * bottom[c] + w11 * bottom[c + 1];
      }
    }
    return;
  }
  const auto clamp_x = [&](int x) { return std::clamp(x, 0, image.cols - 1); };
  const auto clamp_y = [&](int y) { return std::clamp(y, 0, image.rows - 1); };
  for (int r = 0; r < side; ++r) {
    const float* top = image.ptr<float>(clamp_y(at.y0 + r));
    const float* bottom = image.ptr<float>(clamp_y(at.y0 + r + 1));
    float* row = out + r * side;
    for (int c = 0; c < side; ++c) {
      const int left = clamp_x(at.x0 + c);
      const int right = clamp_x(at.x0 + c + 1);
      row[c] = w00 * top[left] + w01 * top[right] + w10 * bottom[left] + w11 * bottom[right];
    }
  }
}

bool finite(cv::Point2f p) {
  return std::isfinite(p.x) && std::isfinite(p.y);
}

// The window's sums run in kLanes independent float partial sums over a length padded to a
// multiple of kLanes (the padding is zero in the gradient windows, so it adds nothing): lanes
// vectorise, one running sum would not, without -ffast-math's reassociation. With the window
// sampling, these sums are most of the follower's time (bench/vision_bench.cpp).
constexpr std::size_t kLanes = 8;

constexpr std::size_t padded(std::size_t area) {
  return (area + kLanes - 1) / kLanes * kLanes;
}

struct GradientSums {
  float xx, xy, yy;
};

// kLength: the padded length when known at compile time, 0 when `length` says it. Lane k of the
// kLanes sums is element k % 4 of the (k / 4)th Float4.
template <std::size_t kLength>
GradientSums gradient_sums(const float* gx, const float* gy, std::size_t length_at_run_time) {
  static_assert(kLanes == 8, "two Float4 per kLanes");
  const std::size_t length = kLength > 0 ? kLength : length_at_run_time;
  Float4 xx[2] = {};
  Float4 xy[2] = {};
  Float4 yy[2] = {};
  for (std::size_t p = 0; p < length; p += kLanes) {
    for (std::size_t h = 0; h < 2; ++h) {
      const Float4 x = load4(gx + p + 4 * h);
      const Float4 y = load4(gy + p + 4 * h);
      xx[h] += x * x;
      xy[h] += x * y;
      yy[h] += y * y;
    }
  }
  GradientSums sums{0.F, 0.F, 0.F};
  for (std::size_t k = 0; k < kLanes; ++k) {
    sums.xx += xx[k / 4][k % 4];
    sums.xy += xy[k / 4][k % 4];
    sums.yy += yy[k / 4][k % 4];
  }
  return sums;
}

// The sums over the window of (I - J) times the gradient, both components.
template <std::size_t kLength>
cv::Point2f mismatch_sums(const float* i, const float* j, const float* gx, const float* gy,
                          std::size_t length_at_run_time) {
  const std::size_t length = kLength > 0 ? kLength : length_at_run_time;
  Float4 bx[2] = {};
  Float4 by[2] = {};
  for (std::size_t p = 0; p < length; p += kLanes) {
    for (std::size_t h = 0; h < 2; ++h) {
      const std::size_t q = p + 4 * h;
      const Float4 difference = load4(i + q) - load4(j + q);
      bx[h] += difference * load4(gx + q);
      by[h] += difference * load4(gy + q);
    }
  }
  cv::Point2f sums(0.F, 0.F);
  for (std::size_t k = 0; k < kLanes; ++k) {
    sums.x += bx[k / 4][k % 4];
    sums.y += by[k / 4][k % 4];
  }
  return sums;
}

/// The window buffers of one point, each `length` floats (the padding stays zero).
struct Windows {
  float* i;   // the "from" image around the point
  float* gx;  // its gradients
  float* gy;
  float* j;  // the "to" image around the point's current guess
};

/// Lucas-Kanade for one point from `start` (level 0 pixels); false where it was not followed.
/// kSide: the window's side when known at compile time (0: config's), so that the window loops,
/// which are most of the follower's time (bench/vision_bench.cpp), unroll.
template <int kSide>
bool track_point(const LucasKanadePyramid& from, const LucasKanadePyramid& to, cv::Point2f start,
                 const LucasKanadeConfig& config, int top_level, const Windows& windows,
                 cv::Point2f& end) {
  constexpr std::size_t kLength =
      kSide > 0 ? padded(static_cast<std::size_t>(kSide) * static_cast<std::size_t>(kSide)) : 0;
  const int side = kSide > 0 ? kSide : (config.window | 1);
  const std::size_t area = static_cast<std::size_t>(side) * static_cast<std::size_t>(side);
  const std::size_t length = padded(area);
  const float converged_squared = config.converged * config.converged;
  cv::Point2f guess(0.F, 0.F);  // the displacement found at coarser levels, this level's pixels
  for (int level = top_level; level >= 0; --level) {
    const float scale = 1.F / static_cast<float>(1 << level);
    const cv::Point2f at(start.x * scale, start.y * scale);
    // The image and its derivatives share their size, so one place serves the three.
    WindowAt from_at{};
    if (!locate(from.image(level).size(), at, side, from_at)) return false;
    sample_window<kSide>(from.image(level), from_at, side, windows.i);
    sample_window<kSide>(from.dx(level), from_at, side, windows.gx);
    sample_window<kSide>(from.dy(level), from_at, side, windows.gy);
    const GradientSums g = gradient_sums<kLength>(windows.gx, windows.gy, length);
    const double gxx = g.xx;
    const double gxy = g.xy;
    const double gyy = g.yy;
    const double det = gxx * gyy - gxy * gxy;
    const double smaller_eigenvalue =
        0.5 * (gxx + gyy - std::sqrt((gxx - gyy) * (gxx - gyy) + 4.0 * gxy * gxy));
    if (smaller_eigenvalue / static_cast<double>(area) < config.min_eigenvalue || det <= 0.0)
      return false;
    const cv::Mat& to_image = to.image(level);
    cv::Point2f step(0.F, 0.F);
    for (int iteration = 0; iteration < config.iterations; ++iteration) {
      const cv::Point2f there = at + guess + step;
      WindowAt to_at{};
      if (!finite(there) || !locate(to_image.size(), there, side, to_at)) return false;
      sample_window<kSide>(to_image, to_at, side, windows.j);
      const cv::Point2f b =
          mismatch_sums<kLength>(windows.i, windows.j, windows.gx, windows.gy, length);
      const double bx = b.x;
      const double by = b.y;
      const auto eta_x = static_cast<float>((gyy * bx - gxy * by) / det);
      const auto eta_y = static_cast<float>((gxx * by - gxy * bx) / det);
      step.x += eta_x;
      step.y += eta_y;
      if (eta_x * eta_x + eta_y * eta_y < converged_squared) break;
    }
    guess = level > 0 ? (guess + step) * 2.F : guess + step;
  }
  if (!finite(guess)) return false;
  end = start + guess;
  return true;
}

// The window side the follower uses (BoxFollowerConfig, LucasKanadeConfig's default): its loops
// are compiled for it; any other side runs the same code with the side known at run time.
constexpr int kUnrolledSide = 9;

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
                  std::vector<float>& window_scratch, const std::vector<unsigned char>* only) {
  const int side = config.window | 1;
  const std::size_t length =
      padded(static_cast<std::size_t>(side) * static_cast<std::size_t>(side));
  window_scratch.assign(4 * length, 0.F);  // the padding stays zero
  const Windows windows{window_scratch.data(), window_scratch.data() + length,
                        window_scratch.data() + 2 * length, window_scratch.data() + 3 * length};
  const int top_level = std::min(from.levels(), to.levels()) - 1;
  to_points.resize(from_points.size());
  status.assign(from_points.size(), 0);
  for (std::size_t k = 0; k < from_points.size(); ++k) {
    const cv::Point2f start = from_points[k];
    to_points[k] = start;
    if (!finite(start) || top_level < 0 || (only != nullptr && (*only)[k] == 0)) continue;
    const bool followed =
        side == kUnrolledSide
            ? track_point<kUnrolledSide>(from, to, start, config, top_level, windows, to_points[k])
            : track_point<0>(from, to, start, config, top_level, windows, to_points[k]);
    status[k] = followed ? 1 : 0;
  }
}

}  // namespace rtmot::vision
