#include "platform/udp_socket.hpp"

#include <arpa/inet.h>
#include <netdb.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <memory>

#include "common/input_error.hpp"
#include "platform/host_port.hpp"

namespace rtmot::platform {
namespace {

static_assert(sizeof(sockaddr_storage) <= 128, "UdpSender::address_ holds a sockaddr_storage");

[[noreturn]] void throw_network(const std::string& endpoint, const std::string& problem) {
  throw InputError("udp://" + endpoint, 0, "", problem, ExitCode::network);
}

struct AddrinfoDeleter {
  void operator()(addrinfo* list) const { freeaddrinfo(list); }
};
using AddrinfoList = std::unique_ptr<addrinfo, AddrinfoDeleter>;

AddrinfoList resolve(const std::string& host, std::uint16_t port, bool passive,
                     const std::string& endpoint) {
  addrinfo hints{};
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_DGRAM;
  hints.ai_protocol = IPPROTO_UDP;
  hints.ai_flags = passive ? AI_PASSIVE : 0;
  addrinfo* list = nullptr;
  const std::string service = std::to_string(port);
  const int status =
      getaddrinfo(host.empty() ? nullptr : host.c_str(), service.c_str(), &hints, &list);
  if (status != 0) {
    throw_network(endpoint, std::string("cannot resolve host: ") + gai_strerror(status));
  }
  return AddrinfoList(list);
}

std::string errno_text(int error) {
  return std::strerror(error);
}

// Tries the resolved addresses in order: opens a UDP socket for each and asks `suits` whether it
// will do (an empty string) or why not. Returns the first that suits; throws with the last reason.
template <typename Suits>
SocketHandle open_first(const AddrinfoList& list, const std::string& endpoint, Suits suits) {
  std::string failure = "no address";
  for (const addrinfo* candidate = list.get(); candidate != nullptr;
       candidate = candidate->ai_next) {
    SocketHandle socket(::socket(candidate->ai_family, candidate->ai_socktype | SOCK_CLOEXEC,
                                 candidate->ai_protocol));
    if (socket.get() < 0) {
      failure = "cannot open socket: " + errno_text(errno);
      continue;
    }
    failure = suits(socket, *candidate);
    if (failure.empty()) return socket;
  }
  throw_network(endpoint, failure);
}

}  // namespace

SocketHandle::~SocketHandle() {
  if (fd_ >= 0) ::close(fd_);
}

SocketHandle& SocketHandle::operator=(SocketHandle&& other) noexcept {
  if (this != &other) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = other.release();
  }
  return *this;
}

int SocketHandle::release() noexcept {
  const int fd = fd_;
  fd_ = -1;
  return fd;
}

UdpSender::UdpSender(const std::string& host, std::uint16_t port)
    : destination_(format_host_port(host, port)) {
  if (host.empty()) throw_network(destination_, "empty host");
  if (port == 0) throw_network(destination_, "port 0 is not a destination");
  const AddrinfoList list = resolve(host, port, false, destination_);
  socket_ = open_first(list, destination_, [this](const SocketHandle&, const addrinfo& candidate) {
    std::memcpy(address_, candidate.ai_addr, candidate.ai_addrlen);
    address_length_ = static_cast<unsigned>(candidate.ai_addrlen);
    return std::string();
  });
}

bool UdpSender::send(const std::uint8_t* data, std::size_t size) {
  // sendto rather than connect+send: a connected UDP socket turns an ICMP "port unreachable" from
  // an absent listener into an error on the next send; a sender must not care whether anyone
  // listens.
  ssize_t sent = -1;
  do {
    sent = ::sendto(socket_.get(), data, size, MSG_NOSIGNAL,
                    reinterpret_cast<const sockaddr*>(address_),
                    static_cast<socklen_t>(address_length_));
  } while (sent < 0 && errno == EINTR);
  if (sent < 0) {
    // Allocates only on failure (the string grows to the message once and is then reused).
    last_error_.assign(std::strerror(errno));
    return false;
  }
  return static_cast<std::size_t>(sent) == size;
}

UdpReceiver::UdpReceiver(const std::string& bind_address, std::uint16_t port)
    : local_address_(format_host_port(bind_address, port)) {
  const AddrinfoList list = resolve(bind_address, port, true, local_address_);
  socket_ = open_first(
      list, local_address_,
      [&](const SocketHandle& socket, const addrinfo& candidate) -> std::string {
        if (::bind(socket.get(), candidate.ai_addr, candidate.ai_addrlen) != 0) {
          const int error = errno;
          std::string failure = "cannot bind: " + errno_text(error);
          if (error == EADDRINUSE) {
            failure += " (is another listener running on this port?)";
          }
          return failure;
        }
        sockaddr_storage bound{};
        socklen_t bound_length = sizeof bound;
        if (::getsockname(socket.get(), reinterpret_cast<sockaddr*>(&bound), &bound_length) != 0) {
          return "getsockname: " + errno_text(errno);
        }
        port_ = bound.ss_family == AF_INET6
                    ? ntohs(reinterpret_cast<const sockaddr_in6*>(&bound)->sin6_port)
                    : ntohs(reinterpret_cast<const sockaddr_in*>(&bound)->sin_port);
        return std::string();
      });
  local_address_ = format_host_port(bind_address, port_);
}

ReceiveStatus UdpReceiver::receive(std::uint8_t* buffer, std::size_t capacity, int timeout_ms,
                                   std::size_t& size, bool& truncated) {
  pollfd waiting{socket_.get(), POLLIN, 0};
  const int ready = ::poll(&waiting, 1, timeout_ms);
  if (ready < 0) {
    if (errno == EINTR) return ReceiveStatus::interrupted;
    throw_network(local_address_, "poll: " + errno_text(errno));
  }
  if (ready == 0) return ReceiveStatus::timeout;
  // MSG_TRUNC makes Linux return the datagram's real length even when it did not fit.
  const ssize_t length = ::recv(socket_.get(), buffer, capacity, MSG_TRUNC);
  if (length < 0) {
    if (errno == EINTR) return ReceiveStatus::interrupted;
    if (errno == EAGAIN || errno == EWOULDBLOCK) return ReceiveStatus::timeout;
    throw_network(local_address_, "receive: " + errno_text(errno));
  }
  truncated = static_cast<std::size_t>(length) > capacity;
  size = truncated ? capacity : static_cast<std::size_t>(length);
  return ReceiveStatus::datagram;
}

}  // namespace rtmot::platform
