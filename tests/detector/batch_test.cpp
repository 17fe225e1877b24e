// Detector::detect_batch: the default (one detect() per image) and the SSD's one forward pass per
// batch must give, image for image, exactly what detect() gives; `out` keeps its entries.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "common/input_error.hpp"
#include "detector/ssd_detector.hpp"
#include "shared_data.hpp"
#include "vtest_frames.hpp"

namespace rtmot::detector {
namespace {

// Reports one box per image whose x is the frame number and whose width is the image's: enough to
// see which image and number went to which output.
class EchoDetector : public Detector {
 public:
  void detect(const cv::Mat& image, std::int64_t frame_number,
              std::vector<tracker::Detection>& out) override {
    out.clear();
    out.push_back(
        {{static_cast<float>(frame_number), 0.F, static_cast<float>(image.cols), 1.F}, 1.F, 1});
    ++calls;
  }
  std::string describe() const override { return "echo"; }
  int calls{0};
};

TEST(DetectBatch, DefaultRunsDetectPerImageInOrder) {
  EchoDetector detector;
  EXPECT_EQ(detector.max_batch(), 1);
  const cv::Mat a(10, 20, CV_8UC3);
  const cv::Mat b(10, 30, CV_8UC3);
  const cv::Mat c(10, 40, CV_8UC3);
  const cv::Mat* images[] = {&a, &b, &c};
  const std::int64_t numbers[] = {7, 8, 9};
  std::vector<std::vector<tracker::Detection>> out;
  detector.detect_batch(images, numbers, 3, out);
  ASSERT_EQ(out.size(), 3U);
  for (int i = 0; i < 3; ++i) {
    ASSERT_EQ(out[i].size(), 1U);
    EXPECT_EQ(out[i][0].box.x, static_cast<float>(numbers[i]));
    EXPECT_EQ(out[i][0].box.w, static_cast<float>(images[i]->cols));
  }
  EXPECT_EQ(detector.calls, 3);
}

TEST(DetectBatch, OutIsGrownNeverShrunk) {
  EchoDetector detector;
  const cv::Mat a(10, 20, CV_8UC3);
  const cv::Mat* images[] = {&a};
  const std::int64_t numbers[] = {5};
  std::vector<std::vector<tracker::Detection>> out(4);
  out[3].assign(2, tracker::Detection{});  // an entry beyond the batch keeps its contents
  detector.detect_batch(images, numbers, 1, out);
  ASSERT_EQ(out.size(), 4U);
  EXPECT_EQ(out[0].size(), 1U);
  EXPECT_EQ(out[3].size(), 2U);
}

TEST(DetectBatch, RejectsAnEmptyBatch) {
  EchoDetector detector;
  std::vector<std::vector<tracker::Detection>> out;
  EXPECT_THROW(detector.detect_batch(nullptr, nullptr, 0, out), std::invalid_argument);
}

// The real model on real frames: batches of 1..5 images (through max_batch 3, so 4 and 5 are
// split into two passes) equal detect() on each image.
TEST(DetectBatch, SsdBatchesEqualSingleImages) {
  const auto model = test::source_path("models/ssdlite_mobilenet_v2_coco.onnx");
  if (!std::filesystem::exists(model)) {
    FAIL() << "missing model " << model << ": run scripts/fetch_model.sh";
  }
  // Under emulation five earlier frames: decoding vtest.avi up to frame 401 is itself minutes
  // there.
  const auto frames = test::under_emulation() ? test::vtest_frames({1, 21, 41, 61, 81})
                                              : test::vtest_frames({1, 101, 201, 301, 401});
  ASSERT_EQ(frames.size(), 5U);
  SsdConfig config;
  config.model_path = model;
  config.backend = BackendRequest::cpu;
  config.score_threshold = 0.3F;
  config.max_batch = 3;
  SsdDetector detector(config);
  EXPECT_EQ(detector.max_batch(), 3);

  std::vector<const cv::Mat*> images;
  std::vector<std::int64_t> numbers;
  std::vector<std::vector<tracker::Detection>> single;
  for (const auto& [number, image] : frames) {
    images.push_back(&image);
    numbers.push_back(number);
    single.emplace_back();
    detector.detect(image, number, single.back());
  }
  std::vector<std::vector<tracker::Detection>> batched;
  // Under emulation (test::under_emulation(), ~15 s a forward) two of the five: one batch shorter
  // than max_batch, and one split into 3 + 2.
  const std::vector<int> counts =
      test::under_emulation() ? std::vector<int>{2, 5} : std::vector<int>{1, 2, 3, 4, 5};
  for (const int count : counts) {
    detector.detect_batch(images.data(), numbers.data(), count, batched);
    for (int i = 0; i < count; ++i) {
      const auto& a = single[static_cast<std::size_t>(i)];
      const auto& b = batched[static_cast<std::size_t>(i)];
      ASSERT_EQ(a.size(), b.size()) << "batch of " << count << ", image " << i;
      ASSERT_FALSE(a.empty()) << "vtest.avi frame " << numbers[i] << " has people";
      for (std::size_t k = 0; k < a.size(); ++k) {
        // The same network on the same pixels: equal up to the float summation order a larger
        // batch may choose in the convolutions.
        EXPECT_EQ(a[k].class_id, b[k].class_id);
        EXPECT_NEAR(a[k].score, b[k].score, 1e-4F);
        EXPECT_NEAR(a[k].box.x, b[k].box.x, 0.01F);
        EXPECT_NEAR(a[k].box.y, b[k].box.y, 0.01F);
        EXPECT_NEAR(a[k].box.w, b[k].box.w, 0.01F);
        EXPECT_NEAR(a[k].box.h, b[k].box.h, 0.01F);
      }
    }
  }
}

TEST(DetectBatch, MaxBatchOutOfRangeIsAUsageError) {
  for (const int bad : {0, -1, kMaxBatchLimit + 1}) {
    SsdConfig config;
    config.model_path = test::source_path("models/ssdlite_mobilenet_v2_coco.onnx");
    config.backend = BackendRequest::cpu;
    config.max_batch = bad;
    try {
      SsdDetector detector(config);
      ADD_FAILURE() << "max_batch " << bad << " accepted";
    } catch (const InputError& e) {
      EXPECT_EQ(e.exit_code(), ExitCode::usage) << e.what();
      EXPECT_EQ(e.field(), "max_batch") << e.what();
    }
  }
}

}  // namespace
}  // namespace rtmot::detector
