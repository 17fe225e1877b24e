// run_setup.hpp's detectors: the SSD or the replayed file, its threads, the lanes in flight, tiles
// (timed where auto must choose) and the appearance signature.
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <opencv2/core/utility.hpp>

#include "detector/dnn_backend.hpp"
#include "detector/replay_detector.hpp"
#include "detector/ssd_detector.hpp"
#include "detector/tiling_detector.hpp"
#include "motio/mot_files.hpp"
#include "runner/class_choice.hpp"
#include "runner/run_setup.hpp"
#include "runner/tiling_choice.hpp"
#include "tracker/score_scale.hpp"
#include "vision/appearance_detector.hpp"

namespace rtmot::runner {
namespace {

// A replayed detections file is cut twice on absolute scores: by the detector's score_threshold
// and by the tracker's own cuts. Both assume [0, 1] scores; a file on another scale gets one
// warning naming it and the range seen (tracker/score_scale.hpp). The SSD's scores are its own
// sigmoid in [0, 1], where its threshold was chosen, so it needs none.
void warn_on_score_scale(const DetectorConfig& detector, const tracker::TrackerConfig& tracker) {
  tracker::ScoreRange range;
  for (const auto& row : motio::read_mot_file(detector.det_file, motio::MotFileKind::detections))
    range.include(row.conf);
  tracker::TrackerConfig cuts = tracker;
  cuts.detection_threshold = std::max(cuts.detection_threshold, detector.score_threshold);
  if (const auto warning = tracker::score_scale_warning(cuts, range))
    spdlog::warn("{}: {} (detector.score_threshold {})", detector.det_file, *warning,
                 detector.score_threshold);
}

// `first`: the first of a run's detectors logs and warns; the lanes after it are alike.
// `images_per_pass`: the images one forward pass takes (the sources, times a frame's tiles).
std::unique_ptr<detector::Detector> build_detector(const RunConfig& config, bool first,
                                                   int images_per_pass) {
  const DetectorConfig& wanted = config.detector;
  if (wanted.kind == DetectorKind::replay) {
    auto replay =
        std::make_unique<detector::ReplayDetector>(wanted.det_file, wanted.score_threshold);
    if (first) warn_on_score_scale(wanted, config.tracker);
    return replay;
  }
  detector::SsdConfig ssd;
  ssd.model_path = wanted.model;
  ssd.anchors_path = wanted.anchors;
  ssd.int8_ranges = wanted.int8_ranges;
  ssd.score_threshold = wanted.score_threshold;
  ssd.nms_iou = wanted.nms_threshold;
  ssd.classes = resolve_classes(config, *run_labels(config));
  ssd.backend = wanted.backend;
  ssd.fp16 = wanted.fp16;
  ssd.plausible_shapes = wanted.plausible_shapes;
  // 0 ("automatic") is made explicit. Left to itself, a TBB build of OpenCV (Debian's, ours) runs
  // its DNN in TBB's automatic arena, sized by TBB: it ignores OpenCV's own OPENCV_FOR_THREADS_NUM
  // (measured) and, depending on the TBB version, a container's CPU quota (docker --cpus), so it
  // can run more workers than the CPUs we may use, and a layer split over them waits for its
  // slowest part. OpenCV's CPU count honours the affinity mask, cpusets and the cgroup quota; on a
  // machine without either both give the same count (measured: no difference on the 2-core CI
  // machine).
  // This is the one place that decides detector.threads, and the setting is process-wide
  // (cv::setNumThreads): made here, in the open. The detector gets the number decided, not 0:
  // its XNNPACK pool and backend auto's choice are sized by it (issue 32: handed 0, auto never
  // saw one thread).
  const int threads = wanted.threads > 0 ? wanted.threads : std::max(1, cv::getNumberOfCPUs());
  cv::setNumThreads(threads);
  ssd.threads = threads;
  if (first) {
    spdlog::info("detector threads: {}{}", threads,
                 wanted.threads > 0 ? "" : " (the CPUs this process may use)");
  }
  // One forward pass takes one frame of every source (the detect stage batches them), and with
  // tiles every tile of those frames: without this the SSD would split each batch again.
  ssd.max_batch = std::clamp(images_per_pass, 1, detector::kMaxBatchLimit);
  return std::make_unique<detector::SsdDetector>(ssd);
}

int source_count(const RunConfig& config) {
  return static_cast<int>(
      std::clamp<std::size_t>(source_list(config).size(), 1, detector::kMaxBatchLimit));
}

// The largest frame of the run's sources (by area), with its rate.
FrameShape largest_frame(const std::vector<platform::SourceInfo>& sources) {
  FrameShape frame;
  for (const platform::SourceInfo& info : sources) {
    if (static_cast<long long>(info.width) * info.height >
        static_cast<long long>(frame.width) * frame.height) {
      frame = {info.width, info.height, info.fps, info.live};
    }
  }
  for (const platform::SourceInfo& info : sources) frame.live = frame.live || info.live;
  return frame;
}

// The milliseconds of the middle of three calls (after one to warm up).
template <typename Call>
double median_ms(Call call) {
  std::vector<double> ms;
  call();
  for (int i = 0; i < 3; ++i) {
    const auto start = std::chrono::steady_clock::now();
    call();
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                     .count());
  }
  std::sort(ms.begin(), ms.end());
  return ms[1];
}

// A grey frame of this shape, cut into its passes (the network's work does not depend on the
// pixels), and what a detector takes for the first `count` of them in one batch.
class CostProbe {
 public:
  CostProbe(const FrameShape& frame, const std::vector<detector::PixelRect>& passes)
      : grey_(frame.height, frame.width, CV_8UC3, cv::Scalar::all(114)) {
    for (const detector::PixelRect& r : passes)
      views_.push_back(grey_(cv::Rect(r.x, r.y, r.width, r.height)));
    for (const cv::Mat& view : views_) images_.push_back(&view);
    numbers_.assign(images_.size(), 1);
  }
  double batch_ms(detector::Detector& ssd, std::size_t count) {
    return median_ms(
        [&] { ssd.detect_batch(images_.data(), numbers_.data(), static_cast<int>(count), out_); });
  }
  std::size_t passes() const { return images_.size(); }

