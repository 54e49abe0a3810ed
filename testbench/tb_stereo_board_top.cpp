// stereo_board_top (the iCEBreaker build, docs/board.md) through its UART pins: the testbench
// drives uart_rx bit by bit with the byte protocol (stereo_io/board_protocol.hpp) and decodes
// uart_tx with a receiver of its own that samples each bit in its middle and checks every stop
// bit. Frames of a real crop (Aloe) and of random images, under random gaps between the host's
// bytes, are compared beat for beat with stereo::match_validated; the identify reply, an
// out-of-range configuration (clamped, status bit), the clear command, a garbage byte, a UART
// framing error and an abandoned frame (idle timeout, then clear) are checked too; and the link
// test build (stereo_uart_echo_top) echoes every byte.
#include <gtest/gtest.h>

#include <cstdint>
#include <deque>
#include <filesystem>
#include <optional>
#include <random>
#include <stdexcept>
#include <utility>
#include <vector>

#include <verilated.h>
#include <verilated_fst_c.h>

#include "Vstereo_arty_top.h"
#include "Vstereo_board_top.h"
#include "Vstereo_uart_echo_top.h"
#include "stereo/pipeline.hpp"
#include "stereo/stage_table.hpp"
#include "stereo_io/board_protocol.hpp"
#include "stereo_io/data_dir.hpp"
#include "stereo_io/io.hpp"
#include "stereo_io/test_support.hpp"
#include "tb_compare.hpp"
#include "tb_options.hpp"
#include "verilated_harness.hpp"

namespace stereo::sim {
namespace {

constexpr table::Params kConfig = table::verilated("Vstereo_board_top").params;
constexpr int kClocksPerBit = kConfig.clks_per_bit;
// stereo_board_top's defaults: POR_BITS 8, TIMEOUT_BITS 14.
constexpr std::uint64_t kPowerOnClocks = 1U << 8;
constexpr std::uint64_t kTimeoutClocks = static_cast<std::uint64_t>(kClocksPerBit) << 14;

// A Verilated board design (stereo_board_top, or its link test stereo_uart_echo_top) with the
// host's UART on its pins.
template <class Model>
class UartSim {
  public:
    explicit UartSim(std::uint32_t seed = 1, double gap = 0.0)
        : harness_("board"), rng_(seed), gap_(gap) {
        if (const std::string path = tb::trace_path(); !path.empty()) {
            harness_.trace_to(path);
        }
        Model& m = harness_.model();
        m.uart_rx = 1;
        m.button_n = 1;
        idle(kPowerOnClocks + 10);
    }

    // Queues bytes for the host's transmitter; `stop_bit` 0 sends them with a broken stop bit.
    void send(const std::vector<std::uint8_t>& bytes, bool stop_bit = true) {
        for (const std::uint8_t byte : bytes) {
            to_board_.push_back({byte, stop_bit});
        }
    }

    // Runs until `count` bytes came back (and everything queued has been sent), or throws after
    // `max_clocks`.
    std::vector<std::uint8_t> receive(std::size_t count, std::uint64_t max_clocks) {
        for (std::uint64_t clock = 0; received_.size() < count || !to_board_.empty() || sending_;
             ++clock) {
            if (clock >= max_clocks) {
                throw std::runtime_error("the board sent " + std::to_string(received_.size()) +
                                         " of " + std::to_string(count) + " bytes");
            }
            step();
        }
        std::vector<std::uint8_t> out(received_.begin(),
                                      received_.begin() + static_cast<std::ptrdiff_t>(count));
        received_.erase(received_.begin(), received_.begin() + static_cast<std::ptrdiff_t>(count));
        return out;
    }

    // Clocks with the line idle once everything queued has gone out.
    void idle(std::uint64_t clocks) {
        while (!to_board_.empty() || sending_) {
            step();
        }
        for (std::uint64_t i = 0; i < clocks; ++i) {
            step();
        }
    }

