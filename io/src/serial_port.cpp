#include "stereo_io/serial_port.hpp"

#include <fcntl.h>
#include <poll.h>
#include <termios.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <utility>

namespace stereo::io {
namespace {

struct BaudSpeed {
    int baud;
    speed_t speed;
};

constexpr std::array<BaudSpeed, 20> kSpeeds = {{
    {1200, B1200},       {2400, B2400},       {4800, B4800},       {9600, B9600},
    {19200, B19200},     {38400, B38400},     {57600, B57600},     {115200, B115200},
    {230400, B230400},   {460800, B460800},   {500000, B500000},   {576000, B576000},
    {921600, B921600},   {1000000, B1000000}, {1152000, B1152000}, {1500000, B1500000},
    {2000000, B2000000}, {2500000, B2500000}, {3000000, B3000000}, {4000000, B4000000},
}};

speed_t speed_of(int baud) {
    for (const BaudSpeed& entry : kSpeeds) {
        if (entry.baud == baud) {
            return entry.speed;
        }
    }
    std::string rates;
    for (const BaudSpeed& entry : kSpeeds) {
        rates += (rates.empty() ? "" : ", ") + std::to_string(entry.baud);
    }
    throw std::invalid_argument("--baud " + std::to_string(baud) + " is not a standard rate (" +
                                rates + ")");
}

std::string system_error(const std::string& what) {
    return what + ": " + std::strerror(errno);
}

}  // namespace

bool supported_baud(int baud) {
    for (const BaudSpeed& entry : kSpeeds) {
        if (entry.baud == baud) {
            return true;
        }
    }
    return false;
}

SerialPort::SerialPort(const std::string& path, int baud) : path_(path) {
    const speed_t speed = speed_of(baud);
    fd_ = ::open(path.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
    if (fd_ < 0) {
        throw std::runtime_error(system_error("cannot open serial port '" + path + "'"));
    }
    termios tty{};
    if (::tcgetattr(fd_, &tty) != 0) {
        const std::string message = system_error("'" + path + "' is not a serial port");
        ::close(fd_);
        throw std::runtime_error(message);
    }
    ::cfmakeraw(&tty);  // 8 data bits, no parity, no echo, no line editing
    tty.c_cflag &= ~static_cast<tcflag_t>(CSTOPB | CRTSCTS | PARENB);
    tty.c_cflag |= CLOCAL | CREAD | CS8;
    tty.c_iflag &= ~static_cast<tcflag_t>(IXON | IXOFF | IXANY);
    tty.c_cc[VMIN] = 0;
    tty.c_cc[VTIME] = 0;
    if (::cfsetispeed(&tty, speed) != 0 || ::cfsetospeed(&tty, speed) != 0 ||
        ::tcsetattr(fd_, TCSANOW, &tty) != 0) {
        const std::string message = system_error("cannot configure serial port '" + path + "'");
        ::close(fd_);
        throw std::runtime_error(message);
    }
    drain_input();
}

SerialPort::~SerialPort() {
    if (fd_ >= 0) {
        ::close(fd_);
    }
}

void SerialPort::drain_input() {
    ::tcflush(fd_, TCIFLUSH);
}

std::vector<std::uint8_t> SerialPort::transfer(std::span<const std::uint8_t> out,
                                               std::size_t reply_bytes,
                                               std::chrono::milliseconds idle_timeout) {
    std::vector<std::uint8_t> reply(reply_bytes);
    std::size_t written = 0;
    std::size_t read = 0;
    auto last_progress = std::chrono::steady_clock::now();
    while (written < out.size() || read < reply_bytes) {
        pollfd poller{fd_, 0, 0};
        if (read < reply_bytes) {
            poller.events |= POLLIN;
        }
        if (written < out.size()) {
            poller.events |= POLLOUT;
        }
        const auto waited = std::chrono::steady_clock::now() - last_progress;
        // Rounded up, so that the timeout never fires early.
        const auto left = std::chrono::ceil<std::chrono::milliseconds>(idle_timeout - waited);
        if (left.count() <= 0) {
            throw SerialTimeout("no answer from '" + path_ + "' within " +
                                std::to_string(idle_timeout.count()) + " ms (sent " +
                                std::to_string(written) + " of " + std::to_string(out.size()) +
                                " bytes, received " + std::to_string(read) + " of " +
                                std::to_string(reply_bytes) + ")");
        }
        const int ready = ::poll(&poller, 1, static_cast<int>(left.count()));
        if (ready < 0) {
            if (errno == EINTR) {
                continue;
            }
            throw std::runtime_error(system_error("poll on '" + path_ + "'"));
        }
        bool progress = false;
        if ((poller.revents & POLLOUT) != 0) {
            const ssize_t n = ::write(fd_, out.data() + written, out.size() - written);
            if (n > 0) {
                written += static_cast<std::size_t>(n);
                progress = true;
            } else if (n < 0 && errno != EAGAIN && errno != EINTR) {
                throw std::runtime_error(system_error("write to '" + path_ + "'"));
            }
        }
        if ((poller.revents & (POLLIN | POLLHUP | POLLERR)) != 0 && read < reply_bytes) {
            const ssize_t n = ::read(fd_, reply.data() + read, reply_bytes - read);
            if (n > 0) {
                read += static_cast<std::size_t>(n);
                progress = true;
            } else if (n < 0 && errno != EAGAIN && errno != EINTR) {
                throw std::runtime_error(system_error("read from '" + path_ + "'"));
            }
        }
        if (progress) {
            last_progress = std::chrono::steady_clock::now();
        } else if ((poller.revents & (POLLHUP | POLLERR)) != 0) {
            // The other end is gone: wait out the timeout without spinning.
            ::usleep(1000);
        }
    }
    return reply;
}

}  // namespace stereo::io
