#pragma once
// The operator's page (--web-port / output.web_port, docs/web.md): civetweb, like the Prometheus
// endpoint (outputs/metrics_server.hpp), but a server of its own on its own port: its MJPEG
// clients hold a worker each for as long as they watch, and would otherwise take the workers a
// scraper needs; its limits (request size, connections) are its own.
//   GET /                  the page (index.html), and the other files of the static folder by
//                          their names only (app.js, style.css): read once at start, so no request
//                          can name a file outside that folder
//   GET /api/status        JSON: per source its geometry (frame size, lines, zones in pixels),
//                          health and counts (PipelineMetrics::status(): the Prometheus facts)
//   GET /video/N.mjpg      source N's live annotated picture, multipart/x-mixed-replace JPEG
//                          (outputs/live_picture.hpp: encoded only while someone watches)
//   POST /api/events?source=N  source N's new lines and zones (the events section, YAML or JSON),
//                          with "Authorization: Bearer TOKEN"; the body at most kMaxBody bytes
//   POST /api/settings     the settings a run takes live (the detector's score cut), as writes
//                          above
#include <atomic>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "outputs/live_picture.hpp"
#include "outputs/pipeline_metrics.hpp"
#include "outputs/web_site.hpp"

namespace rtmot::outputs {

/// The answer to a save: an HTTP status, its JSON body, and on success (200) the source's new
/// geometry (as WebContent::sources' element).
struct SaveAnswer {
  int status{500};
  nlohmann::json body;
  nlohmann::json geometry;
};

/// What the page shows. Pointers not owned: each outlives the server.
struct WebContent {
  const PipelineMetrics* metrics{nullptr};
  std::vector<LivePicture*> pictures;  // one per source, in the run's order
  nlohmann::json sources;              // per source: stream, uri, width, height, lines, zones
  std::string detector;                // the detector's description (backend)
  /// Saves source N's events section (body); null: saving is off.
  std::function<SaveAnswer(std::size_t source, const std::string& body)> save_events;
  /// Per source its geometry as it is now (`sources` updated by saves and by SIGHUP); null:
  /// `sources`.
  std::function<nlohmann::json()> geometry;
  /// Changes the settings a run takes live (`{"score_threshold": 0.4}`); null: off.
  std::function<SaveAnswer(const std::string& body)> save_settings;
  /// Those settings as they are now, shown by the status ("settings"); null: none.
  std::function<nlohmann::json()> settings;
  /// What a write must carry ("Authorization: Bearer TOKEN"); empty: writes are refused.
  std::string token;
};

/// The page's files: next to an installed binary (<prefix>/share/rtmot/web), else the source
/// tree's web/ (a build folder's binary). Throws InputError (naming output.web_port) if neither
/// has index.html.
std::filesystem::path find_static_dir();

class WebServer {
 public:
  /// Most MJPEG clients at once (every source together); one more is answered 503. Each holds a
  /// worker; the rest of the workers serve the page and the status.
  static constexpr int kMaxWatchers = 4;
  static_assert(kMaxWatchers < PageServer::kWorkers, "workers must stay for the page and status");
  /// The largest body a write may send (an events section of many lines and zones fits).
  static constexpr long long kMaxBody = 64 * 1024;

  /// Reads the static folder and listens on `bind_address`:`port` at once; throws InputError
  /// (ExitCode::network) if it cannot listen, (ExitCode::input) if the folder cannot be read.
  WebServer(WebContent content, const std::string& bind_address, std::uint16_t port,
            const std::filesystem::path& static_dir);
  ~WebServer();
  WebServer(const WebServer&) = delete;
  WebServer& operator=(const WebServer&) = delete;

  /// "http://ADDRESS:PORT/", for the start-up log.
  const std::string& url() const { return server_.url(); }
  /// Where its files were read from.
  const std::filesystem::path& static_dir() const { return files_.folder(); }

 private:
  static int serve_static(mg_connection* connection, void* self);
  static int serve_status(mg_connection* connection, void* self);
  static int serve_video(mg_connection* connection, void* self);
  static int serve_events(mg_connection* connection, void* self);
  static int serve_settings(mg_connection* connection, void* self);
  /// A write's checks (method, token, length) and its body; 0 when it may go on, else the status
  /// already answered.
  int read_write(mg_connection* connection, bool enabled, std::string& body) const;
  int stream_video(mg_connection* connection, LivePicture& picture);

  WebContent content_;
  std::mutex geometry_mutex_;  // guards content_.sources (HTTP workers only)
  StaticFiles files_;          // "/" is index.html
  std::atomic<int> watchers_{0};
  std::atomic<bool> stopping_{false};
  PageServer server_;  // last: stopped (its workers joined) before the members they use go
};

}  // namespace rtmot::outputs
