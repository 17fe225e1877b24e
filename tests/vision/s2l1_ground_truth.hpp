#pragma once
// PETS09-S2L1's ground truth (MOT15's gt.txt in ../shared), whose frame numbers are vtest.avi's:
// decoded frame i (1-based, as tests/detector/vtest_frames.hpp numbers them) is the truth's frame
// i.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>

#include "shared_data.hpp"
#include "tracker/box.hpp"

namespace rtmot::test {

using S2l1Boxes = std::map<int, tracker::Box>;  // id -> box

/// The ground truth's boxes of the frames wanted, by frame and id.
inline std::map<int, S2l1Boxes> s2l1_ground_truth(const std::set<int>& frames) {
  const auto path = shared_path("data/mot15-train/PETS09-S2L1/gt/gt.txt");
  std::ifstream in(path);
  EXPECT_TRUE(in) << "missing test data file: " << path;
  std::map<int, S2l1Boxes> boxes;
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    char comma = 0;
    int frame = 0;
    int id = 0;
    tracker::Box box;
    fields >> frame >> comma >> id >> comma >> box.x >> comma >> box.y >> comma >> box.w >> comma >>
        box.h;
    if (frames.count(frame) != 0) boxes[frame][id] = box;
  }
  return boxes;
}

}  // namespace rtmot::test
