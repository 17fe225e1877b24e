#include "detector/ssd_postprocess.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <string>

#include "detector/box_plausibility.hpp"
#include "tracker/box_geometry.hpp"

namespace rtmot::detector {
namespace {

// The box coder's scale factors (TF OD API FasterRcnnBoxCoder with scales 10, 10, 5, 5), as the
// graph's Postprocessor/Decode multiplies by them.
constexpr float kCenterScale = 10.F;
constexpr float kSizeScale = 5.F;

float sigmoid(float logit) {
  return 1.F / (1.F + std::exp(-logit));
}

float logit_of(float probability) {
  if (probability <= 0.F) return -std::numeric_limits<float>::infinity();
  if (probability >= 1.F) return std::numeric_limits<float>::infinity();
  // A hair below the exact logit, so rounding never drops a box that scores exactly the threshold;
  // the score itself is compared again after the sigmoid.
  return std::nextafter(std::log(probability / (1.F - probability)),
                        -std::numeric_limits<float>::infinity());
}

// The product's one IoU (tracker/box_geometry.hpp) on the candidates' corner boxes.
template <typename Corners>
float iou(const Corners& a, const Corners& b) {
  return tracker::iou(tracker::Box{a.x1, a.y1, a.x2 - a.x1, a.y2 - a.y1},
                      tracker::Box{b.x1, b.y1, b.x2 - b.x1, b.y2 - b.y1});
}

}  // namespace

SsdPostprocessor::SsdPostprocessor(std::vector<Anchor> anchors, int num_classes,
                                   SsdPostprocessConfig config)
    : SsdPostprocessor(OutputLayout::deltas, std::move(anchors), num_classes, std::move(config)) {
  if (anchors_.empty()) throw std::invalid_argument("SsdPostprocessor: no anchors");
}

SsdPostprocessor SsdPostprocessor::decoded(int num_classes, SsdPostprocessConfig config) {
  return SsdPostprocessor(OutputLayout::decoded, {}, num_classes, std::move(config));
}

SsdPostprocessor::SsdPostprocessor(OutputLayout layout, std::vector<Anchor> anchors,
                                   int num_classes, SsdPostprocessConfig config)
    : layout_(layout),
      anchors_(std::move(anchors)),
      anchor_count_(anchors_.size()),
      num_classes_(num_classes),
      config_(std::move(config)),
      logit_threshold_(logit_of(config_.score_threshold)) {
  if (config_.classes.empty()) {
    for (int id = 1; id < num_classes_; ++id) class_ids_.push_back(id);
  } else {
    class_ids_ = config_.classes;
    std::sort(class_ids_.begin(), class_ids_.end());
    class_ids_.erase(std::unique(class_ids_.begin(), class_ids_.end()), class_ids_.end());
    for (const int id : class_ids_) {
      if (id < 1 || id >= num_classes_) {
        throw std::invalid_argument("class id " + std::to_string(id) + " is outside 1.." +
                                    std::to_string(num_classes_ - 1));
      }
    }
  }
  reserve();
}

void SsdPostprocessor::size_for(int anchors) {
  anchor_count_ = static_cast<std::size_t>(std::max(anchors, 0));
  reserve();
}

// The worst case (every class of every anchor passes) once, so run() never grows these.
void SsdPostprocessor::reserve() {
  candidates_.reserve(anchor_count_ * class_ids_.size());
  kept_.reserve(anchor_count_);
  const auto max_kept = static_cast<std::size_t>(std::max(config_.max_detections, 0));
  emitted_.reserve(std::min(anchor_count_, max_kept) * class_ids_.size());
}

void SsdPostprocessor::run(const float* boxes, const float* scores, int image_width,
                           int image_height, std::vector<tracker::Detection>& out) {
  out.clear();
  collect(boxes, scores, image_width, image_height);
  suppress_and_emit(image_width, image_height, out);
}

void SsdPostprocessor::collect(const float* boxes, const float* scores, int image_width,
                               int image_height) {
  candidates_.clear();
  const auto width = static_cast<float>(image_width);
  const auto height = static_cast<float>(image_height);
  const bool logits = layout_ == OutputLayout::deltas;
  for (std::size_t a = 0; a < anchor_count_; ++a) {
    const float* row = scores + a * static_cast<std::size_t>(num_classes_);
    bool decoded = false;
    Candidate box{};
    for (const int id : class_ids_) {
      float score = row[id];
      if (logits) {
        if (score < logit_threshold_) continue;
        score = sigmoid(score);
      }
      if (!(score >= config_.score_threshold)) continue;  // NaN too
      if (!decoded) {  // decode an anchor's box only when one of its classes passes
        const float* code = boxes + a * 4;
        if (logits) {
          const Anchor& anchor = anchors_[a];
          const float yc = code[0] / kCenterScale * anchor.height + anchor.y_center;
          const float xc = code[1] / kCenterScale * anchor.width + anchor.x_center;
          const float half_h = 0.5F * std::exp(code[2] / kSizeScale) * anchor.height;
          const float half_w = 0.5F * std::exp(code[3] / kSizeScale) * anchor.width;
          box.x1 = (xc - half_w) * width;
          box.y1 = (yc - half_h) * height;
          box.x2 = (xc + half_w) * width;
          box.y2 = (yc + half_h) * height;
        } else {
          box.x1 = code[0] * width;
          box.y1 = code[1] * height;
          box.x2 = code[2] * width;
          box.y2 = code[3] * height;
        }
        decoded = true;
      }
      if (config_.plausible_shapes && !plausible_shape(id, box.x2 - box.x1, box.y2 - box.y1)) {
        continue;
      }
      box.score = score;
      box.class_id = id;
      candidates_.push_back(box);
    }
  }
}

void SsdPostprocessor::suppress_and_emit(int image_width, int image_height,
                                         std::vector<tracker::Detection>& out) {
  // Group by class, best first inside each group; std::sort does not allocate.
  std::sort(candidates_.begin(), candidates_.end(), [](const Candidate& a, const Candidate& b) {
    return a.class_id != b.class_id ? a.class_id < b.class_id : a.score > b.score;
  });
  const auto width = static_cast<float>(image_width);
  const auto height = static_cast<float>(image_height);
  const auto max_kept = static_cast<std::size_t>(std::max(config_.max_detections, 0));
  emitted_.clear();
  for (auto group = candidates_.begin(); group != candidates_.end();) {
    const int class_id = group->class_id;
    kept_.clear();
    auto it = group;
    for (; it != candidates_.end() && it->class_id == class_id; ++it) {
      if (kept_.size() >= max_kept) continue;
      const bool overlaps = std::any_of(kept_.begin(), kept_.end(), [&](const Candidate& k) {
        return iou(k, *it) > config_.nms_iou;
      });
      if (!overlaps) kept_.push_back(*it);
    }
    group = it;
    for (const Candidate& k : kept_) {
      const float x1 = std::clamp(k.x1, 0.F, width);
      const float y1 = std::clamp(k.y1, 0.F, height);
      const float x2 = std::clamp(k.x2, 0.F, width);
      const float y2 = std::clamp(k.y2, 0.F, height);
      if (x2 <= x1 || y2 <= y1) continue;  // entirely outside the image
      emitted_.push_back({{x1, y1, x2 - x1, y2 - y1}, k.score, k.class_id});
    }
  }
  std::sort(
      emitted_.begin(), emitted_.end(),
      [](const tracker::Detection& a, const tracker::Detection& b) { return a.score > b.score; });
  // Reserving the whole budget once means a later frame with more detections never grows `out`.
  out.reserve(max_kept);
  out.insert(out.end(), emitted_.begin(),
             emitted_.begin() + static_cast<std::ptrdiff_t>(std::min(emitted_.size(), max_kept)));
}

}  // namespace rtmot::detector
