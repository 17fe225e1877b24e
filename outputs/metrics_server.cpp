#include "outputs/metrics_server.hpp"

#include <civetweb.h>

#include "common/input_error.hpp"
#include "outputs/civetweb_library.hpp"
#include "platform/host_port.hpp"

namespace rtmot::outputs {

MetricsServer::MetricsServer(const PipelineMetrics& metrics, const std::string& bind_address,
                             std::uint16_t port)
    : metrics_(metrics),
      url_("http://" + platform::format_host_port(bind_address, port) + "/metrics") {
  ensure_civetweb_library();
  const std::string ports = platform::format_host_port(bind_address, port);
  // A client that connects and sends nothing, or half a request, holds a worker until the request
  // timeout: with civetweb's one worker and 30 s, one idle connection stopped every scrape
  // (Prometheus gives up after 10 s). A scrape's request is one small packet: a second is ample on
  // any link. Workers are cheap (they sleep); 16 of them with a 1 s header timeout clear 50
  // half-sent requests in about 3 s. Connections beyond the workers wait in a bounded queue, then
  // in the kernel's bounded backlog; keep-alive is off so that no scraper holds a worker between
  // scrapes.
  const char* options[] = {"listening_ports",
                           ports.c_str(),
                           "num_threads",
                           "16",
                           "request_timeout_ms",
                           "1000",
                           "enable_keep_alive",
                           "no",
                           "linger_timeout_ms",
                           "0",
                           "connection_queue",
                           "64",
                           "listen_backlog",
                           "128",
                           "max_request_size",
                           "8192",
                           nullptr};
  mg_callbacks callbacks{};
  context_ = mg_start(&callbacks, nullptr, options);
  if (context_ == nullptr) {
    throw InputError(url_, 0, "output.metrics_port", "cannot listen (port in use?)",
                     ExitCode::network);
  }
  mg_set_request_handler(context_, "/metrics", &MetricsServer::handle, this);
}

MetricsServer::~MetricsServer() {
  if (context_ != nullptr) mg_stop(context_);
}

int MetricsServer::handle(mg_connection* connection, void* self) {
  const std::string body = static_cast<MetricsServer*>(self)->metrics_.render();
  mg_printf(connection,
            "HTTP/1.1 200 OK\r\nContent-Type: text/plain; version=0.0.4; charset=utf-8\r\n"
            "Content-Length: %zu\r\nConnection: close\r\n\r\n",
            body.size());
  mg_write(connection, body.data(), body.size());
  return 200;
}

}  // namespace rtmot::outputs
