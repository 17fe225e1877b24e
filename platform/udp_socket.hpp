#pragma once
// RAII UDP sockets: a sender bound to one destination (resolved once, with getaddrinfo) and a
// receiver bound to a local address with a receive timeout. IPv4 and IPv6.
#include <cstddef>
#include <cstdint>
#include <string>

namespace rtmot::platform {

/// Owns one socket descriptor; closes it on destruction. Move-only.
class SocketHandle {
 public:
  SocketHandle() = default;
  explicit SocketHandle(int fd) : fd_(fd) {}
  ~SocketHandle();
  SocketHandle(SocketHandle&& other) noexcept : fd_(other.release()) {}
  SocketHandle& operator=(SocketHandle&& other) noexcept;
  SocketHandle(const SocketHandle&) = delete;
  SocketHandle& operator=(const SocketHandle&) = delete;

  int get() const { return fd_; }
  int release() noexcept;

 private:
  int fd_{-1};
};

/// Sends datagrams to one host:port. Construction resolves the host and opens the socket, or throws
/// rtmot::InputError (ExitCode::network) naming host and port.
class UdpSender {
 public:
  UdpSender(const std::string& host, std::uint16_t port);

  /// Sends one datagram. Never throws and never allocates (the per-frame path): returns false and
  /// keeps errno's text in last_error() if the kernel refused it (e.g. no route, buffer full).
  bool send(const std::uint8_t* data, std::size_t size);
  const std::string& last_error() const { return last_error_; }
  /// "host:port", for messages.
  const std::string& destination() const { return destination_; }

 private:
  SocketHandle socket_;
  std::string destination_;
  std::string last_error_;
  // sockaddr_storage, kept as bytes so that this header needs no system headers.
  alignas(8) unsigned char address_[128]{};
  unsigned address_length_{0};
};

enum class ReceiveStatus { datagram, timeout, interrupted };

/// Receives datagrams on a local address:port (port 0 = an ephemeral port; see port()).
/// Throws rtmot::InputError (ExitCode::network) naming address and port if it cannot bind
/// (port in use, address not local, bad address).
class UdpReceiver {
 public:
  UdpReceiver(const std::string& bind_address, std::uint16_t port);

  /// Waits up to `timeout_ms` for one datagram and copies it into `buffer`; `size` gets its length.
  /// A datagram longer than `capacity` is cut to `capacity` and `truncated` is set (then it will
  /// not decode). A signal interrupts the wait (status interrupted). Throws InputError on socket
  /// errors.
  ReceiveStatus receive(std::uint8_t* buffer, std::size_t capacity, int timeout_ms,
                        std::size_t& size, bool& truncated);

  /// The port actually bound (the ephemeral one when constructed with 0).
  std::uint16_t port() const { return port_; }
  const std::string& local_address() const { return local_address_; }

 private:
  SocketHandle socket_;
  std::string local_address_;
  std::uint16_t port_{0};
};

}  // namespace rtmot::platform