    std::size_t unexpected_bytes() const { return received_.size(); }
    int host_framing_errors() const { return host_framing_errors_; }
    // The status LED: the iCEBreaker's red one (active low), the Arty's led[1] (active high).
    bool red_led() const {
        const Model& m = harness_.model();
        if constexpr (requires { m.led_red_n; }) {
            return m.led_red_n == 0;
        } else {
            return (m.led >> 1 & 1U) != 0;
        }
    }

    board::Identity identify() {
        send(board::identify_command());
        return board::decode_identity(receive(board::kIdentifyReplyBytes, 100'000));
    }

    std::uint8_t configure(const board::Config& config) {
        send(board::configure_command(config));
        return board::decode_ack(receive(board::kAckReplyBytes, 100'000));
    }

    std::uint8_t clear() {
        send(board::clear_command());
        return board::decode_ack(receive(board::kAckReplyBytes, 100'000));
    }

    ValidatedDisparity frame(const Image& left, const Image& right) {
        send(board::frame_command(left, right));
        const auto pixels = static_cast<std::uint64_t>(left.width) * left.height;
        // 60 bit times per pixel in, plus gaps and the pipeline's tail: a generous limit.
        const std::uint64_t limit = (pixels * 120 + 20'000) * kClocksPerBit;
        return board::decode_beats(receive(board::kBeatBytes * pixels, limit), left.width,
                                   left.height);
    }

  private:
    struct Byte {
        std::uint8_t value;
        bool stop_bit;
    };

    // One clock: the host's transmitter sets uart_rx, the host's receiver samples uart_tx.
    void step() {
        Model& m = harness_.model();
        drive_line();
        harness_.tick();
        sample_line(m.uart_tx != 0);
    }

    void drive_line() {
        Model& m = harness_.model();
        if (!sending_) {
            if (to_board_.empty()) {
                m.uart_rx = 1;
                return;
            }
            // Random idle bit times between the host's bytes.
            if (gap_ > 0.0 && std::bernoulli_distribution(gap_)(rng_)) {
                send_bits_ = {1};
            } else {
                const Byte byte = to_board_.front();
                to_board_.pop_front();
                send_bits_.clear();
                send_bits_.push_back(0);
                for (int b = 0; b < 8; ++b) {
                    send_bits_.push_back((byte.value >> b & 1U) != 0 ? 1 : 0);
                }
                send_bits_.push_back(byte.stop_bit ? 1 : 0);
            }
            sending_ = true;
            send_bit_ = 0;
            send_clock_ = 0;
        }
        m.uart_rx = send_bits_[send_bit_];
        if (++send_clock_ == kClocksPerBit) {
            send_clock_ = 0;
            if (++send_bit_ == send_bits_.size()) {
                sending_ = false;
            }
        }
    }

    // 8N1 receiver: a falling edge starts a byte; bit k is sampled (k + 0.5) bit times later.
    void sample_line(bool line) {
        if (!receiving_) {
            if (!line) {
                receiving_ = true;
                receive_clock_ = 0;
            }
            return;
        }
        ++receive_clock_;
        if (receive_clock_ % kClocksPerBit != kClocksPerBit / 2) {
            return;
        }
        const int bit = receive_clock_ / kClocksPerBit;  // 0: start, 1..8: data, 9: stop
        if (bit == 0) {
            if (line) {
                receiving_ = false;  // a glitch
            }
        } else if (bit <= 8) {
            receive_value_ = static_cast<std::uint8_t>(receive_value_ >> 1 | (line ? 0x80 : 0));
        } else {
            if (!line) {
                ++host_framing_errors_;
            }
            received_.push_back(receive_value_);
            receiving_ = false;
        }
    }

    VerilatedHarness<Model> harness_;
    std::mt19937 rng_;
    double gap_;
    std::deque<Byte> to_board_;
    std::vector<int> send_bits_;
    std::size_t send_bit_ = 0;
    int send_clock_ = 0;
    bool sending_ = false;
    bool receiving_ = false;
    int receive_clock_ = 0;
    std::uint8_t receive_value_ = 0;
    int host_framing_errors_ = 0;
    std::vector<std::uint8_t> received_;
};

using BoardSim = UartSim<Vstereo_board_top>;

MatchParams board_params(int ndisp, bool use_ca) {
    return {ndisp, kConfig.window, fx::kDefaultSigma, use_ca};
}

// Configures the board for `params` on the pair's size, streams it and compares every beat.
template <class Board>
::testing::AssertionResult frame_equals_model(Board& board, const Image& left, const Image& right,
                                              const MatchParams& params) {
    const std::uint8_t status = board.configure(board::config_for(left.width, left.height, params));
    if (status != 0) {
        return ::testing::AssertionFailure() << "status after configure: " << int{status};
    }
    return tb::same_validated(match_validated(left, right, params), board.frame(left, right));
}

TEST(BoardProtocol, IdentifyReportsTheBuild) {
    BoardSim board;
    const board::Identity identity = board.identify();
    EXPECT_EQ(identity.id, 0x53544552U);  // "STER", by hand
    tb::expect_reported_build(kConfig, identity.version, identity.width, identity.height,
                              identity.ndisp, identity.window, identity.max_min_disp);
    EXPECT_EQ(identity.status, 0);
    EXPECT_FALSE(board.red_led());
    EXPECT_EQ(board.host_framing_errors(), 0);
    EXPECT_EQ(board.unexpected_bytes(), 0U);
}

// A crop of the Aloe pair (downscaled 8x, as tb_stereo_top's real pairs): CA on and off, and
// stage 6 with a shifted range.
TEST(BoardFrames, AloeCropEqualsTheModel) {
    const std::filesystem::path left_path = io::aloe_dir() / "aloeL.jpg";
    const std::filesystem::path right_path = io::aloe_dir() / "aloeR.jpg";
    if (!std::filesystem::exists(left_path) || !std::filesystem::exists(right_path)) {
        GTEST_SKIP() << "Aloe pair not found in " << io::aloe_dir();
    }
    const auto pair = io::load_pair(left_path, right_path, 8);
    auto crop = [](const Image& image) {
        Image out(kConfig.width, kConfig.height, image.channels);
        for (int y = 0; y < kConfig.height; ++y) {
            for (int x = 0; x < kConfig.width; ++x) {
                for (int c = 0; c < image.channels; ++c) {
                    out.at(x, y, c) = image.at(50 + x, 40 + y, c);
                }
            }
        }
        return out;
    };
    const Image left = crop(pair.left);
    const Image right = crop(pair.right);
    BoardSim board(tb::test_seed(), 0.05);
    EXPECT_TRUE(frame_equals_model(board, left, right, board_params(kConfig.ndisp, true)));
    MatchParams stage6 = board_params(kConfig.ndisp, true);
    stage6.min_disp = -3;
    stage6.validation = {true, 15, true, 1, true};
    EXPECT_TRUE(frame_equals_model(board, left, right, stage6));
    EXPECT_EQ(board.identify().status, 0);
    EXPECT_EQ(board.host_framing_errors(), 0);
}

// Random pairs at two sizes, with and without CA and stage 6, byte gaps on the host side.
TEST(BoardFrames, RandomPairsEqualTheModel) {
    const std::uint32_t seed = tb::test_seed();
    std::mt19937 rng(seed);
    BoardSim board(seed, 0.1);
    {
        const Image left = test::random_image(kConfig.width, kConfig.height, 3, rng);
        const Image right = test::shifted_copy(left, 3, 20, rng);
        EXPECT_TRUE(frame_equals_model(board, left, right, board_params(kConfig.ndisp, false)));
    }
    {
        const Image left = test::random_image(37, 23, 3, rng);
        const Image right = test::shifted_copy(left, 2, 20, rng);
        MatchParams params = board_params(12, true);
        params.min_disp = 2;
        params.validation = ValidationParams::all_on();
        params.validation.lr_tolerance = 1;
        EXPECT_TRUE(frame_equals_model(board, left, right, params));
    }
    EXPECT_EQ(board.identify().status, 0);
    EXPECT_EQ(board.host_framing_errors(), 0);
    EXPECT_EQ(board.unexpected_bytes(), 0U);
}

// ndisp 0 is out of range: the core clamps it to NDISP (the model at NDISP labels) and sets the
// status bit; the clear command resets it. A radius other than WINDOW / 2 is flagged the same.
TEST(BoardErrors, OutOfRangeConfigurationIsClampedAndFlagged) {
    std::mt19937 rng(tb::test_seed());
    const Image left = test::random_image(24, 16, 3, rng);
    const Image right = test::shifted_copy(left, 2, 10, rng);
    BoardSim board;
    board::Config config = board::config_for(24, 16, board_params(kConfig.ndisp, true));
    config.ndisp = 0;
    EXPECT_EQ(board.configure(config), 0);  // flagged when a frame starts
    EXPECT_TRUE(tb::same_validated(match_validated(left, right, board_params(kConfig.ndisp, true)),
                                   board.frame(left, right)));
    EXPECT_EQ(board.identify().status, 1U << board::kStatusConfigClamped);
    EXPECT_TRUE(board.red_led());
    EXPECT_EQ(board.clear(), 1U << board::kStatusConfigClamped);  // the status it cleared
    EXPECT_FALSE(board.red_led());
    config.ndisp = kConfig.ndisp;
    config.radius = kConfig.window / 2 - 1;
    EXPECT_EQ(board.configure(config), 0);
    EXPECT_TRUE(tb::same_validated(match_validated(left, right, board_params(kConfig.ndisp, true)),
                                   board.frame(left, right)));
    EXPECT_EQ(board.identify().status, 1U << board::kStatusConfigClamped);
}

TEST(BoardErrors, GarbageUnknownOpcodeAndFramingErrorAreFlagged) {
    BoardSim board;
    board.send({0x00});  // not a header
    board.idle(20 * kClocksPerBit);
    EXPECT_EQ(board.identify().status, 1U << board::kStatusProtocolError);
    EXPECT_EQ(board.clear(), 1U << board::kStatusProtocolError);  // the status it cleared
    EXPECT_EQ(board.identify().status, 0);
    board.send({board::kHeader, 'Z'});  // unknown opcode
    board.idle(30 * kClocksPerBit);
    EXPECT_EQ(board.clear(), 1U << board::kStatusProtocolError);
    board.send({0xFF}, false);  // stop bit 0
    board.idle(30 * kClocksPerBit);
    // 0xFF is not a header either.
    EXPECT_EQ(board.identify().status,
              1U << board::kStatusFramingError | 1U << board::kStatusProtocolError);
    EXPECT_EQ(board.clear(), 1U << board::kStatusFramingError | 1U << board::kStatusProtocolError);
    EXPECT_EQ(board.identify().status, 0);
    EXPECT_EQ(board.unexpected_bytes(), 0U);
}

// Half a frame, then silence: the board times out, and the clear command brings the core back
// out of the frame; the next frame is exact again.
TEST(BoardErrors, AbandonedFrameTimesOutAndClearRecovers) {
    std::mt19937 rng(tb::test_seed());
    const Image left = test::random_image(20, 12, 3, rng);
    const Image right = test::shifted_copy(left, 3, 10, rng);
    const MatchParams params = board_params(8, true);
    BoardSim board;
    EXPECT_EQ(board.configure(board::config_for(20, 12, params)), 0);
    std::vector<std::uint8_t> half = board::frame_command(left, right);
    half.resize(2 + board::kPixelBytes * 20 * 6);
    board.send(half);
    board.idle(kTimeoutClocks + 100 * kClocksPerBit);
    const std::size_t partial = board.unexpected_bytes();  // beats of the half frame, if any
    (void)board.receive(partial, 1);
    // The core holds pixels whose beats never come, so only the clear is answered: its reply
    // shows the timeout, and the status is clear after it.
    EXPECT_EQ(board.clear(), 1U << board::kStatusProtocolError);
    EXPECT_EQ(board.identify().status, 0);
    EXPECT_TRUE(tb::same_validated(match_validated(left, right, params), board.frame(left, right)));
    EXPECT_EQ(board.identify().status, 0);
}

// The link test: every byte comes back, back to back and with gaps; a broken stop bit lights
// the red LED.
// The Arty A7 top (rtl/stereo_arty_top.sv, the board top at the same size and UART speed): the
// same protocol through its pins, frames equal to the model, the status on led[1].
TEST(ArtyBoard, IdentifyFramesAndStatusLed) {
    constexpr table::Params arty = table::verilated("Vstereo_arty_top").params;
    static_assert(arty.clks_per_bit == kClocksPerBit, "the testbench's UART speed");
    const std::uint32_t seed = tb::test_seed();
    std::mt19937 rng(seed);
    UartSim<Vstereo_arty_top> board(seed, 0.05);
    const board::Identity identity = board.identify();
    EXPECT_EQ(identity.id, 0x53544552U);  // "STER", by hand
    EXPECT_EQ(identity.width, arty.width);
    EXPECT_EQ(identity.height, arty.height);
    EXPECT_EQ(identity.ndisp, arty.ndisp);
    EXPECT_EQ(identity.window, arty.window);
    EXPECT_EQ(identity.status, 0);
    {
        const Image left = test::random_image(arty.width, arty.height, 3, rng);
        const Image right = test::shifted_copy(left, 3, 20, rng);
        MatchParams params{arty.ndisp, arty.window, fx::kDefaultSigma, true};
        params.min_disp = -2;
        params.validation = ValidationParams::all_on();
        params.validation.lr_tolerance = 1;
        EXPECT_TRUE(frame_equals_model(board, left, right, params));
    }
    EXPECT_FALSE(board.red_led());
    // An out-of-range configuration: clamped when the frame starts, its status bit on led[1].
    const MatchParams all{arty.ndisp, arty.window, fx::kDefaultSigma, true};
    const Image left = test::random_image(24, 16, 3, rng);
    const Image right = test::shifted_copy(left, 2, 10, rng);
    board::Config config = board::config_for(24, 16, all);
    config.ndisp = 0;
    EXPECT_EQ(board.configure(config), 0);
    EXPECT_TRUE(tb::same_validated(match_validated(left, right, all), board.frame(left, right)));
    EXPECT_EQ(board.identify().status, 1U << board::kStatusConfigClamped);
    EXPECT_TRUE(board.red_led());
    EXPECT_EQ(board.host_framing_errors(), 0);
    EXPECT_EQ(board.unexpected_bytes(), 0U);
}

TEST(UartEcho, EveryByteComesBack) {
    const std::uint32_t seed = tb::test_seed();
    std::mt19937 rng(seed);
    UartSim<Vstereo_uart_echo_top> echo(seed, 0.2);
    std::vector<std::uint8_t> bytes(300);
    for (std::uint8_t& byte : bytes) {
        byte = static_cast<std::uint8_t>(rng());
    }
    echo.send(bytes);
    EXPECT_EQ(echo.receive(bytes.size(), 20'000 * kClocksPerBit), bytes);
    EXPECT_EQ(echo.host_framing_errors(), 0);
    EXPECT_FALSE(echo.red_led());
    echo.send({0x55}, false);
    EXPECT_EQ(echo.receive(1, 40 * kClocksPerBit), std::vector<std::uint8_t>{0x55});
    EXPECT_TRUE(echo.red_led());
    EXPECT_EQ(echo.unexpected_bytes(), 0U);
}

}  // namespace
}  // namespace stereo::sim
