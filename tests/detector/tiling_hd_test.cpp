// The SSD on HD frames of a real street (MOT15's ADL-Rundle-6, 1920x1080, in ../shared), untiled
// and in the tiles auto cuts for that size: the tiles find people the thumbnail loses, without
// losing the ones it finds. Scored against the sequence's ground truth (IoU >= 0.5, one to one,
// greedy).
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "detector/ssd_detector.hpp"
#include "detector/tiling_detector.hpp"
#include "motio/mot_files.hpp"
#include "shared_data.hpp"
#include "tracker/box_geometry.hpp"

namespace rtmot::detector {
namespace {

// Every 75th frame. On these, with the study's detections (XNNPACK): 66 people; untiled 32 of 54
// boxes on a person, tiled (4 x 2 + the whole frame) 44 of 64. Asked: half that gain, and a
// precision no more than 0.05 below untiled (another engine's and CPU's rounding).
const std::vector<int> kFrames{1, 76, 151, 226, 301, 376, 451};
constexpr int kTiledMargin = 6;
constexpr double kPrecisionSlack = 0.05;

struct Matches {
  int found{0};     // detections matched to a person
  int reported{0};  // detections
  int people{0};    // annotated people
};

Matches match(const std::vector<tracker::Detection>& detections,
              const std::vector<tracker::Box>& people) {
  Matches m;
  m.reported = static_cast<int>(detections.size());
  m.people = static_cast<int>(people.size());
  std::vector<bool> taken(people.size(), false);
  for (const auto& d : detections) {  // best score first, as the detector reports them
    int best = -1;
    float best_iou = 0.5F;
    for (std::size_t p = 0; p < people.size(); ++p) {
      const float iou = tracker::iou(d.box, people[p]);
      if (!taken[p] && iou >= best_iou) {
        best = static_cast<int>(p);
        best_iou = iou;
      }
    }
    if (best >= 0) {
      taken[static_cast<std::size_t>(best)] = true;
      ++m.found;
    }
  }
  return m;
}

TEST(TilingHd, TilesFindMorePeopleOnAnHdStreetAtNoLowerPrecision) {
  const auto folder = test::shared_path("data/video-gt/ADL-Rundle-6");
  RTMOT_REQUIRE_FILE(folder / "gt/gt.txt");
  const auto rows = motio::read_mot_file(folder / "gt/gt.txt", motio::MotFileKind::ground_truth);
  SsdConfig ssd;
  ssd.model_path = test::source_path("models/ssdlite_mobilenet_v2_coco.onnx");
  ssd.backend = BackendRequest::cpu;
  ssd.max_batch = 1;
  TilingConfig tiling;      // the defaults, which a run's are (runner/tiling_choice.cpp)
  tiling.automatic = true;  // what auto cuts 1920 x 1080 into
  TilingDetector tiled(std::make_unique<SsdDetector>(ssd), tiling);
  SsdDetector whole(ssd);
  Matches untiled_total;
  Matches tiled_total;
  for (const int frame : kFrames) {
    char name[16];
    std::snprintf(name, sizeof name, "%06d.jpg", frame);
    const cv::Mat image = cv::imread((folder / "img1" / name).string(), cv::IMREAD_COLOR);
    ASSERT_FALSE(image.empty()) << folder / "img1" / name;
    std::vector<tracker::Box> people;
    for (const auto& row : rows) {
      if (row.frame == frame && row.conf != 0.F) people.push_back(row.box);
    }
    std::vector<tracker::Detection> boxes;
    whole.detect(image, frame, boxes);
    const Matches u = match(boxes, people);
    tiled.detect(image, frame, boxes);
    const Matches t = match(boxes, people);
    std::printf("frame %d: %d people; untiled %d of %d boxes on a person, tiled %d of %d\n", frame,
                u.people, u.found, u.reported, t.found, t.reported);
    untiled_total.found += u.found;
    untiled_total.reported += u.reported;
    tiled_total.found += t.found;
    tiled_total.reported += t.reported;
    untiled_total.people += u.people;
  }
  ASSERT_GT(untiled_total.people, 0);
  EXPECT_GE(tiled_total.found, untiled_total.found + kTiledMargin) << "tiles found no more people";
  const double untiled_precision =
      static_cast<double>(untiled_total.found) / untiled_total.reported;
  const double tiled_precision = static_cast<double>(tiled_total.found) / tiled_total.reported;
  EXPECT_GE(tiled_precision, untiled_precision - kPrecisionSlack);
}

}  // namespace
}  // namespace rtmot::detector
