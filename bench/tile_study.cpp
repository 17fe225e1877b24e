// The tiling study's two steps (docs/tiling.md, "How the settings were chosen"); research code, the
// product never runs it.
//
//   tile_study dump --source URI --out RAW.csv [--grids 2x2,3x2] [--overlap 0.2] [--cut 0.1]
//                   [--backend xnnpack] [--threads N] [--frames N]
//     runs the SSD (score cut --cut, shape limits off) on every frame's whole picture and on the
//     tiles of each grid, and writes every box of every pass, in that pass's pixels:
//     frame,pass_x,pass_y,pass_w,pass_h,class,score,x,y,w,h
//   tile_study merge --raw RAW.csv --grid CxR|off [--overlap 0.2] [--cut 0.3] [--tile-cut 0.3]
//                    [--nms 0.5] [--containment 0.8] [--edge 0.02] [--tile-max-height 0.9]
//                    [--shapes on|off]
//     merges one grid's passes as the product's TilingDetector does and prints MOTChallenge
//     detection rows (frame,-1,x,y,w,h,score,-1,-1,-1) for `rtmot track`.
//   tile_study draw --source URI --frame N --before DET.txt --after DET.txt --out IMAGE [--gt
//   GT.txt]
//                   [--scale S]
//     draws frame N with two merges' boxes: before in red, after in green (thicker), the ground
//     truth in thin white: the picture of docs/tiling.md.
// Dumping once and merging many times lets the merge settings be swept in seconds.
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "detector/box_plausibility.hpp"
#include "detector/ssd_detector.hpp"
#include "detector/tile_layout.hpp"
#include "detector/tile_merge.hpp"
#include "detector/tiling_detector.hpp"
#include "platform/video_source.hpp"

namespace {

using rtmot::detector::PixelRect;
using rtmot::detector::TileGrid;
using rtmot::tracker::Detection;

std::map<std::string, std::string> parse(int argc, char** argv, int first) {
  std::map<std::string, std::string> options;
  for (int i = first; i + 1 < argc; i += 2) options[argv[i]] = argv[i + 1];
  return options;
}

std::string get(const std::map<std::string, std::string>& o, const std::string& key,
                const std::string& fallback) {
  const auto it = o.find(key);
  return it == o.end() ? fallback : it->second;
}

TileGrid parse_grid(const std::string& text, float overlap) {
  TileGrid grid;
  grid.overlap = overlap;
  if (text == "off") return grid;
  const auto x = text.find('x');
  grid.columns = std::stoi(text.substr(0, x));
  grid.rows = std::stoi(text.substr(x + 1));
  return grid;
}

std::vector<std::string> split(const std::string& text) {
  std::vector<std::string> parts;
  std::stringstream in(text);
  std::string part;
  while (std::getline(in, part, ',')) parts.push_back(part);
  return parts;
}

int dump(const std::map<std::string, std::string>& o) {
  rtmot::detector::SsdConfig ssd;
  ssd.score_threshold = std::stof(get(o, "--cut", "0.1"));
  ssd.backend = get(o, "--backend", "xnnpack") == "cpu" ? rtmot::detector::BackendRequest::cpu
                                                        : rtmot::detector::BackendRequest::xnnpack;
  ssd.threads = std::stoi(get(o, "--threads", "0"));
  ssd.plausible_shapes = false;
  ssd.model_path = get(o, "--model", ssd.model_path.string());
  rtmot::detector::SsdDetector detector(ssd);
  const float overlap = std::stof(get(o, "--overlap", "0.2"));
  std::vector<TileGrid> grids;
  for (const auto& g : split(get(o, "--grids", "2x2,3x2"))) grids.push_back(parse_grid(g, overlap));
  const int max_frames = std::stoi(get(o, "--frames", "1000000"));
  auto source = rtmot::platform::open_video_source(get(o, "--source", ""));
  std::ofstream out(get(o, "--out", "raw.csv"));
  cv::Mat frame;
  rtmot::platform::FrameInfo info;
  std::vector<Detection> boxes;
  for (int number = 1; number <= max_frames; ++number) {
    if (source->read(frame, info) != rtmot::platform::ReadStatus::frame) break;
    std::vector<PixelRect> passes{{0, 0, frame.cols, frame.rows}};
    for (const TileGrid& grid : grids) {
      for (const PixelRect& r : rtmot::detector::tile_rects(frame.cols, frame.rows, grid)) {
        bool seen = false;
        for (const PixelRect& p : passes) seen = seen || p == r;
        if (!seen) passes.push_back(r);
      }
    }
    for (const PixelRect& r : passes) {
      detector.detect(frame(cv::Rect(r.x, r.y, r.width, r.height)), number, boxes);
      for (const Detection& d : boxes) {
        out << number << ',' << r.x << ',' << r.y << ',' << r.width << ',' << r.height << ','
            << d.class_id << ',' << d.score << ',' << d.box.x << ',' << d.box.y << ',' << d.box.w
            << ',' << d.box.h << '\n';
      }
    }
    if (number % 50 == 0) std::cerr << "frame " << number << "\n";
  }
  out.close();
  return out ? 0 : 1;
}

// A comma-separated line of numbers (the dump's rows, MOTChallenge rows). Research input written
// by this tool or the benchmark: a malformed one stops the tool (std::stof throws).
std::vector<float> numbers_of(const std::string& line) {
  std::stringstream fields(line);
  std::string field;
  std::vector<float> numbers;
  while (std::getline(fields, field, ',')) numbers.push_back(std::stof(field));
  return numbers;
}

struct RawRow {
  PixelRect pass;
  Detection detection;
};

int merge(const std::map<std::string, std::string>& o) {
  const float overlap = std::stof(get(o, "--overlap", "0.2"));
  const TileGrid grid = parse_grid(get(o, "--grid", "off"), overlap);
  const float cut = std::stof(get(o, "--cut", "0.3"));
  const bool shapes = get(o, "--shapes", "on") == "on";
  rtmot::detector::TileMergeConfig config;
  config.tile_score_threshold = std::stof(get(o, "--tile-cut", "0.3"));
  config.nms_iou = std::stof(get(o, "--nms", "0.5"));
  config.containment = std::stof(get(o, "--containment", "0.8"));
  config.edge_margin = std::stof(get(o, "--edge", "0.02"));
  config.tile_max_height = std::stof(get(o, "--tile-max-height", "0.9"));
  rtmot::detector::TileMerger merger(config);
  std::map<int, std::vector<RawRow>> frames;
  int width = 0;
  int height = 0;
  std::ifstream in(get(o, "--raw", "raw.csv"));
  std::string line;
  while (std::getline(in, line)) {
    const std::vector<float> v = numbers_of(line);
    RawRow row{{static_cast<int>(v[1]), static_cast<int>(v[2]), static_cast<int>(v[3]),
                static_cast<int>(v[4])},
               {{v[7], v[8], v[9], v[10]}, v[6], static_cast<int>(v[5])}};
    if (row.pass.x == 0 && row.pass.y == 0) {
      width = std::max(width, row.pass.width);
      height = std::max(height, row.pass.height);
    }
    frames[static_cast<int>(v[0])].push_back(row);
  }
  std::vector<PixelRect> passes{{0, 0, width, height}};
  if (grid.tiled()) {
    for (const PixelRect& r : rtmot::detector::tile_rects(width, height, grid)) passes.push_back(r);
  }
  std::vector<std::vector<Detection>> per_pass(passes.size());
  std::vector<Detection> merged;
  for (const auto& [number, rows] : frames) {
    for (auto& p : per_pass) p.clear();
    for (const RawRow& row : rows) {
      const Detection& d = row.detection;
      const bool whole = row.pass == passes[0];
      if (d.score < (whole ? cut : std::min(cut, config.tile_score_threshold))) continue;
      if (shapes && !rtmot::detector::plausible_shape(d.class_id, d.box.w, d.box.h)) continue;
      for (std::size_t i = 0; i < passes.size(); ++i) {
        if (row.pass == passes[i]) per_pass[i].push_back(d);
      }
    }
    // Greedy NMS decides the boxes above a cut alike whatever lower boxes it saw, so the dump's
    // lower cut changes nothing above --cut; but here the shape limits come after the SSD's NMS
    // (in the product, before it): an implausible box may have suppressed one that the product
    // keeps.
    merger.merge(passes.data(), per_pass.data(), static_cast<int>(passes.size()), merged);
    for (const Detection& d : merged) {
      std::printf("%d,-1,%.2f,%.2f,%.2f,%.2f,%.4f,-1,-1,-1\n", number, d.box.x, d.box.y, d.box.w,
                  d.box.h, d.score);
    }
  }
  return 0;
}

// The boxes of frame `number` in a MOTChallenge file (det.txt or gt.txt: x, y, w, h in columns
// 3..6; gt rows of confidence 0 are not people to find).
std::vector<cv::Rect> boxes_of(const std::string& path, int number, bool ground_truth) {
  std::vector<cv::Rect> boxes;
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    const std::vector<float> v = numbers_of(line);
    if (static_cast<int>(v[0]) != number || (ground_truth && v[6] == 0.F)) continue;
    boxes.emplace_back(static_cast<int>(v[2]), static_cast<int>(v[3]), static_cast<int>(v[4]),
                       static_cast<int>(v[5]));
  }
  return boxes;
}

