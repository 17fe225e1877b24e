// Tiles of a large frame (detector/tile_layout.hpp), their boxes merged back into frame pixels
// (tile_merge.hpp), and the detector that runs both around another one (tiling_detector.hpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <vector>

#include "detector/tile_layout.hpp"
#include "detector/tile_merge.hpp"
#include "detector/tiling_detector.hpp"
#include "tracker/box_geometry.hpp"

namespace rtmot::detector {
namespace {

using tracker::Box;
using tracker::Detection;

TEST(TileLayout, TilesCoverTheFrameWithTheAskedOverlap) {
  for (const auto& [w, h, grid] :
       {std::tuple{1920, 1080, TileGrid{3, 2, 0.2F}}, std::tuple{1920, 1080, TileGrid{4, 2, 0.2F}},
        std::tuple{768, 576, TileGrid{2, 2, 0.25F}}, std::tuple{641, 479, TileGrid{3, 3, 0.F}}}) {
    const auto tiles = tile_rects(w, h, grid);
    ASSERT_EQ(tiles.size(), static_cast<std::size_t>(grid.columns * grid.rows));
    // Every pixel of the frame lies in a tile; none lies outside the frame.
    std::vector<int> covered(static_cast<std::size_t>(w * h), 0);
    for (const PixelRect& t : tiles) {
      ASSERT_GE(t.x, 0);
      ASSERT_GE(t.y, 0);
      ASSERT_LE(t.right(), w);
      ASSERT_LE(t.bottom(), h);
      EXPECT_EQ(t.width, tiles.front().width);  // one tile size: one scale for the network
      EXPECT_EQ(t.height, tiles.front().height);
      for (int y = t.y; y < t.bottom(); ++y)
        for (int x = t.x; x < t.right(); ++x) covered[static_cast<std::size_t>(y * w + x)] = 1;
    }
    EXPECT_EQ(std::count(covered.begin(), covered.end(), 0), 0) << w << "x" << h;
    // Horizontal neighbours share about `overlap` of a tile (rounding: a pixel).
    if (grid.columns > 1) {
      const int shared = tiles[0].right() - tiles[1].x;
      EXPECT_NEAR(shared, grid.overlap * tiles[0].width, 1.5) << w << "x" << h;
    }
  }
}

TEST(TileLayout, RefusesGridsThatCannotBeCut) {
  EXPECT_THROW(tile_rects(0, 10, {1, 1, 0.2F}), std::invalid_argument);
  EXPECT_THROW(tile_rects(10, 10, {11, 1, 0.2F}), std::invalid_argument);
  EXPECT_THROW(tile_rects(100, 100, {2, 2, 0.95F}), std::invalid_argument);
  EXPECT_THROW(tile_rects(100, 100, {2, 2, -0.1F}), std::invalid_argument);
}

TEST(TileLayout, AutomaticGridLeavesSmallFramesWholeAndCutsLargeOnes) {
  // Two rows of 640 x 480 would be 267 px tall: magnified for the 300 px network, so whole.
  EXPECT_FALSE(automatic_grid(640, 480, 300, 2.F, 0.2F).tiled());
  EXPECT_FALSE(automatic_grid(1280, 500, 300, 2.F, 0.2F).tiled());
  for (const auto& [w, h, columns, rows] :
       {std::tuple{768, 576, 3, 2}, std::tuple{1920, 1080, 4, 2}, std::tuple{1280, 720, 4, 2}}) {
    const TileGrid grid = automatic_grid(w, h, 300, 2.F, 0.2F);
    EXPECT_EQ(grid.columns, columns) << w << "x" << h;
    EXPECT_EQ(grid.rows, rows) << w << "x" << h;
  }
  // Every auto tile is at least the network's size and at most twice it tall, and near square.
  for (const auto& [w, h] : {std::pair{768, 576}, std::pair{1920, 1080}, std::pair{1280, 720},
                             std::pair{2560, 1440}, std::pair{1080, 1920}}) {
    const TileGrid grid = automatic_grid(w, h, 300, 2.F, 0.2F);
    const auto tiles = tile_rects(w, h, grid);
    EXPECT_GE(tiles.front().height, 300) << w << "x" << h;
    EXPECT_LE(tiles.front().height, 601) << w << "x" << h;  // rounded up to whole pixels
    const double aspect = static_cast<double>(tiles.front().width) / tiles.front().height;
    EXPECT_GT(aspect, 0.7) << w << "x" << h;
    EXPECT_LT(aspect, 1.45) << w << "x" << h;
  }
  // A 4K frame is cut in at most kMaxTileSide of each.
  const TileGrid uhd = automatic_grid(3840, 2160, 300, 2.F, 0.2F);
  EXPECT_LE(uhd.columns, kMaxTileSide);
  EXPECT_LE(uhd.rows, kMaxTileSide);
}

// A frame of 1000 x 500 as its whole and two tiles side by side sharing 200 pixels.
const std::vector<PixelRect> kPasses{{0, 0, 1000, 500}, {0, 0, 600, 500}, {400, 0, 600, 500}};

std::vector<Detection> merged(const std::vector<std::vector<Detection>>& passes,
                              TileMergeConfig config = {}) {
  TileMerger merger(config);
  std::vector<Detection> out;
  merger.merge(kPasses.data(), passes.data(), static_cast<int>(passes.size()), out);
  return out;
}

TEST(TileMerge, OnePersonSeenWholeAndInATileIsOneBoxWithTheBetterScore) {
  // At (100, 100) in the frame: the tile (at 0, 0) sees it 2 px off.
  const auto out = merged({{{{100, 100, 40, 100}, 0.5F, 1}}, {{{102, 101, 40, 100}, 0.8F, 1}}, {}});
  ASSERT_EQ(out.size(), 1U);
  EXPECT_FLOAT_EQ(out[0].score, 0.8F);
  EXPECT_FLOAT_EQ(out[0].box.x, 102.F);
}

TEST(TileMerge, BoxesAreMovedIntoFramePixels) {
  const auto out = merged({{}, {}, {{{300, 50, 30, 90}, 0.7F, 1}}});
  ASSERT_EQ(out.size(), 1U);
  EXPECT_FLOAT_EQ(out[0].box.x, 700.F);  // the second tile starts at x = 400
  EXPECT_FLOAT_EQ(out[0].box.y, 50.F);
}

TEST(TileMerge, TwoHalvesCutByTheSharedEdgeBecomeOnePerson) {
  // A person at x 380..460 of the frame, sticking out of the overlap (400..600) to the left: the
  // left tile sees it whole, the right tile sees 400..460, cut at its left edge.
  const auto whole_in_left =
      merged({{}, {{{380, 100, 80, 200}, 0.6F, 1}}, {{{0, 102, 60, 196}, 0.55F, 1}}});
  ASSERT_EQ(whole_in_left.size(), 1U) << "the cut part lies inside the whole one";
  EXPECT_FLOAT_EQ(whole_in_left[0].box.x, 380.F);
  // Wider than the overlap: neither tile sees it whole; x 300..700 cut by both tiles.
  const auto halves =
      merged({{}, {{{300, 100, 300, 200}, 0.5F, 1}}, {{{0, 104, 300, 196}, 0.6F, 1}}});
  ASSERT_EQ(halves.size(), 1U);
  EXPECT_NEAR(halves[0].box.x, 300.F, 1e-3);
  EXPECT_NEAR(halves[0].box.x + halves[0].box.w, 700.F, 1e-3);
  EXPECT_FLOAT_EQ(halves[0].score, 0.6F);
}

TEST(TileMerge, HalvesOfDifferentHeightsOrClassesStayApart) {
  // Cut at the facing edges, overlapping, but one is 0.4 of the other's height: two objects.
  const auto heights =
      merged({{}, {{{500, 100, 100, 200}, 0.5F, 1}}, {{{0, 100, 150, 80}, 0.6F, 1}}});
  EXPECT_EQ(heights.size(), 2U);
  const auto classes =
      merged({{}, {{{500, 100, 100, 200}, 0.5F, 1}}, {{{0, 100, 150, 200}, 0.6F, 3}}});
  EXPECT_EQ(classes.size(), 2U);
  const auto alike =
      merged({{}, {{{500, 100, 100, 200}, 0.5F, 1}}, {{{0, 100, 150, 200}, 0.6F, 1}}});
  EXPECT_EQ(alike.size(), 1U);
}

TEST(TileMerge, APartOfAPersonSeenInATileGoesWithThePerson) {
  // The whole frame sees the person; a tile sees its upper body only (inside it), scored lower.
  const auto out = merged({{{{100, 100, 50, 150}, 0.7F, 1}}, {{{105, 100, 40, 70}, 0.6F, 1}}, {}});
  ASSERT_EQ(out.size(), 1U);
  EXPECT_FLOAT_EQ(out[0].box.h, 150.F);
  TileMergeConfig loose;
  loose.containment = 1.01F;  // containment off: both stay
  EXPECT_EQ(
      merged({{{{100, 100, 50, 150}, 0.7F, 1}}, {{{105, 100, 40, 70}, 0.6F, 1}}, {}}, loose).size(),
      2U);
  // Greedy by score: a part scored above its whole is kept first, and the whole (not inside it)
  // stays too (docs/tiling.md says so).
  EXPECT_EQ(merged({{{{100, 100, 50, 150}, 0.7F, 1}}, {{{105, 100, 40, 70}, 0.9F, 1}}, {}}).size(),
            2U);
}

TEST(TileMerge, WithinOnePassTheDetectorsOwnNmsDecided) {
  // Two people close together in one tile, overlapping by IoU 0.6: both were kept by the SSD.
  const std::vector<Detection> two{{{100, 100, 50, 100}, 0.8F, 1}, {{112, 100, 50, 100}, 0.7F, 1}};
  ASSERT_GT(tracker::iou(two[0].box, two[1].box), 0.5F);
  EXPECT_EQ(merged({{}, two, {}}).size(), 2U);
}

TEST(TileMerge, TilesHaveTheirOwnCutAndLeaveTallObjectsToTheWholeFrame) {
  TileMergeConfig config;
  config.tile_score_threshold = 0.5F;
  config.tile_max_height = 0.8F;
  // 0.4 in a tile is below its cut; in the whole frame it stays (the detector's cut applied).
  EXPECT_TRUE(merged({{}, {{{100, 100, 40, 100}, 0.4F, 1}}, {}}, config).empty());
  EXPECT_EQ(merged({{{{100, 100, 40, 100}, 0.4F, 1}}, {}, {}}, config).size(), 1U);
  // 450 of the tile's 500 rows: a large object, the whole frame's to report.
  EXPECT_TRUE(merged({{}, {{{100, 20, 150, 450}, 0.9F, 1}}, {}}, config).empty());
}

// Reports one 20 x 20 box per image, at the image's centre, scored by its frame number: enough to
// see which region of which frame went where.
class RegionEcho : public Detector {
 public:
  void detect(const cv::Mat& image, std::int64_t frame_number,
              std::vector<Detection>& out) override {
    out.clear();
    out.push_back({{static_cast<float>(image.cols) / 2.F - 10.F,
                    static_cast<float>(image.rows) / 2.F - 10.F, 20.F, 20.F},
                   static_cast<float>(frame_number) / 10.F,
                   1});
    ++images;
  }
  void detect_batch(const cv::Mat* const* images_in, const std::int64_t* numbers, int count,
                    std::vector<std::vector<Detection>>& out) override {
    ++calls;
    Detector::detect_batch(images_in, numbers, count, out);
  }
  int max_batch() const override { return 14; }
  std::string describe() const override { return "echo"; }
  int images{0};
  int calls{0};
};

TEST(TilingDetector, AFrameAndItsTilesGoAsOneBatchAndComeBackInFramePixels) {
  auto echo = std::make_unique<RegionEcho>();
  RegionEcho* inner = echo.get();
  TilingConfig config;
  config.grid = {3, 2, 0.2F};
  TilingDetector tiling(std::move(echo), config);
  const cv::Mat hd(1080, 1920, CV_8UC3, cv::Scalar::all(0));
  const cv::Mat small(100, 100, CV_8UC3, cv::Scalar::all(0));
  const cv::Mat* images[] = {&hd, &small};
  const std::int64_t numbers[] = {5, 6};
  std::vector<std::vector<Detection>> out;
  tiling.detect_batch(images, numbers, 2, out);
  EXPECT_EQ(inner->calls, 1);
  EXPECT_EQ(inner->images, 14);  // (the whole frame + 6 tiles) x 2
  ASSERT_GE(out.size(), 2U);
  for (std::size_t i = 0; i < 2; ++i) {
    const cv::Mat& image = *images[i];
    std::vector<PixelRect> passes{{0, 0, image.cols, image.rows}};
    for (const PixelRect& t : tile_rects(image.cols, image.rows, config.grid)) passes.push_back(t);
    ASSERT_EQ(out[i].size(), passes.size()) << "image " << i;
    for (const PixelRect& p : passes) {
      const float x = static_cast<float>(p.x) + static_cast<float>(p.width) / 2.F - 10.F;
      const float y = static_cast<float>(p.y) + static_cast<float>(p.height) / 2.F - 10.F;
      const bool found = std::any_of(out[i].begin(), out[i].end(), [&](const Detection& d) {
        return d.box.x == x && d.box.y == y && d.score == static_cast<float>(numbers[i]) / 10.F;
      });
      EXPECT_TRUE(found) << "image " << i << ", the pass at " << p.x << "," << p.y;
    }
  }
  EXPECT_EQ(tiling.max_batch(), 2);  // 14 images a call: two frames' passes
}

TEST(TilingDetector, AFrameTheGridDoesNotFitIsSeenWhole) {
  auto echo = std::make_unique<RegionEcho>();
  RegionEcho* inner = echo.get();
  TilingConfig config;
  config.grid = {4, 2, 0.2F};
  TilingDetector tiling(std::move(echo), config);
  const cv::Mat tiny(1, 3, CV_8UC3, cv::Scalar::all(0));
  std::vector<Detection> out;
  tiling.detect(tiny, 3, out);
  EXPECT_EQ(inner->images, 1);
  ASSERT_EQ(out.size(), 1U);
  EXPECT_FLOAT_EQ(out[0].box.x, 1.5F - 10.F);  // the echo's box at the whole image's centre
}

}  // namespace
}  // namespace rtmot::detector
