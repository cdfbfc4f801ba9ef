#include "mvw/process/Wire.h"

#include <poll.h>
#include <sys/socket.h>

#include <cerrno>

namespace mvw::process {

bool sendAll(int fd, const void* data, std::size_t size) {
  const char* p = static_cast<const char*>(data);
  while (size > 0) {
    const ssize_t n = ::send(fd, p, size, MSG_NOSIGNAL);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    p += n;
    size -= static_cast<std::size_t>(n);
  }
  return true;
}

bool receiveAll(int fd, void* data, std::size_t size) {
  char* p = static_cast<char*>(data);
  while (size > 0) {
    const ssize_t n = ::recv(fd, p, size, 0);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    p += n;
    size -= static_cast<std::size_t>(n);
  }
  return true;
}

bool receiveAllBy(int fd, void* data, std::size_t size,
                  std::chrono::steady_clock::time_point deadline) {
  char* p = static_cast<char*>(data);
  while (size > 0) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
                          deadline - std::chrono::steady_clock::now())
                          .count();
    if (left <= 0) throw WireTimeout{};
    pollfd waitFor{fd, POLLIN, 0};
    const int ready = ::poll(&waitFor, 1, static_cast<int>(std::min<long long>(left, 1000)));
    if (ready < 0 && errno != EINTR) return false;
    if (ready <= 0) continue;
    const ssize_t n = ::recv(fd, p, size, MSG_DONTWAIT);
    if (n < 0 && (errno == EINTR || errno == EAGAIN)) continue;
    if (n <= 0) return false;
    p += n;
    size -= static_cast<std::size_t>(n);
  }
  return true;
}

void Message::append(const void* data, std::size_t size) {
  const char* p = static_cast<const char*>(data);
  bytes_.insert(bytes_.end(), p, p + size);
}

void Message::put(const std::string& text) {
  put(static_cast<std::uint64_t>(text.size()));
  append(text.data(), text.size());
}

bool receive(int fd, std::string& text, std::uint64_t maxSize) {
  std::uint64_t size = 0;
  if (!receive(fd, size) || size > maxSize) return false;
  text.resize(size);
  return size == 0 || receiveAll(fd, text.data(), size);
}

}  // namespace mvw::process
