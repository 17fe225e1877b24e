#pragma once
// Owning handles for the GStreamer/GLib C objects we hold, so every early return and exception
// releases them.
#include <gst/gst.h>

#include <memory>

namespace rtmot::platform::gst {

struct ObjectUnref {
  void operator()(gpointer object) const { gst_object_unref(object); }
};
template <typename T>
using ObjectPtr = std::unique_ptr<T, ObjectUnref>;

struct SampleUnref {
  void operator()(GstSample* sample) const { gst_sample_unref(sample); }
};
using SamplePtr = std::unique_ptr<GstSample, SampleUnref>;

struct MessageUnref {
  void operator()(GstMessage* message) const { gst_message_unref(message); }
};
using MessagePtr = std::unique_ptr<GstMessage, MessageUnref>;

struct CapsUnref {
  void operator()(GstCaps* caps) const { gst_caps_unref(caps); }
};
using CapsPtr = std::unique_ptr<GstCaps, CapsUnref>;

struct ErrorFree {
  void operator()(GError* error) const { g_error_free(error); }
};
using ErrorPtr = std::unique_ptr<GError, ErrorFree>;

struct StringFree {
  void operator()(gchar* text) const { g_free(text); }
};
using StringPtr = std::unique_ptr<gchar, StringFree>;

/// A buffer mapped for reading for as long as this lives.
class MappedBuffer {
 public:
  explicit MappedBuffer(GstBuffer* buffer) : buffer_(buffer) {
    mapped_ = gst_buffer_map(buffer_, &map_, GST_MAP_READ);
  }
  ~MappedBuffer() {
    if (mapped_) gst_buffer_unmap(buffer_, &map_);
  }
  MappedBuffer(const MappedBuffer&) = delete;
  MappedBuffer& operator=(const MappedBuffer&) = delete;

  bool ok() const { return mapped_; }
  const guint8* data() const { return map_.data; }
  gsize size() const { return map_.size; }

 private:
  GstBuffer* buffer_;
  GstMapInfo map_{};
  bool mapped_{false};
};

/// Initialises GStreamer once per process; throws rtmot::InputError (source_failed) if it cannot.
void ensure_initialized();

}  // namespace rtmot::platform::gst
