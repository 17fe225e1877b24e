#include "outputs/bgr_buffer.hpp"

#include <cstring>

namespace rtmot::outputs {

GstBuffer* copy_to_gst_buffer(const cv::Mat& bgr) {
  const gsize row_bytes = static_cast<gsize>(bgr.cols) * 3;
  // Raw video caps without a GstVideoMeta mean rows padded to 4 bytes (GST_ROUND_UP_4): a 33-pixel
  // row is 100 bytes, not 99. Packed rows were read sheared (and short) at widths not a multiple
  // of 4: wrong colours in every encoded output of such a frame.
  const gsize stride = GST_ROUND_UP_4(row_bytes);
  GstBuffer* buffer =
      gst_buffer_new_allocate(nullptr, stride * static_cast<gsize>(bgr.rows), nullptr);
  GstMapInfo map;
  gst_buffer_map(buffer, &map, GST_MAP_WRITE);
  for (int row = 0; row < bgr.rows; ++row) {
    guint8* out = map.data + stride * static_cast<gsize>(row);
    std::memcpy(out, bgr.ptr(row), row_bytes);
    std::memset(out + row_bytes, 0, stride - row_bytes);
  }
  gst_buffer_unmap(buffer, &map);
  return buffer;
}

}  // namespace rtmot::outputs
