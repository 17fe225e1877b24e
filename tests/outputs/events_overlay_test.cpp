// The lines and zones drawn on the picture, with counts summed from the frames' events.
#include "outputs/events_overlay.hpp"

#include <gtest/gtest.h>

#include <opencv2/core.hpp>

namespace rtmot::outputs {
namespace {

TEST(EventsOverlay, DrawsLinesAndZonesAndCountsTheEvents) {
  events::EventsConfig config;
  config.lines.push_back({"door", {{320.0, 100.0}, {320.0, 470.0}}, true});
  config.zones.push_back({"hall", {{20, 20}, {200, 20}, {200, 200}, {20, 200}}, 0.0});
  EventsOverlay overlay(config);
  messages::FrameResult frame;
  events::Event in;
  in.kind = events::EventKind::line_in;
  events::Event out = in;
  out.kind = events::EventKind::line_out;
  events::Event enter;
  enter.kind = events::EventKind::zone_enter;
  events::Event leave = enter;
  leave.kind = events::EventKind::zone_exit;
  frame.events = {in, in, out, enter, enter, leave};
  overlay.count(frame);
  EXPECT_EQ(overlay.line_in(0), 2);
  EXPECT_EQ(overlay.line_out(0), 1);
  EXPECT_EQ(overlay.occupancy(0), 1);

  cv::Mat image(480, 640, CV_8UC3, cv::Scalar(0, 0, 0));
  overlay.draw(image);
  // The line's pixels away from its label, and the zone's border, are drawn; the rest is not.
  EXPECT_NE(image.at<cv::Vec3b>(130, 320), cv::Vec3b(0, 0, 0));
  EXPECT_NE(image.at<cv::Vec3b>(450, 320), cv::Vec3b(0, 0, 0));
  EXPECT_NE(image.at<cv::Vec3b>(120, 200), cv::Vec3b(0, 0, 0));
  EXPECT_EQ(image.at<cv::Vec3b>(120, 110), cv::Vec3b(0, 0, 0));  // inside the zone: not filled
  EXPECT_EQ(image.at<cv::Vec3b>(400, 500), cv::Vec3b(0, 0, 0));
  // The labels' dark background with text: the line's label sits at its middle.
  const cv::Mat around_label = image(cv::Rect(320, 260, 150, 30));
  EXPECT_GT(cv::countNonZero(around_label.reshape(1)), 50);
}

}  // namespace
}  // namespace rtmot::outputs