 private:
  cv::Mat grey_;
  std::vector<cv::Mat> views_;
  std::vector<const cv::Mat*> images_;
  std::vector<std::int64_t> numbers_;
  std::vector<std::vector<tracker::Detection>> out_;
};

// The image's work is done only where the tracker will use it.
bool measures_appearance(const RunConfig& config) {
  const tracker::TrackerConfig& tracker = config.tracker;
  return config.detector.appearance && (tracker.appearance_weight > 0.0 ||
                                        tracker.appearance_gate < 1.0 || tracker.reid_gate > 0.0);
}

bool runs_on_cpu(const detector::Detector& detector) {
  const auto* ssd = dynamic_cast<const detector::SsdDetector*>(&detector);
  return ssd != nullptr && ssd->backend().backend != cv::dnn::DNN_BACKEND_CUDA;
}

}  // namespace

std::unique_ptr<detector::Detector> make_detector(const RunConfig& config) {
  auto built = build_detector(config, true, source_count(config));
  if (measures_appearance(config))
    built = std::make_unique<vision::AppearanceDetector>(std::move(built));
  return built;
}

std::vector<platform::SourceInfo> source_infos(const std::vector<pipeline::PipelineInput>& inputs) {
  std::vector<platform::SourceInfo> infos;
  for (const auto& input : inputs) infos.push_back(input.source->info());
  return infos;
}

