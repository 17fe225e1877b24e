#include "gst_read_back.hpp"

#include <gst/app/gstappsink.h>
#include <gst/gst.h>
#include <gtest/gtest.h>

#include "platform/gst_ptr.hpp"

namespace rtmot::test {

const std::string to_bgr_sink =
    " ! videoconvert ! video/x-raw,format=BGR ! appsink name=out sync=false";

ReadBack read_back(const std::string& description, int save_index, int stop_after,
                   std::chrono::milliseconds limit, const std::function<void()>& once_playing) {
  platform::gst::ensure_initialized();
  ReadBack result;
  GError* raw_error = nullptr;
  platform::gst::ObjectPtr<GstElement> pipeline(gst_parse_launch(description.c_str(), &raw_error));
  const platform::gst::ErrorPtr error(raw_error);
  EXPECT_TRUE(pipeline && !error) << description << ": " << (error ? error->message : "");
  if (!pipeline) return result;
  platform::gst::ObjectPtr<GstElement> sink(gst_bin_get_by_name(GST_BIN(pipeline.get()), "out"));
  gst_element_set_state(pipeline.get(), GST_STATE_PLAYING);
  once_playing();
  const auto deadline = std::chrono::steady_clock::now() + limit;
  while (result.frames < stop_after && std::chrono::steady_clock::now() < deadline) {
    const platform::gst::SamplePtr sample(
        gst_app_sink_try_pull_sample(GST_APP_SINK(sink.get()), 100 * GST_MSECOND));
    if (!sample) {
      if (gst_app_sink_is_eos(GST_APP_SINK(sink.get()))) break;
      continue;
    }
    if (result.frames == save_index) {
      GstCaps* caps = gst_sample_get_caps(sample.get());
      const GstStructure* structure = gst_caps_get_structure(caps, 0);
      int width = 0;
      int height = 0;
      gst_structure_get_int(structure, "width", &width);
      gst_structure_get_int(structure, "height", &height);
      platform::gst::MappedBuffer map(gst_sample_get_buffer(sample.get()));
      // GStreamer's raw rows are padded to 4 bytes (a 34-pixel BGR row is 104 bytes, not 102).
      const std::size_t stride = height > 0 ? map.size() / static_cast<std::size_t>(height) : 0;
      result.saved =
          cv::Mat(height, width, CV_8UC3, const_cast<guint8*>(map.data()), stride).clone();
    }
    ++result.frames;
  }
  gst_element_set_state(pipeline.get(), GST_STATE_NULL);
  return result;
}

}  // namespace rtmot::test
