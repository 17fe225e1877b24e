#include "outputs/bgr_buffer.hpp"

#include <cstring>

namespace rtmot::outputs {

GstBuffer* copy_to_gst_buffer(const cv::Mat& bgr) {
  const gsize row_bytes = static_cast<gsize>(bgr.cols) * 3;
  GstBuffer* buffer =
      gst_buffer_new_allocate(nullptr, row_bytes * static_cast<gsize>(bgr.rows), nullptr);
  GstMapInfo map;
  gst_buffer_map(buffer, &map, GST_MAP_WRITE);
  for (int row = 0; row < bgr.rows; ++row) {
    std::memcpy(map.data + row_bytes * static_cast<gsize>(row), bgr.ptr(row), row_bytes);
  }
  gst_buffer_unmap(buffer, &map);
  return buffer;
}

}  // namespace rtmot::outputs
