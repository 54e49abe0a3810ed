#include "stereo_io/board_client.hpp"

#include <stdexcept>
#include <string>

#include "stereo/stage_table.hpp"

namespace stereo::board {

Client::Client(io::SerialPort& port, std::chrono::milliseconds timeout)
    : port_(port), timeout_(timeout) {}

std::vector<std::uint8_t> Client::exchange(const std::vector<std::uint8_t>& command,
                                           std::size_t reply_bytes, const char* what) {
    try {
        std::vector<std::uint8_t> reply = port_.transfer(command, reply_bytes, timeout_);
        sent_ += command.size();
        received_ += reply.size();
        return reply;
    } catch (const io::SerialTimeout& timeout) {
        throw NoAnswer(std::string("the board did not answer the ") + what +
                       " command: " + timeout.what() +
                       "; is it an iCEBreaker flashed with stereo_board_top, at this "
                       "baud rate? (docs/board.md)");
    }
}

Identity Client::identify() {
    port_.drain_input();
    const Identity identity =
        decode_identity(exchange(identify_command(), kIdentifyReplyBytes, "identify"));
    if (identity.id != table::kRegmapId) {
        throw std::runtime_error("the device on '" + port_.path() + "' answered with ID " +
                                 std::to_string(identity.id) + ", not the stereo core's " +
                                 std::to_string(table::kRegmapId));
    }
    return identity;
}

std::uint8_t Client::configure(const Config& config) {
    return decode_ack(exchange(configure_command(config), kAckReplyBytes, "configure"));
}

std::uint8_t Client::clear() {
    return decode_ack(exchange(clear_command(), kAckReplyBytes, "clear"));
}

ValidatedDisparity Client::frame(const Image& left, const Image& right) {
    const std::size_t beats = static_cast<std::size_t>(left.width) * left.height;
    return decode_beats(exchange(frame_command(left, right), kBeatBytes * beats, "frame"),
                        left.width, left.height);
}

void check_fits(const Identity& board, int width, int height, const Config& config) {
    auto fail = [](const std::string& what) {
        throw std::invalid_argument(what + " (the board's build, docs/board.md)");
    };
    if (width > board.width || height > board.height) {
        fail("the frame is " + std::to_string(width) + "x" + std::to_string(height) +
             ", the board takes at most " + std::to_string(board.width) + "x" +
             std::to_string(board.height));
    }
    if (config.ndisp < 1 || config.ndisp > board.ndisp) {
        fail("ndisp " + std::to_string(config.ndisp) + ": the board has " +
             std::to_string(board.ndisp) + " labels");
    }
    if (2 * config.radius + 1 != board.window) {
        fail("window " + std::to_string(2 * config.radius + 1) + ": the board's kernel is " +
             std::to_string(board.window) + "x" + std::to_string(board.window));
    }
    if (config.min_disp > board.max_min_disp || config.min_disp < -board.max_min_disp) {
        fail("min-disp " + std::to_string(config.min_disp) +
             ": the board takes |min-disp| <= " + std::to_string(board.max_min_disp));
    }
}

}  // namespace stereo::board
