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

namespace {

bool fits(const Identity& board, const Config& config) {
    try {
        check_fits(board, config.width, config.height, config);
        return true;
    } catch (const std::invalid_argument&) {
        return false;
    }
}

}  // namespace

Identity Client::identify() {
    port_.drain_input();
    const Identity identity =
        decode_identity(exchange(identify_command(), kIdentifyReplyBytes, "identify"));
    if (identity.id != table::kRegmapId) {
        throw std::runtime_error("the device on '" + port_.path() + "' answered with ID " +
                                 std::to_string(identity.id) + ", not the stereo core's " +
                                 std::to_string(table::kRegmapId));
    }
    check_identity(identity, port_.path());
    identity_ = identity;
    return identity;
}

std::uint8_t Client::configure(const Config& config) {
    const std::uint8_t status =
        decode_ack(exchange(configure_command(config), kAckReplyBytes, "configure"));
    configured_ = config;
    return status;
}

std::uint8_t Client::clear() {
    return decode_ack(exchange(clear_command(), kAckReplyBytes, "clear"));
}

ValidatedDisparity Client::frame(const Image& left, const Image& right) {
    const std::size_t beats = static_cast<std::size_t>(left.width) * left.height;
    ValidatedDisparity result = decode_beats(
        exchange(frame_command(left, right), kBeatBytes * beats, "frame"), left.width, left.height);
    if (configured_) {
        Config bounds = *configured_;
        if (identity_ && !fits(*identity_, bounds)) {
            // The core clamps a configuration outside its build: any range it can search.
            bounds.min_disp = -identity_->max_min_disp;
            bounds.ndisp = identity_->ndisp + 2 * identity_->max_min_disp;
        }
        check_frame(result, bounds);
    }
    return result;
}

void check_identity(const Identity& board, const std::string& port) {
    const bool possible = board.width >= 1 && board.width <= table::kMaxFrameSide &&
                          board.height >= 1 && board.height <= table::kMaxFrameSide &&
                          board.ndisp >= 1 && board.ndisp <= fx::kMaxDisparities &&
                          board.window >= 1 && board.window <= fx::kMaxWindow &&
                          board.window % 2 == 1 && board.max_min_disp >= 0 &&
                          board.max_min_disp <= fx::kMaxMinDisparity;
    if (!possible) {
        throw std::runtime_error("the device on '" + port + "' reports an impossible build (" +
                                 std::to_string(board.width) + "x" + std::to_string(board.height) +
                                 ", " + std::to_string(board.ndisp) + " labels, window " +
                                 std::to_string(board.window) + ", |min-disp| " +
                                 std::to_string(board.max_min_disp) +
                                 "): a corrupt link or not the stereo core");
    }
}

void check_frame(const ValidatedDisparity& frame, const Config& config) {
    // Sub-pixel refinement moves a label by at most half a pixel: 8 sixteenths.
    const int lowest = config.min_disp * 16 - 8;
    const int highest = (config.min_disp + config.ndisp - 1) * 16 + 8;
    for (std::size_t i = 0; i < frame.fixed.size(); ++i) {
        const int reason = frame.reason[i];
        const int fixed = frame.fixed[i];
        std::string problem;
        if (reason > fx::kReasonLeftRight) {
            problem = "reason code " + std::to_string(reason) + ", which the core does not have";
        } else if (reason != fx::kReasonValid && fixed != 0) {
            problem = "an invalid pixel (reason " + std::to_string(reason) +
                      ") with the disparity " + std::to_string(fixed) + "/16";
        } else if (reason == fx::kReasonValid && (fixed < lowest || fixed > highest)) {
            problem = "the disparity " + std::to_string(fixed) + "/16 outside the searched " +
                      std::to_string(lowest) + ".." + std::to_string(highest);
        }
        if (!problem.empty()) {
            throw std::runtime_error("the board sent " + problem + " at pixel " +
                                     std::to_string(i % static_cast<std::size_t>(frame.width)) +
                                     "," +
                                     std::to_string(i / static_cast<std::size_t>(frame.width)) +
                                     ": a corrupt link or a faulty core");
        }
    }
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
