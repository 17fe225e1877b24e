// The SSD on N images per forward pass (Detector::detect_batch), per backend, side by side in one
// process: for each thread count and batch size it builds one detector per backend and then calls
// them in turn, call by call, so a shared or loaded machine's drift hits every backend alike. It
// times detect_batch() over vtest.avi frames held in memory and, inside it, the forward pass alone
// (SsdDetector::last_forward_ns) and the preprocessing of the call's images (last_preprocess_ns,
// "pre med": the batch's images in parallel on OpenCV's pool, so --threads 1 shows them serial),
// and prints min / median (and the forward's p99) per batch and per image, and each backend's
// median forward pass relative to the first backend's. Not Google Benchmark: the numbers wanted are
// the min and median of individual calls, per image, for a table (docs/gpu.md,
// docs/cpu-detector.md).
//
// Run: detector_batch_bench [--backends cpu,xnnpack,xnnpack-int8,cuda,cuda-fp16] [--batches
// 1,2,4,8]
//                           [--threads 1,2] [--iterations N] [--model PATH] [--vary]
//                           [--tiles off,3x2]
// Backends default to every one this build has (cpu is OpenCV DNN; a backend the machine lacks is
// reported and skipped); threads default to 1,2 (0: OpenCV's default and one XNNPACK worker per
// core).
// --vary: every other call one image short (batch, batch - 1, batch, ...), as a multi-source
// pipeline's batches are when a camera is late: shows what OpenCV's re-planning on a change of
// input shape costs.
// --tiles: each frame seen whole and in that grid's tiles (detector/tiling_detector.hpp, as
// `detector.tiles` in a run), the batch counting frames: the forward pass then takes batch x
// (tiles + 1) images, and "img med" is the cost of a frame with its tiles (docs/tiling.md). With
// RTMOT_BENCH_FRAMES=images://.../ADL-Rundle-6/img1 the frames are HD.
// Frames: RTMOT_BENCH_FRAMES=URI (e.g. images://DIR), else ../shared/data/video/vtest.avi through
// GStreamer.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <opencv2/core/version.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "bench_frames.hpp"
#include "common/input_error.hpp"
#include "detector/ssd_detector.hpp"
#include "detector/tile_request.hpp"
#include "detector/tiling_detector.hpp"
#include "detector/xnnpack_network.hpp"
#include "platform/log_setup.hpp"

namespace {

using rtmot::detector::BackendRequest;
using rtmot::detector::Fp16Request;

std::vector<std::string> built_backends() {
  std::vector<std::string> names{"cpu"};
  if (rtmot::detector::xnnpack_built()) {
    names.emplace_back("xnnpack");
    names.emplace_back("xnnpack-int8");
  }
  names.emplace_back("cuda");
  names.emplace_back("cuda-fp16");
  return names;
}

struct Options {
  std::vector<std::string> backends{built_backends()};
  std::vector<int> batches{1, 2, 4, 8};
  int iterations{30};
  std::vector<int> threads{1, 2};
  std::string model{RTMOT_MODEL_PATH};
  bool vary{false};
  std::vector<rtmot::detector::TileRequest> tiles{{rtmot::detector::TileMode::off, 1, 1}};
};

std::vector<std::string> split(const std::string& text) {
  std::vector<std::string> parts;
  std::stringstream in(text);
  std::string part;
  while (std::getline(in, part, ',')) {
    if (!part.empty()) parts.push_back(part);
  }
  return parts;
}

Options parse(int argc, char** argv) {
  Options options;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const bool has_value = i + 1 < argc;
    if (arg == "--backends" && has_value) {
      options.backends = split(argv[++i]);
    } else if (arg == "--batches" && has_value) {
      options.batches.clear();
      for (const auto& b : split(argv[++i])) options.batches.push_back(std::stoi(b));
    } else if (arg == "--iterations" && has_value) {
      options.iterations = std::stoi(argv[++i]);
    } else if (arg == "--threads" && has_value) {
      options.threads.clear();
      for (const auto& t : split(argv[++i])) options.threads.push_back(std::stoi(t));
    } else if (arg == "--model" && has_value) {
      options.model = argv[++i];
    } else if (arg == "--vary") {
      options.vary = true;
    } else if (arg == "--tiles" && has_value) {
      options.tiles.clear();
      for (const auto& t : split(argv[++i])) {
        std::string problem;
        const auto request = rtmot::detector::parse_tile_request(t, problem);
        if (!request || request->mode == rtmot::detector::TileMode::automatic) {
          std::cerr << "detector_batch_bench: --tiles " << t << ": off or a grid, e.g. 3x2\n";
          std::exit(2);
        }
        options.tiles.push_back(*request);
      }
    } else {
      std::cerr
          << "usage: detector_batch_bench [--backends cpu,xnnpack,xnnpack-int8,cuda,cuda-fp16] "
             "[--batches 1,2,4,8] [--threads 1,2] [--iterations N] [--model PATH] "
             "[--vary] [--tiles off,3x2]\n";
      std::exit(2);
    }
  }
  return options;
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

// Nearest rank: of fewer than 100 calls, the slowest.
double p99(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const auto rank = static_cast<std::size_t>(std::ceil(0.99 * static_cast<double>(values.size())));
  return values[std::max<std::size_t>(rank, 1) - 1];
}

double minimum(const std::vector<double>& values) {
  return *std::min_element(values.begin(), values.end());
}

}  // namespace

