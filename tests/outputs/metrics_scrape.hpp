#pragma once
// Reading a Prometheus endpoint the way a scraper does: a plain HTTP GET over loopback, and one
// series' value out of the text.
#include <string>

namespace rtmot::test {

/// A TCP connection to 127.0.0.1:port (-1 if refused); the caller closes it.
int connect_to(unsigned short port);
/// GET `path` from 127.0.0.1:port with a plain socket; the whole response (headers and body), or
/// what came within `timeout_s` (Prometheus' default scrape timeout is 10 s).
std::string http_get(unsigned short port, const std::string& path, int timeout_s = 10);
/// The value of `series` (name and labels exactly as rendered) in Prometheus text; fails the test
/// and returns -1 when it is absent.
double value_of(const std::string& text, const std::string& series);

}  // namespace rtmot::test