int draw(const std::map<std::string, std::string>& o) {
  const int wanted = std::stoi(get(o, "--frame", "1"));
  auto source = rtmot::platform::open_video_source(get(o, "--source", ""));
  cv::Mat frame;
  rtmot::platform::FrameInfo info;
  for (int number = 1; number <= wanted; ++number) {
    if (source->read(frame, info) != rtmot::platform::ReadStatus::frame) {
      std::cerr << "tile_study: the source ends before frame " << wanted << "\n";
      return 1;
    }
  }
  const int thin = std::max(1, frame.cols / 960);
  if (o.count("--gt")) {
    for (const auto& r : boxes_of(o.at("--gt"), wanted, true)) {
      cv::rectangle(frame, r, cv::Scalar(255, 255, 255), thin);
    }
  }
  for (const auto& r : boxes_of(get(o, "--before", ""), wanted, false)) {
    cv::rectangle(frame, r, cv::Scalar(0, 0, 255), 3 * thin);
  }
  for (const auto& r : boxes_of(get(o, "--after", ""), wanted, false)) {
    cv::rectangle(frame, r + cv::Point(thin, thin), cv::Scalar(0, 255, 0), 2 * thin);
  }
  const double scale = std::stod(get(o, "--scale", "1"));
  if (scale != 1.0) cv::resize(frame, frame, cv::Size(), scale, scale, cv::INTER_AREA);
  return cv::imwrite(get(o, "--out", "frame.png"), frame) ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  spdlog::set_default_logger(spdlog::stderr_color_mt("tile_study"));
  const std::string mode = argc > 1 ? argv[1] : "";
  try {
    if (mode == "dump") return dump(parse(argc, argv, 2));
    if (mode == "merge") return merge(parse(argc, argv, 2));
    if (mode == "draw") return draw(parse(argc, argv, 2));
  } catch (const std::exception& e) {
    std::cerr << "tile_study: " << e.what() << "\n";
    return 1;
  }
  std::cerr << "usage: tile_study dump|merge|draw ... (see the comment at the top of "
               "bench/tile_study.cpp)\n";
  return 2;
}