struct Run {
  std::string backend;
  std::unique_ptr<rtmot::detector::Detector> detector;
  const rtmot::detector::SsdDetector* ssd;  // the detector, or the one its tiles go through
  std::vector<double> call_ms;
  std::vector<double> forward_ms;
  std::vector<double> preprocess_ms;
};

std::unique_ptr<rtmot::detector::SsdDetector> make_ssd(const Options& options,
                                                       const std::string& backend, int threads,
                                                       int batch) {
  rtmot::detector::SsdConfig config;
  config.model_path = options.model;
  config.backend = backend == "xnnpack"        ? BackendRequest::xnnpack
                   : backend == "xnnpack-int8" ? BackendRequest::xnnpack_int8
                   : backend == "cpu"          ? BackendRequest::cpu
                                               : BackendRequest::cuda;
  // The model is named by absolute path here; its committed ranges too (the default is relative).
  if (options.model == RTMOT_MODEL_PATH) config.int8_ranges = RTMOT_INT8_RANGES_PATH;
  config.fp16 = backend == "cuda-fp16" ? Fp16Request::on : Fp16Request::off;
  config.threads = threads;
  config.max_batch = batch;
  return std::make_unique<rtmot::detector::SsdDetector>(config);
}

// The SSD alone, or wrapped in the tiles of `tiles` for frames of `width` x `height` (its batch
// then holds every tile of `batch` frames).
Run make_run(const Options& options, const std::string& backend, int threads, int batch,
             const rtmot::detector::TileRequest& tiles, int width, int height) {
  if (tiles.mode == rtmot::detector::TileMode::off) {
    auto ssd = make_ssd(options, backend, threads, batch);
    const auto* raw = ssd.get();
    return {backend, std::move(ssd), raw, {}, {}, {}};
  }
  rtmot::detector::TilingConfig tiling;
  tiling.grid = {tiles.columns, tiles.rows, tiling.grid.overlap};
  const auto passes = rtmot::detector::TilingDetector::plan_passes(width, height, tiling).size();
  auto ssd =
      make_ssd(options, backend, threads,
               std::min<int>(batch * static_cast<int>(passes), rtmot::detector::kMaxBatchLimit));
  const auto* raw = ssd.get();
  return {backend, std::make_unique<rtmot::detector::TilingDetector>(std::move(ssd), tiling),
          raw,     {},
          {},      {}};
}

