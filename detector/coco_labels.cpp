#include "detector/coco_labels.hpp"

#include <array>

namespace rtmot::detector {
namespace {

// Index = class id. Empty entries are ids COCO reserved but never annotated.
constexpr std::array<std::string_view, kCocoMaxClassId + 1> kLabels{"",
                                                                    "person",
                                                                    "bicycle",
                                                                    "car",
                                                                    "motorcycle",
                                                                    "airplane",
                                                                    "bus",
                                                                    "train",
                                                                    "truck",
                                                                    "boat",
                                                                    "traffic light",
                                                                    "fire hydrant",
                                                                    "",
                                                                    "stop sign",
                                                                    "parking meter",
                                                                    "bench",
                                                                    "bird",
                                                                    "cat",
                                                                    "dog",
                                                                    "horse",
                                                                    "sheep",
                                                                    "cow",
                                                                    "elephant",
                                                                    "bear",
                                                                    "zebra",
                                                                    "giraffe",
                                                                    "",
                                                                    "backpack",
                                                                    "umbrella",
                                                                    "",
                                                                    "",
                                                                    "handbag",
                                                                    "tie",
                                                                    "suitcase",
                                                                    "frisbee",
                                                                    "skis",
                                                                    "snowboard",
                                                                    "sports ball",
                                                                    "kite",
                                                                    "baseball bat",
                                                                    "baseball glove",
                                                                    "skateboard",
                                                                    "surfboard",
                                                                    "tennis racket",
                                                                    "bottle",
                                                                    "",
                                                                    "wine glass",
                                                                    "cup",
                                                                    "fork",
                                                                    "knife",
                                                                    "spoon",
                                                                    "bowl",
                                                                    "banana",
                                                                    "apple",
                                                                    "sandwich",
                                                                    "orange",
                                                                    "broccoli",
                                                                    "carrot",
                                                                    "hot dog",
                                                                    "pizza",
                                                                    "donut",
                                                                    "cake",
                                                                    "chair",
                                                                    "couch",
                                                                    "potted plant",
                                                                    "bed",
                                                                    "",
                                                                    "dining table",
                                                                    "",
                                                                    "",
                                                                    "toilet",
                                                                    "",
                                                                    "tv",
                                                                    "laptop",
                                                                    "mouse",
                                                                    "remote",
                                                                    "keyboard",
                                                                    "cell phone",
                                                                    "microwave",
                                                                    "oven",
                                                                    "toaster",
                                                                    "sink",
                                                                    "refrigerator",
                                                                    "",
                                                                    "book",
                                                                    "clock",
                                                                    "vase",
                                                                    "scissors",
                                                                    "teddy bear",
                                                                    "hair drier",
                                                                    "toothbrush"};

}  // namespace

std::string_view coco_label(int class_id) {
  if (class_id < 0 || class_id > kCocoMaxClassId) return {};
  return kLabels[static_cast<std::size_t>(class_id)];
}

int coco_class_id(std::string_view label) {
  if (label.empty()) return -1;
  for (int id = 1; id <= kCocoMaxClassId; ++id) {
    if (kLabels[static_cast<std::size_t>(id)] == label) return id;
  }
  return -1;
}

}  // namespace rtmot::detector
