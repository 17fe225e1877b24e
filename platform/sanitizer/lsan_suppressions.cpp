// LeakSanitizer reads its default suppressions from this function in the executable.
// GLib never frees some blocks on purpose: its quark table (16 KiB, allocated by GLib's own
// initialiser) is replaced when it grows and the old block is left for lock-free readers;
// GStreamer's plugin loading grows it. GLib is built without frame pointers, so with ASan's default
// (fast) unwinder the stack of such a block ends at g_malloc and cannot be told apart from other
// GLib allocations: the suppression has to cover allocations made inside GLib. Our own GStreamer
// objects are owned by RAII handles (platform/gst_ptr.hpp); leaks of memory we allocate are still
// reported.
extern "C" const char* __lsan_default_suppressions() {
  return "leak:_dl_init\n"
         "leak:libglib-2.0.so\n";
}
