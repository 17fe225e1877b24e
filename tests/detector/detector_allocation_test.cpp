// Steady-state allocation of the detectors' per-frame paths, counted by replacing the global
// operator new in this executable (its own binary, so no other test is affected).
#include <gtest/gtest.h>

#include <algorithm>
#include <opencv2/core/version.hpp>
#include <vector>

#include "allocation_counter.hpp"
#include "detector/replay_detector.hpp"
#include "detector/ssd_detector.hpp"
#include "detector/ssd_postprocess.hpp"
#include "detector/tiling_detector.hpp"
#include "opencv_pool_warmup.hpp"
#include "shared_data.hpp"
#include "vision/appearance_detector.hpp"
#include "vtest_frames.hpp"

#if RTMOT_HAVE_XNNPACK
#include <unistd.h>
#include <xnnpack.h>

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "detector/coco_labels.hpp"
#include "detector/xnnpack_network.hpp"
#endif

namespace rtmot::detector {
namespace {

// What OpenCV's forward() takes from operator new beyond small bookkeeping, per image of the batch.
// OpenCV 4.6 (Debian): nothing. OpenCV 4.7+ (the pinned 4.10): its new convolution layers take a
// scratch buffer in a std::vector every pass, measured 3,257,984 bytes for one image and 13,003,904
// for four: ours to know, not to fix. What must hold either way: the same every frame, and nothing
// of our own the size of an image.
#if CV_VERSION_MAJOR > 4 || (CV_VERSION_MAJOR == 4 && CV_VERSION_MINOR >= 7)
constexpr std::size_t kOpenCvScratchPerImage = 3'500'000;
#else
constexpr std::size_t kOpenCvScratchPerImage = 0;
#endif
constexpr std::size_t kImageBytes = 300U * 300U * 3U;

TEST(DetectorAllocation, PostprocessingAllocatesNothingInSteadyState) {
  // Many candidates in several classes, so sorting and NMS do real work.
  std::vector<Anchor> anchors;
  for (int i = 0; i < 400; ++i) anchors.push_back({0.3F + 0.001F * i, 0.5F, 0.2F, 0.1F});
  constexpr int kClasses = 5;
  std::vector<float> boxes(anchors.size() * 4, 0.F);
  std::vector<float> logits(anchors.size() * kClasses);
  for (std::size_t i = 0; i < logits.size(); ++i) logits[i] = static_cast<float>(i % 7) - 3.F;
  SsdPostprocessor post(anchors, kClasses, {0.3F, 0.6F, 100, {}});
  std::vector<tracker::Detection> out;
  post.run(boxes.data(), logits.data(), 640, 480, out);  // `out` grows once
  ASSERT_FALSE(out.empty());
  const test::CountingScope counting;
  for (int i = 0; i < 10; ++i) post.run(boxes.data(), logits.data(), 640, 480, out);
  EXPECT_EQ(counting.allocations(), 0);
}

// Two boxes in every image it is given: one at its centre, one against its right edge (cut, in a
// tile), so that the merge joins, suppresses and keeps.
class TwoBoxes : public Detector {
 public:
  void detect(const cv::Mat& image, std::int64_t, std::vector<tracker::Detection>& out) override {
    const auto w = static_cast<float>(image.cols);
    const auto h = static_cast<float>(image.rows);
    out.clear();
    out.push_back({{w / 2.F - 20.F, h / 2.F - 40.F, 40.F, 80.F}, 0.9F, 1});
    out.push_back({{w - 30.F, h / 4.F, 30.F, 90.F}, 0.6F, 1});
  }
  std::string describe() const override { return "two boxes"; }
};

TEST(DetectorAllocation, TilingAllocatesNothingInSteadyState) {
  TilingConfig config;
  config.grid = {4, 2, 0.2F};
  TilingDetector tiling(std::make_unique<TwoBoxes>(), config);
  const cv::Mat frame(1080, 1920, CV_8UC3, cv::Scalar::all(0));
  std::vector<tracker::Detection> out;
  tiling.detect(frame, 1, out);  // plans the size's tiles, grows the buffers
  tiling.detect(frame, 2, out);
  ASSERT_GE(out.size(), 9U);
  const test::CountingScope counting;
  for (int i = 0; i < 10; ++i) tiling.detect(frame, 3 + i, out);
  EXPECT_EQ(counting.allocations(), 0);
}

TEST(DetectorAllocation, AppearanceAllocatesNothingInSteadyState) {
  vision::AppearanceDetector appearance(std::make_unique<TwoBoxes>());
  cv::Mat frame(576, 768, CV_8UC3);
  cv::randu(frame, cv::Scalar::all(0), cv::Scalar::all(255));
  std::vector<tracker::Detection> out;
  appearance.detect(frame, 1, out);  // its HSV buffer takes the frame's size
  ASSERT_EQ(out.size(), 2U);
  ASSERT_TRUE(out[0].appearance.valid);
  const test::CountingScope counting;
  for (int i = 0; i < 10; ++i) appearance.detect(frame, 2 + i, out);
  EXPECT_EQ(counting.allocations(), 0);
}

TEST(DetectorAllocation, ReplayAllocatesNothingInSteadyState) {
  const auto path = test::shared_path("data/mot15-train/TUD-Campus/det/det.txt");
  RTMOT_REQUIRE_FILE(path);
  ReplayDetector replay(path);
  std::vector<tracker::Detection> out;
  out.reserve(256);
  const test::CountingScope counting;
  for (int frame = 1; frame <= replay.last_frame(); ++frame) replay.detect(cv::Mat(), frame, out);
  EXPECT_EQ(counting.allocations(), 0);
}

TEST(DetectorAllocation, SsdAllocatesNoImageBuffersPerFrame) {
  const auto model = test::source_path("models/ssdlite_mobilenet_v2_coco.onnx");
  if (!std::filesystem::exists(model)) {
    FAIL() << "missing model " << model << ": run scripts/fetch_model.sh";
  }
  const auto frames = test::vtest_frames({1});
  ASSERT_EQ(frames.size(), 1U);
  const cv::Mat& image = frames.at(1);
  SsdConfig config;
  config.model_path = model;
  config.backend = BackendRequest::cpu;
  config.threads = 1;
  SsdDetector detector(config);
  std::vector<tracker::Detection> out;
  detector.detect(image, 1, out);
  ASSERT_TRUE(test::run_a_task_on_every_opencv_pool_thread()) << "an OpenCV pool thread never ran";
  long counts[2] = {0, 0};
  std::size_t largest = 0;
  for (long& count : counts) {
    const test::CountingScope counting;
    detector.detect(image, 2, out);
    count = counting.allocations();
    largest = counting.largest();
  }
  // operator new sees OpenCV's C++ containers, not cv::Mat data (cv::fastMalloc). What it sees:
  // forward()'s per-layer bookkeeping (and 4.7+'s convolution scratch, above) and cv::resize's
  // tables, the same every frame.
  std::cout << "SsdDetector::detect: " << counts[1] << " allocations, largest " << largest
            << " bytes\n";
  EXPECT_EQ(counts[0], counts[1]);
  EXPECT_LT(largest, kImageBytes + kOpenCvScratchPerImage);
}

TEST(DetectorAllocation, SsdBatchAllocatesNoImageBuffersPerBatch) {
  const auto model = test::source_path("models/ssdlite_mobilenet_v2_coco.onnx");
  if (!std::filesystem::exists(model)) {
    FAIL() << "missing model " << model << ": run scripts/fetch_model.sh";
  }
  const auto frames = test::vtest_frames({1, 51, 101, 151});
  ASSERT_EQ(frames.size(), 4U);
  std::vector<const cv::Mat*> images;
  std::vector<std::int64_t> numbers;
  for (const auto& [number, image] : frames) {
    images.push_back(&image);
    numbers.push_back(number);
  }
  SsdConfig config;
  config.model_path = model;
  config.backend = BackendRequest::cpu;
  config.threads = 1;
  config.max_batch = 4;
  SsdDetector detector(config);
  std::vector<std::vector<tracker::Detection>> out;
  detector.detect_batch(images.data(), numbers.data(), 4, out);  // `out` grows once
  ASSERT_TRUE(test::run_a_task_on_every_opencv_pool_thread()) << "an OpenCV pool thread never ran";
  long counts[2] = {0, 0};
  std::size_t largest = 0;
  for (long& count : counts) {
    const test::CountingScope counting;
    detector.detect_batch(images.data(), numbers.data(), 4, out);
    count = counting.allocations();
    largest = counting.largest();
  }
  // As for one image: OpenCV's per-layer bookkeeping and cv::resize's tables, the same every
  // batch, nothing the size of an image; our own buffers (blob, views, outputs) are reused.
  std::cout << "SsdDetector::detect_batch(4): " << counts[1] << " allocations, largest " << largest
            << " bytes\n";
  EXPECT_EQ(counts[0], counts[1]);
  EXPECT_LT(largest, kImageBytes + 4 * kOpenCvScratchPerImage);
}

#if RTMOT_HAVE_XNNPACK
// XNNPACK allocates with malloc/posix_memalign through its own allocator table, which operator
// new never sees: counted here by handing XNNPACK a counting table (the same functions as its
// default one, so blocks allocated before stay compatible).
std::atomic<long> xnnpack_allocations{0};

void* xnn_counted(void* /*context*/, std::size_t size) {
  ++xnnpack_allocations;
  return std::malloc(size);
}
void* xnn_counted_realloc(void* /*context*/, void* pointer, std::size_t size) {
  ++xnnpack_allocations;
  return std::realloc(pointer, size);
}
void xnn_free(void* /*context*/, void* pointer) {
  std::free(pointer);
}
void* xnn_counted_aligned(void* /*context*/, std::size_t alignment, std::size_t size) {
  ++xnnpack_allocations;
  void* pointer = nullptr;
  return posix_memalign(&pointer, alignment, size) == 0 ? pointer : nullptr;
}

// fp32 and int8 (the int8 engine's converts and requantization must not allocate either).
void expect_no_xnnpack_allocation_in_steady_state(BackendRequest backend) {
  const auto model = test::source_path("models/ssdlite_mobilenet_v2_coco.onnx");
  if (!std::filesystem::exists(model)) {
    FAIL() << "missing model " << model << ": run scripts/fetch_model.sh";
  }
  const auto frames = test::vtest_frames({1, 51, 101, 151});
  ASSERT_EQ(frames.size(), 4U);
  std::vector<const cv::Mat*> images;
  std::vector<std::int64_t> numbers;
  for (const auto& [number, image] : frames) {
    images.push_back(&image);
    numbers.push_back(number);
  }
  SsdConfig config;
  config.model_path = model;
  config.backend = backend;
  config.int8_ranges = test::source_path("configs/int8/ssdlite_mobilenet_v2_coco.ranges");
  config.threads = 2;  // the thread pool's hand-over must not allocate either
  config.max_batch = 4;
  SsdDetector detector(config);
  std::vector<tracker::Detection> one;
  std::vector<std::vector<tracker::Detection>> many;
  detector.detect(*images[0], 1, one);                            // the outputs grow once
  detector.detect_batch(images.data(), numbers.data(), 4, many);  // every slot used once
  ASSERT_TRUE(test::run_a_task_on_every_opencv_pool_thread()) << "an OpenCV pool thread never ran";
  // After start-up (which initialized XNNPACK): every later XNNPACK allocation is counted.
  const xnn_allocator counting{nullptr,   &xnn_counted,         &xnn_counted_realloc,
                               &xnn_free, &xnn_counted_aligned, &xnn_free};
  ASSERT_EQ(xnn_initialize(&counting), xnn_status_success);
  // The batch's images are preprocessed on OpenCV's thread pool, so which thread resizes which
  // image, and in which frame a pool thread gets its first task, is the scheduler's choice: on a
  // loaded 2-core CI machine a worker first ran in a counted frame and added its per-thread state
  // (3 blocks, once). So: every frame in which no thread allocated for the first time allocates
  // the same (cv::resize's two tables per image), and a first-time thread's frame only adds to it.
  // A thread that allocated before but never ran a pool task adds its RNG slot on its first task:
  // every pool thread ran one above (opencv_pool_warmup.hpp).
  constexpr int kFrames = 6;
  long steady = -1;  // the count of the first frame without a first-time thread
  std::size_t largest = 0;
  xnnpack_allocations = 0;
  for (int frame = 0; frame < kFrames; ++frame) {
    const test::CountingScope counting_new;
    detector.detect(*images[1], 2, one);
    detector.detect_batch(images.data(), numbers.data(), 4, many);
    detector.detect_batch(images.data(), numbers.data(), 2, many);
    const long count = counting_new.allocations();
    largest = std::max(largest, counting_new.largest());
    std::cout << "xnnpack detect + detect_batch(4) + detect_batch(2), frame " << frame << ": "
              << count << " operator new allocations, " << counting_new.new_threads()
              << " first-time threads (largest " << counting_new.largest() << " bytes)\n";
    if (counting_new.new_threads() > 0) continue;
    if (steady < 0) steady = count;
    EXPECT_EQ(count, steady) << "frame " << frame;
  }
  EXPECT_GE(steady, 0) << "every frame had a first-time thread: nothing steady was seen";
  std::cout << xnnpack_allocations.load() << " XNNPACK allocations\n";
  EXPECT_EQ(xnnpack_allocations.load(), 0);
  EXPECT_LT(largest, kImageBytes);
}

TEST(DetectorAllocation, XnnpackAllocatesNothingInSteadyState) {
  if (!xnnpack_runs_here()) GTEST_SKIP() << "XNNPACK does not initialize on this processor";
  expect_no_xnnpack_allocation_in_steady_state(BackendRequest::xnnpack);
}

TEST(DetectorAllocation, XnnpackInt8AllocatesNothingInSteadyState) {
  if (!xnnpack_runs_here()) GTEST_SKIP() << "XNNPACK does not initialize on this processor";
  expect_no_xnnpack_allocation_in_steady_state(BackendRequest::xnnpack_int8);
}

// The host-side decoding tail (xnnpack_decoding_tail.hpp) of a decoded-layout model, pytorch-ssd's
// interface made from the bundled model by make_model_fixture.py: after the first passes, a pass
// of the network and its tail allocates nothing, at batch 1 and 2, on either allocator.
TEST(DetectorAllocation, XnnpackDecodingTailAllocatesNothingInSteadyState) {
  if (!xnnpack_runs_here()) GTEST_SKIP() << "XNNPACK does not initialize on this processor";
  const auto model = test::source_path("models/ssdlite_mobilenet_v2_coco.onnx");
  if (!std::filesystem::exists(model)) {
    FAIL() << "missing model " << model << ": run scripts/fetch_model.sh";
  }
  const auto dir = std::filesystem::temp_directory_path() /
                   ("rtmot-allocation-tail-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  {
    std::ofstream labels(dir / "coco.txt");
    for (int id = 0; id <= kCocoMaxClassId; ++id) labels << coco_label(id) << '\n';
  }
  const char* python = std::getenv("PYTHON");
  const std::string command =
      std::string(python != nullptr ? python : "/usr/bin/python3") + " " +
      test::source_path("tests/detector/make_model_fixture.py").string() + " " + model.string() +
      " " + test::source_path("models/ssdlite_mobilenet_v2_coco.anchors.csv").string() + " " +
      (dir / "coco.txt").string() + " " + (dir / "decoded").string();
  ASSERT_EQ(std::system(command.c_str()), 0) << "make_model_fixture.py (python3-onnx, numpy)";
  XnnpackNetworkConfig config;
  config.model_path = dir / "decoded.onnx";
  config.box_output = "boxes";
  config.logit_output = "scores";
  config.threads = 1;
  config.max_batch = 2;
  XnnpackNetwork network(config);
  std::filesystem::remove_all(dir);
  EXPECT_NE(network.summary().find("decoding tail"), std::string::npos) << network.summary();
  network.run(1);
  network.run(2);
  const xnn_allocator counting{nullptr,   &xnn_counted,         &xnn_counted_realloc,
                               &xnn_free, &xnn_counted_aligned, &xnn_free};
  ASSERT_EQ(xnn_initialize(&counting), xnn_status_success);
  xnnpack_allocations = 0;
  const test::CountingScope counting_new;
  for (int pass = 0; pass < 3; ++pass) {
    network.run(1);
    network.run(2);
  }
  EXPECT_EQ(counting_new.allocations(), 0);
  EXPECT_EQ(xnnpack_allocations.load(), 0);
  // Decoded, not garbage: corners in 0..1-ish and probabilities.
  EXPECT_EQ(network.anchors(), 1917U);
  EXPECT_EQ(network.classes(), 91U);
  EXPECT_GE(network.logits()[0], 0.F);
  EXPECT_LE(network.logits()[0], 1.F);
}
#endif

}  // namespace
}  // namespace rtmot::detector
