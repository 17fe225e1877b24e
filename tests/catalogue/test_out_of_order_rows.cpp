// Decision (docs/reliability.md): rows of a det/gt/results file may come in any frame order, as the
// MOTChallenge devkit accepts them; they are grouped by frame. So a shuffled det.txt is no error
// and must give exactly the results of the ordered one.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <sstream>

#include "run_process.hpp"
#include "shared_data.hpp"
#include "workspace.hpp"

namespace rtmot::test {
namespace {

TEST(OutOfOrderRows, ShuffledDetectionsTrackExactlyLikeOrderedOnes) {
  Workspace ws("out_of_order");
  ws.copy_sequence("TUD-Campus", "ordered/TUD-Campus");
  ws.copy_sequence("TUD-Campus", "shuffled/TUD-Campus");
  std::istringstream in(read_text(ws.path("ordered/TUD-Campus/det/det.txt")));
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  ASSERT_GT(lines.size(), 100U);
  // Frames in a scrambled order (by frame % 7, then descending). The sort is stable, so rows of one
  // frame keep their relative order: the tracker's output may depend on detection order in a frame.
  std::stable_sort(lines.begin(), lines.end(), [](const std::string& a, const std::string& b) {
    const int fa = std::stoi(a);
    const int fb = std::stoi(b);
    return fa % 7 != fb % 7 ? fa % 7 < fb % 7 : fa > fb;
  });
  std::string shuffled;
  for (const auto& line : lines) shuffled += line + "\n";
  ws.write("shuffled/TUD-Campus/det/det.txt", shuffled);

  for (const std::string variant : {"ordered", "shuffled"}) {
    const auto run = run_process({rtmot_binary(), "track", "--dataset", ws.path(variant).string(),
                                  "--out", ws.path(variant + "-out").string()},
                                 ws.dir(), std::chrono::seconds(60));
    ASSERT_TRUE(run.exited && run.exit_code == 0) << variant << ": " << run.err;
  }
  const std::string ordered = read_text(ws.path("ordered-out/TUD-Campus.txt"));
  ASSERT_FALSE(ordered.empty());
  EXPECT_EQ(read_text(ws.path("shuffled-out/TUD-Campus.txt")), ordered);
}

}  // namespace
}  // namespace rtmot::test
