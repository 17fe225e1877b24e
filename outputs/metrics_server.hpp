#pragma once
// The optional HTTP endpoint (--metrics-port / output.metrics_port) serving GET /metrics in
// Prometheus' text format, with civetweb (Debian's libcivetweb-dev): worker threads of its own, so
// a slow scraper never touches the pipeline, and enough of them, with a short request timeout, that
// idle or half-sent connections do not stop scrapes (metrics_server.cpp says the numbers).
#include <cstdint>
#include <string>

#include "outputs/pipeline_metrics.hpp"

struct mg_context;
struct mg_connection;

namespace rtmot::outputs {

class MetricsServer {
 public:
  /// Listens on `bind_address`:`port` at once; throws InputError (ExitCode::network) if it cannot.
  MetricsServer(const PipelineMetrics& metrics, const std::string& bind_address,
                std::uint16_t port);
  ~MetricsServer();
  MetricsServer(const MetricsServer&) = delete;
  MetricsServer& operator=(const MetricsServer&) = delete;

  /// "http://ADDRESS:PORT/metrics", for the start-up log.
  const std::string& url() const { return url_; }

 private:
  static int handle(mg_connection* connection, void* self);

  const PipelineMetrics& metrics_;
  std::string url_;
  mg_context* context_{nullptr};
};

}  // namespace rtmot::outputs
