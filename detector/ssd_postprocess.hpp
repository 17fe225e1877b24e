#pragma once
// What the TF.js graph's Postprocessor did, plus the non-maximum suppression of the TensorFlow
// Object Detection API's SSD (multi-class: every class of every anchor is a candidate, NMS per
// class): the network's raw outputs become scored boxes in pixels. See docs/model.md.
#include <vector>

#include "detector/model_description.hpp"
#include "detector/ssd_anchors.hpp"
#include "detector/ssd_defaults.hpp"
#include "tracker/box.hpp"

namespace rtmot::detector {

struct SsdPostprocessConfig {
  float score_threshold{kDefaultScoreThreshold};
  /// Boxes of one class overlapping a better one by more than this IoU are dropped.
  float nms_iou{kDefaultNmsIou};
  int max_detections{kDefaultMaxDetections};  // per class and in total, as the TF pipeline
  std::vector<int> classes;                   // class ids to report; empty = all
  /// Drop boxes of shapes their class does not have (box_plausibility.hpp) before NMS.
  bool plausible_shapes{true};
};

class SsdPostprocessor {
 public:
  /// Layout deltas: the outputs are box codes against `anchors`. `num_classes` counts the
  /// background column 0 (91 for COCO). Throws std::invalid_argument for class ids outside
  /// 1..num_classes-1 or an empty anchor list.
  SsdPostprocessor(std::vector<Anchor> anchors, int num_classes, SsdPostprocessConfig config);
  /// Layout decoded: the outputs are corner boxes in 0..1 and probabilities; the anchor count is
  /// the model's, known once it ran (size_for()). Throws as above for the class ids.
  static SsdPostprocessor decoded(int num_classes, SsdPostprocessConfig config);
  /// Layout decoded: sets the rows per image and reserves for them (once, at start-up).
  void size_for(int anchors);

  /// `boxes`: num_anchors() x 4 (deltas: ty, tx, th, tw; decoded: x1, y1, x2, y2 in 0..1);
  /// `scores`: num_anchors() x num_classes (deltas: logits; decoded: probabilities). Fills `out`
  /// (cleared first) with boxes in pixels of a `image_width` x `image_height` image, clipped to
  /// it, best score first. Allocates nothing once `out` has grown to its working size.
  void run(const float* boxes, const float* scores, int image_width, int image_height,
           std::vector<tracker::Detection>& out);

  int num_anchors() const { return static_cast<int>(anchor_count_); }
  int num_classes() const { return num_classes_; }
  OutputLayout layout() const { return layout_; }

 private:
  struct Candidate {
    float score;
    int class_id;
    float x1, y1, x2, y2;  // pixels, not clipped (as the TF pipeline suppresses)
  };

  SsdPostprocessor(OutputLayout layout, std::vector<Anchor> anchors, int num_classes,
                   SsdPostprocessConfig config);
  void reserve();
  void collect(const float* boxes, const float* scores, int image_width, int image_height);
  void suppress_and_emit(int image_width, int image_height, std::vector<tracker::Detection>& out);

  OutputLayout layout_;
  std::vector<Anchor> anchors_;  // layout deltas only
  std::size_t anchor_count_;
  int num_classes_;
  SsdPostprocessConfig config_;
  std::vector<int> class_ids_;  // the classes to look at, ascending
  float logit_threshold_;       // sigmoid is monotonic: compare logits, take exp() of few
  std::vector<Candidate> candidates_;
  std::vector<Candidate> kept_;
  // Every class's survivors before the overall cut to max_detections: the caller's vector then
  // only ever receives at most max_detections, so it reaches its final capacity on the first call.
  std::vector<tracker::Detection> emitted_;
};

}  // namespace rtmot::detector
