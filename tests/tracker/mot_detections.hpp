#pragma once
// A tiny det.txt reader for the tracker's tests and bench: tracker/ must not depend on mot/, and
// these tests only need frame, box and score.
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "tracker/box.hpp"

namespace rtmot::test {

struct MotSequence {
  std::string name;
  double frame_rate{30.0};
  float width{1920.F};
  float height{1080.F};
  std::vector<std::vector<tracker::Detection>> frames;  // frames[f - 1] holds frame f
};

inline std::string ini_value(const std::filesystem::path& ini, const std::string& key) {
  std::ifstream in(ini);
  if (!in) throw std::runtime_error("cannot open " + ini.string());
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind(key + "=", 0) == 0) return line.substr(key.size() + 1);
  }
  throw std::runtime_error(ini.string() + ": no " + key);
}

/// Reads <sequence_dir>/seqinfo.ini and det/det.txt.
inline MotSequence load_mot_sequence(const std::filesystem::path& sequence_dir) {
  MotSequence sequence;
  const auto ini = sequence_dir / "seqinfo.ini";
  sequence.name = sequence_dir.filename().string();
  sequence.frame_rate = std::stod(ini_value(ini, "frameRate"));
  sequence.width = std::stof(ini_value(ini, "imWidth"));
  sequence.height = std::stof(ini_value(ini, "imHeight"));
  sequence.frames.resize(static_cast<std::size_t>(std::stoi(ini_value(ini, "seqLength"))));
  const auto det_path = sequence_dir / "det" / "det.txt";
  std::ifstream in(det_path);
  if (!in) throw std::runtime_error("cannot open " + det_path.string());
  std::string line;
  int line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    if (line.empty()) continue;
    std::istringstream fields(line);
    double values[7] = {};
    char comma = 0;
    for (int i = 0; i < 7; ++i) {
      if (i > 0) fields >> comma;
      if (!(fields >> values[i]))
        throw std::runtime_error(det_path.string() + ":" + std::to_string(line_number));
    }
    const auto frame = static_cast<std::size_t>(values[0]);
    if (frame < 1) throw std::runtime_error(det_path.string() + ": frame < 1");
    if (frame > sequence.frames.size()) sequence.frames.resize(frame);
    tracker::Detection detection;
    detection.box = tracker::Box{static_cast<float>(values[2]), static_cast<float>(values[3]),
                                 static_cast<float>(values[4]), static_cast<float>(values[5])};
    detection.score = static_cast<float>(values[6]);
    sequence.frames[frame - 1].push_back(detection);
  }
  return sequence;
}

inline const char* const kMot15Sequences[] = {
    "ADL-Rundle-6", "ADL-Rundle-8", "ETH-Bahnhof", "ETH-Pedcross2",  "ETH-Sunnyday", "KITTI-13",
    "KITTI-17",     "PETS09-S2L1",  "TUD-Campus",  "TUD-Stadtmitte", "Venice-2"};

}  // namespace rtmot::test
