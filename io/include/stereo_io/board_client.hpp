// The host side of the iCEBreaker board (docs/board.md): identify, configure, stream a frame and
// read its beats back, clear the status; each a command of stereo_io/board_protocol.hpp over a
// serial port. `stereo board` drives it; the tests drive it against an emulated board.
#pragma once

#include <chrono>
#include <cstdint>
#include <optional>
#include <stdexcept>

#include "stereo/image.hpp"
#include "stereo/validated.hpp"
#include "stereo_io/board_protocol.hpp"
#include "stereo_io/serial_port.hpp"

namespace stereo::board {

// The board did not answer a command within the timeout.
class NoAnswer : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

class Client {
  public:
    // `timeout`: the longest silence of the board inside a command's reply.
    Client(io::SerialPort& port, std::chrono::milliseconds timeout);

    // The identify reply; throws NoAnswer when the board does not answer (naming the port),
    // std::runtime_error when it answers with another ID than fx_pkg::REGMAP_ID. A board whose
    // core was left inside an abandoned frame answers only clear() (docs/board.md).
    Identity identify();
    // Writes the configuration registers; returns the status of the acknowledgement.
    std::uint8_t configure(const Config& config);
    // Clears the board's status (and a core left inside a frame); returns the status it cleared.
    std::uint8_t clear();
    // Streams the pair and decodes its width * height beats. The board must be configured for
    // the pair's size first. Throws std::runtime_error (the board's fault, not the options') when
    // a beat is impossible for the configuration sent: a reason code the core does not have, an
    // invalid pixel with a disparity, a valid one outside the searched range.
    ValidatedDisparity frame(const Image& left, const Image& right);

    std::uint64_t bytes_sent() const { return sent_; }
    std::uint64_t bytes_received() const { return received_; }

  private:
    std::vector<std::uint8_t> exchange(const std::vector<std::uint8_t>& command,
                                       std::size_t reply_bytes, const char* what);

    io::SerialPort& port_;
    std::chrono::milliseconds timeout_;
    std::optional<Identity> identity_;  // the last identify reply
    std::optional<Config> configured_;  // the last configuration acknowledged
    std::uint64_t sent_ = 0;
    std::uint64_t received_ = 0;
};

// Throws std::runtime_error when an identify reply is impossible for any build of the core
// (a frame side, label count, window or |min-disp| outside fx_pkg's limits): a corrupt link or
// another device, reported as such instead of as options the board cannot take.
void check_identity(const Identity& board, const std::string& port);

// Throws std::runtime_error naming the first beat of `frame` that the core cannot produce under
// `config` (see Client::frame).
void check_frame(const ValidatedDisparity& frame, const Config& config);

// Checks that a frame and a configuration are within what the board was built for (its identify
// reply); throws std::invalid_argument naming the first limit exceeded.
void check_fits(const Identity& board, int width, int height, const Config& config);

}  // namespace stereo::board
