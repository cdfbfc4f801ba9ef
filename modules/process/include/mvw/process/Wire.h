#pragma once
// Bytes over a stream socket between two of mvw's processes: the process pool and its launcher,
// a reader and its decoder child (Helper.h). Sends never raise SIGPIPE (MSG_NOSIGNAL): a peer
// that is gone is a false return, not the end of this process. Values go as their bytes (both
// ends are the same build on the same machine); a string as its 64-bit length, then its bytes.
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace mvw::process {

// False when the peer is gone.
bool sendAll(int fd, const void* data, std::size_t size);

// False at the end of the stream (the peer is gone) before `size` bytes came.
bool receiveAll(int fd, void* data, std::size_t size);

// As receiveAll, waiting no later than `deadline`; throws WireTimeout past it.
struct WireTimeout {};
bool receiveAllBy(int fd, void* data, std::size_t size,
                  std::chrono::steady_clock::time_point deadline);

// A message assembled, then sent at once.
class Message {
 public:
  template <class T>
  void put(const T& value) {
    append(&value, sizeof value);
  }
  void put(const std::string& text);
  bool send(int fd) const { return sendAll(fd, bytes_.data(), bytes_.size()); }

 private:
  void append(const void* data, std::size_t size);
  std::vector<char> bytes_;
};

template <class T>
bool receive(int fd, T& value) {
  return receiveAll(fd, &value, sizeof value);
}

// A string of at most `maxSize` bytes (a longer one is a false return: the peer is not to be
// trusted with this process's memory).
bool receive(int fd, std::string& text, std::uint64_t maxSize = std::uint64_t(1) << 30);

}  // namespace mvw::process
