// The lines and zones drawn on the picture, with counts summed from the frames' events.
#include "outputs/events_overlay.hpp"

#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include "outputs/followed_events_overlay.hpp"

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

// A vertical line at x: the pixel (row 130, x) is drawn.
bool drawn_at(FollowedEventsOverlay& followed, int x) {
  cv::Mat image(480, 640, CV_8UC3, cv::Scalar(0, 0, 0));
  if (EventsOverlay* overlay = followed.get()) overlay->draw(image);
  return image.at<cv::Vec3b>(130, x) != cv::Vec3b(0, 0, 0);
}

events::EventsConfig one_line(const char* name, double x) {
  events::EventsConfig config;
  config.lines.push_back({name, {{x, 100.0}, {x, 470.0}}, true});
  return config;
}

TEST(FollowedEventsOverlay, DrawsANewConfigurationFromItsFirstFrameOnCountsFromZero) {
  pipeline::EventsMailbox mailbox;
  FollowedEventsOverlay followed;
  followed.start_with(one_line("door", 320));
  followed.follow(&mailbox);
  messages::FrameResult frame;
  events::Event in;
  in.kind = events::EventKind::line_in;
  frame.events = {in};
  followed.switch_to(0);
  followed.get()->count(frame);
  EXPECT_TRUE(drawn_at(followed, 320));

  mailbox.post(one_line("hall", 500), 1);
  // Frames counted with the run's own configuration still come: it stays.
  followed.switch_to(0);
  EXPECT_TRUE(drawn_at(followed, 320));
  EXPECT_FALSE(drawn_at(followed, 500));
  EXPECT_EQ(followed.get()->line_in(0), 1);
  // The first frame counted with the new one: drawn, counted from zero.
  followed.switch_to(1);
  EXPECT_EQ(followed.generation(), 1U);
  EXPECT_FALSE(drawn_at(followed, 320));
  EXPECT_TRUE(drawn_at(followed, 500));
  EXPECT_EQ(followed.get()->line_in(0), 0);

  // A configuration without lines or zones draws nothing.
  mailbox.post(events::EventsConfig{}, 2);
  followed.switch_to(2);
  EXPECT_EQ(followed.get(), nullptr);
}

TEST(FollowedEventsOverlay, AConfigurationReplacedBeforeItsFramesCameIsSkipped) {
  pipeline::EventsMailbox mailbox;
  FollowedEventsOverlay followed;
  followed.start_with(one_line("door", 320));
  followed.follow(&mailbox);
  mailbox.post(one_line("hall", 500), 1);
  mailbox.post(one_line("gate", 100), 2);
  followed.switch_to(1);  // its configuration was replaced: the run's own stays
  EXPECT_TRUE(drawn_at(followed, 320));
  followed.switch_to(2);
  EXPECT_TRUE(drawn_at(followed, 100));
  EXPECT_FALSE(drawn_at(followed, 320));
}

}  // namespace
}  // namespace rtmot::outputs
