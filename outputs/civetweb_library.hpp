#pragma once
// civetweb's mg_init_library must run once per process before its first server (the metrics
// endpoint and the web page each start one).
namespace rtmot::outputs {

void ensure_civetweb_library();

}  // namespace rtmot::outputs