int main(int argc, char** argv) {
  rtmot::platform::configure_logging(rtmot::platform::LogFormat::text, "");  // stderr: the table
  const Options options = parse(argc, argv);
  for (const auto& backend : options.backends) {
    if (backend != "cpu" && backend != "xnnpack" && backend != "xnnpack-int8" &&
        backend != "cuda" && backend != "cuda-fp16") {
      std::cerr << "detector_batch_bench: unknown backend '" << backend
                << "' (cpu, xnnpack, xnnpack-int8, cuda, cuda-fp16)\n";
      return 2;
    }
  }
  std::string error;
  const std::vector<cv::Mat> frames = rtmot::bench::load_bench_frames(16, 25, error);
  if (frames.empty()) {
    std::cerr << "detector_batch_bench: " << error << "\n";
    return 3;
  }
  std::printf(
      "frames: %zu of %s, %dx%d; %d timed calls per row after 3 warm-up calls, backends "
      "called in turn; OpenCV %s\n",
      frames.size(), rtmot::bench::bench_frames_uri().c_str(), frames[0].cols, frames[0].rows,
      options.iterations, CV_VERSION);
  std::printf("%-10s %7s %5s %5s | %9s %9s | %9s %9s %9s | %9s %9s | %8s | %6s | %8s\n", "backend",
              "threads", "batch", "tiles", "call min", "call med", "fwd min", "fwd med", "fwd p99",
              "img med", "fwd/img", "images/s", "fwd x", "pre med");
  for (const int threads : options.threads) {
    for (const int batch : options.batches) {
      for (const auto& tiles : options.tiles) {
        const std::string tiles_text = rtmot::detector::tile_request_text(tiles);
        std::vector<Run> runs;
        for (const std::string& backend : options.backends) {
          try {
            runs.push_back(
                make_run(options, backend, threads, batch, tiles, frames[0].cols, frames[0].rows));
            std::printf("# %s\n", runs.back().detector->describe().c_str());
          } catch (const rtmot::InputError& e) {
            std::printf("%-10s %7d %5d %5s | skipped: %s\n", backend.c_str(), threads, batch,
                        tiles_text.c_str(), e.what());
          }
        }
        std::vector<const cv::Mat*> images(static_cast<std::size_t>(batch));
        std::vector<std::int64_t> numbers(static_cast<std::size_t>(batch));
        std::vector<std::vector<rtmot::tracker::Detection>> out;
        std::size_t next = 0;
        for (int i = -3; i < options.iterations; ++i) {
          const int count = options.vary && batch > 1 && i % 2 != 0 ? batch - 1 : batch;
          for (int k = 0; k < count; ++k) {  // different frames in every call and slot
            images[static_cast<std::size_t>(k)] = &frames[next % frames.size()];
            numbers[static_cast<std::size_t>(k)] = static_cast<std::int64_t>(next % frames.size());
            ++next;
          }
          for (Run& run : runs) {  // the same images for every backend, in turn
            const auto start = std::chrono::steady_clock::now();
            run.detector->detect_batch(images.data(), numbers.data(), count, out);
            const double ms =
                std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                    .count();
            if (i < 0) continue;  // warm-up
            run.call_ms.push_back(ms);
            run.forward_ms.push_back(static_cast<double>(run.ssd->last_forward_ns()) * 1e-6);
            run.preprocess_ms.push_back(static_cast<double>(run.ssd->last_preprocess_ns()) * 1e-6);
          }
        }
        // With --vary the calls hold batch - 0.5 images on average.
        const bool varied = options.vary && batch > 1;
        const double per_call = varied ? batch - 0.5 : batch;
        const std::string label = varied ? std::to_string(batch) + "/" + std::to_string(batch - 1)
                                         : std::to_string(batch);
        const double baseline = runs.empty() ? 0.0 : median(runs.front().forward_ms);
        for (const Run& run : runs) {
          const double call_median = median(run.call_ms);
          const double forward_median = median(run.forward_ms);
          std::printf(
              "%-10s %7d %5s %5s | %9.2f %9.2f | %9.2f %9.2f %9.2f | %9.2f %9.2f | %8.1f | %6.2f | "
              "%8.2f\n",
              run.backend.c_str(), threads, label.c_str(), tiles_text.c_str(), minimum(run.call_ms),
              call_median, minimum(run.forward_ms), forward_median, p99(run.forward_ms),
              call_median / per_call, forward_median / per_call, 1000.0 * per_call / call_median,
              baseline / forward_median, median(run.preprocess_ms));
        }
        for (const Run& run : runs) {
          const std::string pool = run.ssd->xnnpack_pool_use();
          if (!pool.empty()) std::printf("# %s pool: %s\n", run.backend.c_str(), pool.c_str());
        }
        std::fflush(stdout);
      }
    }
  }
  return 0;
}
