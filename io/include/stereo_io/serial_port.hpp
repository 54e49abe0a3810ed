// A serial port in raw 8N1 mode (POSIX termios), and the transfer the board protocol needs:
// writing a command while reading its reply, so that neither side's buffer fills up and stalls
// the other (docs/board.md). Used by `stereo board`; the tests use it on a pseudo-terminal.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace stereo::io {

// No byte arrived within the timeout.
class SerialTimeout : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

class SerialPort {
  public:
    // Opens `path` (a tty) raw, 8N1, no flow control, at `baud`. Throws std::invalid_argument
    // for a baud rate termios has no constant for, std::runtime_error when the port cannot be
    // opened or configured (the message names the path and the reason).
    SerialPort(const std::string& path, int baud);
    SerialPort(const SerialPort&) = delete;
    SerialPort& operator=(const SerialPort&) = delete;
    ~SerialPort();

    const std::string& path() const { return path_; }

    // Writes `out` and reads exactly `reply_bytes`, both at once. Throws SerialTimeout when
    // nothing moves in either direction for `idle_timeout`.
    std::vector<std::uint8_t> transfer(std::span<const std::uint8_t> out, std::size_t reply_bytes,
                                       std::chrono::milliseconds idle_timeout);

    // Discards whatever has arrived and not been read.
    void drain_input();

  private:
    std::string path_;
    int fd_ = -1;
};

// Whether termios has a speed constant for `baud` (the rates SerialPort accepts).
bool supported_baud(int baud);

}  // namespace stereo::io