std::vector<std::unique_ptr<detector::Detector>> make_detectors(
    const RunConfig& config, const std::vector<platform::SourceInfo>& sources) {
  const DetectorConfig& wanted = config.detector;
  const FrameShape frame = largest_frame(sources);
  const detector::TilingConfig tiling = tiling_config(wanted);
  // The passes of the largest frame if it is tiled: the SSD's batch is sized for them.
  const std::size_t tiled_passes =
      wanted.kind == DetectorKind::ssd && wanted.tiles.mode != detector::TileMode::off &&
              frame.width > 0 && frame.height > 0
          ? detector::TilingDetector::plan_passes(frame.width, frame.height, tiling).size()
          : 1;
  const int sources_per_pass = source_count(config);
  std::vector<std::unique_ptr<detector::Detector>> lanes;
  std::optional<DetectorCost> cost;
  if (tiled_passes > 1 && tiling_needs_measurement(wanted, config.playback.mode, frame)) {
    // Timed in two steps: the whole frame on a detector sized for it, then the tiled batch only
    // where the whole frame's cost leaves room for it (on the CPU it mostly does not, and building
    // and timing the batch took 2-3 s of start-up).
    lanes.push_back(build_detector(config, true, sources_per_pass));
    CostProbe probe(frame,
                    detector::TilingDetector::plan_passes(frame.width, frame.height, tiling));
    cost = DetectorCost{probe.batch_ms(*lanes.front(), 1), 0.0, false};
    if (tiled_cost_needs_timing(frame, cost->whole_ms, probe.passes(),
                                runs_on_cpu(*lanes.front()))) {
      lanes.front() =
          build_detector(config, false, sources_per_pass * static_cast<int>(tiled_passes));
      cost->tiled_ms = probe.batch_ms(*lanes.front(), probe.passes());
    } else {
      cost->tiled_ms = cpu_tiled_floor_ms(cost->whole_ms, probe.passes());
      cost->tiled_estimated = true;
    }
  } else {
    lanes.push_back(
        build_detector(config, true, sources_per_pass * static_cast<int>(tiled_passes)));
  }
  const TilingDecision decision = decide_tiling(wanted, config.playback.mode, frame, cost);
  const bool tiled = decision.tiled && tiled_passes > 1;
  spdlog::info("{}", decision.why);
  if (!tiled && tiled_passes > 1 && !(cost && cost->tiled_estimated)) {
    // Sized for tiles that will not be cut: its batch network would compute empty slots.
    lanes.front() = build_detector(config, false, sources_per_pass);
  }
  const auto lane_images = sources_per_pass * (tiled ? static_cast<int>(tiled_passes) : 1);
  const auto* ssd = dynamic_cast<const detector::SsdDetector*>(lanes.front().get());
  const bool cuda = ssd != nullptr && ssd->backend().backend == cv::dnn::DNN_BACKEND_CUDA;
  // auto: on CUDA the GPU runs one batch while the host prepares and decodes the others. Measured
  // on an H200, 8 sources, every frame, two passes (docs/gpu.md §3, "Batches in flight", the
  // batch's images preprocessed in parallel): 1 -> 2 -> 3 -> 4 lanes gave 1311-1567 -> 1890-2215
  // -> 1969-2464 -> 2357-2735 FPS on cuda, p99 12-16 -> 17-20 -> 19-24 -> 20-25 ms: 3 keeps p99
  // within what one lane had before the parallel preprocessing (24-25 ms). On cuda-fp16 the GPU
  // is the limit sooner: 840-934 -> 1193-1196 -> 1292-1301 -> 1390 FPS, GPU busy 53-59 -> 69-71
  // -> 74 -> 77-79 %, and p99 20-23 -> 29 -> 37 -> 45-46 ms: 2 lanes keep p99 within one lane's
  // before (28-32 ms) and stay above 900 FPS; a 3rd buys 8 % for 30 % more p99. At a camera rate
  // (8 x 60 fps) the lane count does not move p99 (8-13 ms). On the H100 (docs/gpu.md, "Three
  // lanes on cuda-fp16") 2 lanes left the GPU busy 65-69 % at 8 sources and 3 reached 71-72 %
  // (the 70 %) with 1235-1262 FPS and p99 37.6-38.4 ms, within what one lane had before
  // batches in flight (37.6-44.9 ms), and camera-rate p99 the same (12.7 against 12.2 ms): so 3
  // on fp16 as on fp32. Each lane holds its own networks and host thread. One on the CPU, where a
  // second lane only takes cores from the first's OpenCV threads (docs/gpu.md).
  const int automatic = cuda ? 3 : 1;
  const int in_flight = wanted.in_flight > 0 ? wanted.in_flight : automatic;
  // One after another: each loads, warms up and (CUDA) captures its graphs alone.
  while (static_cast<int>(lanes.size()) < in_flight) {
    lanes.push_back(build_detector(config, false, lane_images));
  }
  spdlog::info("detector: {} batch{} in flight{}", in_flight, in_flight == 1 ? "" : "es",
               config.detector.in_flight > 0 ? ""
               : cuda                        ? " (auto: CUDA)"
                                             : " (auto: not CUDA)");
  if (tiled) {
    for (auto& lane : lanes) {
      lane = std::make_unique<detector::TilingDetector>(std::move(lane), tiling);
    }
  }
  if (measures_appearance(config)) {
    for (auto& lane : lanes) lane = std::make_unique<vision::AppearanceDetector>(std::move(lane));
  }
  return lanes;
}

}  // namespace rtmot::runner
