// The host side of the iCEBreaker build (docs/board.md): the byte protocol both ways, the serial
// port, the client and `stereo board`, against a board emulated on a pseudo-terminal: a thread
// serves the other end with the protocol and the golden model (stereo::match_validated), the
// way the RTL does (tb_stereo_board_top checks the RTL against the same model). `stereo board`
// and `stereo match` with the same options must write the same bytes.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <poll.h>
#include <pty.h>
#include <termios.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "cli.hpp"
#include "stereo/pipeline.hpp"
#include "stereo/stage_table.hpp"
#include "stereo_io/board_client.hpp"
#include "stereo_io/board_protocol.hpp"
#include "stereo_io/io.hpp"
#include "stereo_io/serial_port.hpp"
#include "stereo_io/test_support.hpp"
#include "temp_folder.hpp"

namespace stereo {
namespace {

using namespace std::chrono_literals;

// A board on a pseudo-terminal: the protocol of rtl/stereo_board_top.sv with the golden model
// in place of the core, including its clamping of out-of-range configurations. `mute`: a device
// that takes bytes and never answers. `stuck`: a board whose core an earlier host left inside a
// frame: like the RTL, it answers nothing but the clear command until it has been cleared.
class EmulatedBoard {
  public:
    // What a faulty link or core does to the frame's reply (the identity is faked by the test).
    enum class Fault { none, reason_code, invalid_with_disparity, out_of_range };

    explicit EmulatedBoard(board::Identity identity, bool mute = false, bool stuck = false,
                           Fault fault = Fault::none)
        : identity_(identity), mute_(mute), stuck_(stuck), fault_(fault) {
        if (::openpty(&master_, &slave_, nullptr, nullptr, nullptr) != 0) {
            throw std::runtime_error("openpty failed");
        }
        slave_path_ = ::ttyname(slave_);
        termios tty{};
        ::tcgetattr(slave_, &tty);
        ::cfmakeraw(&tty);
        ::tcsetattr(slave_, TCSANOW, &tty);
        // The emulator keeps its own slave descriptor open, so the master never sees a hang-up
        // between two clients.
        thread_ = std::thread([this] { serve(); });
    }
    EmulatedBoard(const EmulatedBoard&) = delete;
    EmulatedBoard& operator=(const EmulatedBoard&) = delete;
    ~EmulatedBoard() {
        stop_ = true;
        thread_.join();
        ::close(master_);
        ::close(slave_);
    }

    const std::string& path() const { return slave_path_; }
    int frames() const { return frames_; }

  private:
    void serve() {
        std::vector<std::uint8_t> buffer(4096);
        while (!stop_) {
            pollfd poller{master_, POLLIN, 0};
            if (::poll(&poller, 1, 20) <= 0) {
                continue;
            }
            const ssize_t n = ::read(master_, buffer.data(), buffer.size());
            if (n <= 0) {
                std::this_thread::sleep_for(1ms);
                continue;
            }
            if (mute_) {
                continue;
            }
            for (ssize_t i = 0; i < n; ++i) {
                take(buffer[static_cast<std::size_t>(i)]);
            }
        }
    }

    void reply(const std::vector<std::uint8_t>& bytes) {
        std::size_t written = 0;
        while (written < bytes.size() && !stop_) {
            const ssize_t n = ::write(master_, bytes.data() + written, bytes.size() - written);
            if (n > 0) {
                written += static_cast<std::size_t>(n);
            }
        }
    }

    // One byte of the host's stream through the command parser.
    void take(std::uint8_t byte) {
        switch (state_) {
            case State::header:
                if (byte == board::kHeader) {
                    state_ = State::opcode;
                } else {
                    status_ |= 1U << board::kStatusProtocolError;
                }
                return;
            case State::opcode:
                state_ = State::header;
                if (stuck_ && byte != board::kOpClear) {
                    return;  // waits for beats that never come
                }
                if (byte == board::kOpIdentify) {
                    board::Identity identity = identity_;
                    identity.status = status_;
                    reply(board::identify_reply(identity));
                } else if (byte == board::kOpClear) {
                    reply(board::ack_reply(status_));
                    status_ = 0;
                    stuck_ = false;
                } else if (byte == board::kOpConfigure) {
                    state_ = State::config;
                    payload_.clear();
                } else if (byte == board::kOpFrame) {
                    start_frame();
                } else {
                    status_ |= 1U << board::kStatusProtocolError;
                }
                return;
            case State::config:
                payload_.push_back(byte);
                if (payload_.size() == board::kConfigBytes) {
                    config_ = board::decode_config(payload_);
                    state_ = State::header;
                    reply(board::ack_reply(status_));
                }
                return;
            case State::frame:
                payload_.push_back(byte);
                if (payload_.size() ==
                    board::kPixelBytes * static_cast<std::size_t>(frame_.width * frame_.height)) {
                    const auto [left, right] =
                        board::decode_pixels(payload_, frame_.width, frame_.height);
                    ValidatedDisparity result =
                        match_validated(left, right, board::match_params(frame_, identity_.window));
                    spoil(result);
                    reply(board::encode_beats(result));
                    ++frames_;
                    state_ = State::header;
                }
                return;
        }
    }

    // The fault, at the last pixel (so the whole reply arrives first).
    void spoil(ValidatedDisparity& result) const {
        const std::size_t last = result.fixed.size() - 1;
        if (fault_ == Fault::reason_code) {
            result.reason[last] = 7;
            result.fixed[last] = 0;
        } else if (fault_ == Fault::invalid_with_disparity) {
            result.reason[last] = fx::kReasonUniqueness;
            result.fixed[last] = 48;
        } else if (fault_ == Fault::out_of_range) {
            result.reason[last] = fx::kReasonValid;
            result.fixed[last] = 16 * (frame_.min_disp + frame_.ndisp + 3);
        }
    }

    // stereo_top's clamping of the configuration, sampled at the start of the frame.
    void start_frame() {
        frame_ = config_;
        bool clamped = false;
        auto clamp = [&clamped](int& value, int low, int high, int replacement) {
            if (value < low || value > high) {
                value = replacement;
                clamped = true;
            }
        };
        clamp(frame_.width, 1, identity_.width, identity_.width);
        clamp(frame_.height, 1, identity_.height, identity_.height);
        clamp(frame_.ndisp, 1, identity_.ndisp, identity_.ndisp);
        clamp(frame_.radius, identity_.window / 2, identity_.window / 2, identity_.window / 2);
        const int limit = identity_.max_min_disp;
        clamp(frame_.min_disp, -limit, limit, frame_.min_disp < 0 ? -limit : limit);
        if (clamped) {
            status_ |= 1U << board::kStatusConfigClamped;
        }
        state_ = State::frame;
        payload_.clear();
    }

    enum class State { header, opcode, config, frame };

    board::Identity identity_;
    bool mute_;
    bool stuck_;
    Fault fault_;
    int master_ = -1;
    int slave_ = -1;
    std::string slave_path_;
    std::atomic<bool> stop_ = false;
    std::atomic<int> frames_ = 0;
    State state_ = State::header;
    std::vector<std::uint8_t> payload_;
    board::Config config_{};
    board::Config frame_{};
    std::uint8_t status_ = 0;
    std::thread thread_;
};

// A board built for 32x24, 12 labels, 5x5 (the emulator's numbers; any build answers alike).
board::Identity small_board() {
    return {table::kRegmapId, table::kRegmapVersion, 32, 24, 12, 5, table::kDefaultMaxMinDisp, 0};
}

// ---- the protocol, both ways ----------------------------------------------------------------

TEST(BoardProtocol, ConfigurationRoundTripsWithNegativeMinDisparity) {
    board::Config config{31, 17, 300, 2, false, -7, true, 35, true, 3, true};
    const std::vector<std::uint8_t> command = board::configure_command(config);
    ASSERT_EQ(command.size(), 2 + board::kConfigBytes);
    EXPECT_EQ(command[0], 0xA5);
    EXPECT_EQ(command[1], 'C');
    // Bytes by hand: width 31 = 0x1F, 0x00; ndisp 300 = 0x12C; min_disp -7 = 0xFF9 (12 bits);
    // flags: uniqueness 2 | left-right 4 | sub-pixel 8 = 14.
    EXPECT_EQ(command[2], 0x1F);
    EXPECT_EQ(command[3], 0x00);
    EXPECT_EQ(command[6], 0x2C);
    EXPECT_EQ(command[7], 0x01);
    EXPECT_EQ(command[9], 14);
    EXPECT_EQ(command[10], 0xF9);
    EXPECT_EQ(command[11], 0x0F);
    EXPECT_EQ(board::decode_config(std::span(command).subspan(2)), config);
}

TEST(BoardProtocol, PixelsBeatsAndIdentityRoundTrip) {
    std::mt19937 rng(7);
    const Image left = test::random_image(9, 5, 3, rng);
    const Image right = test::random_image(9, 5, 3, rng);
    const std::vector<std::uint8_t> frame = board::frame_command(left, right);
    ASSERT_EQ(frame.size(), 2 + 6 * 9 * 5U);
    EXPECT_EQ(frame[2], left.at(0, 0, 0));   // left R first
    EXPECT_EQ(frame[5], right.at(0, 0, 0));  // then right R
    const auto [l, r] = board::decode_pixels(std::span(frame).subspan(2), 9, 5);
    EXPECT_EQ(l.pixels, left.pixels);
    EXPECT_EQ(r.pixels, right.pixels);

    const ValidatedDisparity result = match_validated(left, right, {4, 3, fx::kDefaultSigma, true});
    const std::vector<std::uint8_t> beats = board::encode_beats(result);
    EXPECT_EQ(board::decode_beats(beats, 9, 5), result);
    EXPECT_THROW(board::decode_beats(std::span(beats).first(beats.size() - 1), 9, 5),
                 std::runtime_error);
    std::vector<std::uint8_t> padded = beats;
    padded[2] |= 0x80;  // a padding bit of the first beat
    EXPECT_THROW(board::decode_beats(padded, 9, 5), std::runtime_error);
    // Beats by hand (docs/board.md): fixed disparity x 16 as 16-bit two's complement, low byte
    // first, then reason and certainty. The random pair above has no negative disparity:
    // -35 = 0xFFDD, 4000 = 0x0FA0.
    ValidatedDisparity hand(3, 1);
    hand.fixed = {-35, 4000, 0};
    hand.reason = {fx::kReasonValid, fx::kReasonValid, fx::kReasonUniqueness};
    hand.certainty = {7, 200, 0};
    const std::vector<std::uint8_t> hand_beats{0xDD, 0xFF, 0, 7, 0xA0, 0x0F, 0, 200, 0, 0, 2, 0};
    EXPECT_EQ(board::encode_beats(hand), hand_beats);
    EXPECT_EQ(board::decode_beats(hand_beats, 3, 1), hand);

    const board::Identity identity = small_board();
    EXPECT_EQ(board::decode_identity(board::identify_reply(identity)), identity);
    EXPECT_THROW(board::decode_identity(board::ack_reply(0)), std::runtime_error);
    EXPECT_EQ(board::describe_status(0), "ok");
    EXPECT_EQ(board::describe_status(0x0C), "configuration clamped, protocol error");
}

TEST(BoardProtocol, GreyImagesAreSentAsRgbAndSizesMustMatch) {
    std::mt19937 rng(3);
    const Image grey = test::random_image(4, 2, 1, rng);
    const std::vector<std::uint8_t> frame = board::frame_command(grey, grey);
    EXPECT_EQ(frame[2], grey.at(0, 0, 0));
    EXPECT_EQ(frame[3], grey.at(0, 0, 0));
    EXPECT_EQ(frame[4], grey.at(0, 0, 0));
    EXPECT_THROW(board::frame_command(grey, test::random_image(5, 2, 1, rng)),
                 std::invalid_argument);
}

// ---- the client against the emulated board --------------------------------------------------

TEST(BoardClient, FramesEqualTheModelAndClampingIsReported) {
    const EmulatedBoard device(small_board());
    io::SerialPort port(device.path(), 115200);
    board::Client client(port, 2000ms);
    EXPECT_EQ(client.identify(), small_board());
    std::mt19937 rng(11);
    const Image left = test::random_image(32, 24, 3, rng);
    const Image right = test::shifted_copy(left, 3, 10, rng);
    MatchParams params{12, 5, fx::kDefaultSigma, true};
    params.min_disp = -2;
    params.validation = {true, 15, true, 1, true};
    EXPECT_EQ(client.configure(board::config_for(32, 24, params)), 0);
    EXPECT_EQ(client.frame(left, right), match_validated(left, right, params));
    EXPECT_EQ(client.bytes_sent(), 2 + 14 + 2 + 6 * 32 * 24U);
    EXPECT_EQ(client.bytes_received(), 18 + 2 + 4 * 32 * 24U);
    // ndisp 0: the board uses all 12 labels and sets the status bit; clear returns it.
    board::Config bad = board::config_for(32, 24, params);
    bad.ndisp = 0;
    EXPECT_EQ(client.configure(bad), 0);
    params.ndisp = 12;
    EXPECT_EQ(client.frame(left, right), match_validated(left, right, params));
    EXPECT_EQ(client.identify().status, 1U << board::kStatusConfigClamped);
    EXPECT_EQ(client.clear(), 1U << board::kStatusConfigClamped);
    EXPECT_EQ(client.identify().status, 0);
}

// Data no core can send is the board's fault (std::runtime_error, exit 1), not accepted and not
// blamed on the options: an impossible identity, a reason code the core does not have, an
// invalid pixel with a disparity, a valid one outside the searched range.
TEST(BoardClient, ImpossibleDataFromTheBoardIsRefused) {
    using Fault = EmulatedBoard::Fault;
    std::mt19937 rng(12);
    const Image left = test::random_image(32, 24, 3, rng);
    const Image right = test::shifted_copy(left, 3, 10, rng);
    const MatchParams params{12, 5, fx::kDefaultSigma, true};
    for (const Fault fault :
         {Fault::none, Fault::reason_code, Fault::invalid_with_disparity, Fault::out_of_range}) {
        const EmulatedBoard device(small_board(), false, false, fault);
        io::SerialPort port(device.path(), 115200);
        board::Client client(port, 2000ms);
        (void)client.identify();
        (void)client.configure(board::config_for(32, 24, params));
        if (fault == Fault::none) {
            EXPECT_EQ(client.frame(left, right), match_validated(left, right, params));
            continue;
        }
        try {
            (void)client.frame(left, right);
            ADD_FAILURE() << "fault " << static_cast<int>(fault) << " accepted";
        } catch (const std::runtime_error& error) {
            EXPECT_NE(std::string(error.what()).find("at pixel 31,23"), std::string::npos)
                << error.what();
        }
    }
    board::Identity impossible = small_board();
    impossible.window = 0;
    const EmulatedBoard device(impossible);
    io::SerialPort port(device.path(), 115200);
    board::Client client(port, 2000ms);
    EXPECT_THROW((void)client.identify(), std::runtime_error);
}

TEST(BoardClient, LimitsOfTheBuildAreChecked) {
    const board::Identity identity = small_board();
    const MatchParams fits{12, 5, fx::kDefaultSigma, true};
    EXPECT_NO_THROW(board::check_fits(identity, 32, 24, board::config_for(32, 24, fits)));
    EXPECT_THROW(board::check_fits(identity, 33, 24, board::config_for(33, 24, fits)),
                 std::invalid_argument);
    EXPECT_THROW(board::check_fits(identity, 32, 25, board::config_for(32, 25, fits)),
                 std::invalid_argument);
    EXPECT_THROW(board::check_fits(identity, 32, 24,
                                   board::config_for(32, 24, {13, 5, fx::kDefaultSigma, true})),
                 std::invalid_argument);
    EXPECT_THROW(board::check_fits(identity, 32, 24,
                                   board::config_for(32, 24, {12, 3, fx::kDefaultSigma, true})),
                 std::invalid_argument);
    MatchParams shifted = fits;
    shifted.min_disp = -(table::kDefaultMaxMinDisp + 1);
    EXPECT_THROW(board::check_fits(identity, 32, 24, board::config_for(32, 24, shifted)),
                 std::invalid_argument);
}

TEST(BoardClient, SilentDeviceTimesOut) {
    const EmulatedBoard device(small_board(), true);
    io::SerialPort port(device.path(), 115200);
    board::Client client(port, 200ms);
    const auto start = std::chrono::steady_clock::now();
    try {
        (void)client.identify();
        FAIL() << "a silent device answered";
    } catch (const std::runtime_error& error) {
        EXPECT_NE(std::string(error.what()).find("did not answer"), std::string::npos)
            << error.what();
    }
    const auto waited = std::chrono::steady_clock::now() - start;
    EXPECT_GE(waited, 200ms);
    EXPECT_LT(waited, 2s);
}

TEST(SerialPort, MissingPortAndNonTerminalAreErrors) {
    EXPECT_THROW(io::SerialPort("/nonexistent/ttyUSB9", 115200), std::runtime_error);
    const test::TempFolder folder;
    const std::filesystem::path file = folder.write_text("not_a_tty.bin", "x");
    EXPECT_THROW(io::SerialPort(file.string(), 115200), std::runtime_error);
    const EmulatedBoard device(small_board());
    EXPECT_THROW(io::SerialPort(device.path(), 123456), std::invalid_argument);
}

// ---- `stereo board` -------------------------------------------------------------------------

struct Outcome {
    int exit_code;
    std::string out;
    std::string err;
};

Outcome run_stereo(std::vector<std::string> args) {
    CLI::App app{"stereo", "stereo"};
    cli::add_stereo_commands(app);
    args.insert(args.begin(), "stereo");
    std::vector<char*> argv;
    for (std::string& arg : args) {
        argv.push_back(arg.data());
    }
    argv.push_back(nullptr);
    testing::internal::CaptureStdout();
    testing::internal::CaptureStderr();
    const int code = cli::run(app, static_cast<int>(args.size()), argv.data());
    std::string err = testing::internal::GetCapturedStderr();
    return {code, testing::internal::GetCapturedStdout(), std::move(err)};
}

std::string file_bytes(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

class BoardCli : public ::testing::Test {
  protected:
    void SetUp() override {
        std::mt19937 rng(5);
        const Image left = test::random_image(32, 24, 3, rng);
        // Disparity 4, and -2 in the bottom quarter: signed output over --min-disp -3.
        Image right = test::shifted_copy(left, 4, 12, rng);
        const Image behind = test::shifted_copy(left, -2, 12, rng);
        const std::size_t quarter = right.pixels.size() / 4;
        std::copy(behind.pixels.end() - quarter, behind.pixels.end(), right.pixels.end() - quarter);
        io::write_png(path("left.png"), io::to_bgr(left));
        io::write_png(path("right.png"), io::to_bgr(right));
        io::write_png(path("big.png"), io::to_bgr(test::random_image(40, 24, 3, rng)));
        io::write_png(path("narrow.png"), io::to_bgr(test::random_image(31, 24, 3, rng)));
    }
    std::string path(const std::string& name) const { return folder_.file(name).string(); }

    const test::TempFolder folder_;
};

TEST_F(BoardCli, BoardOutputEqualsStereoMatchByteForByte) {
    const EmulatedBoard device(small_board());
    int negative = 0;  // valid negative disparities in the 16-bit outputs
    for (const std::vector<std::string>& options :
         {std::vector<std::string>{"--ndisp", "12", "--window", "5"},
          std::vector<std::string>{"--ndisp", "9", "--window", "5", "--min-disp", "-3", "--no-ca",
                                   "--png16"},
          // A speckle size larger than the frame: the host-side filter removes every region,
          // so the two agree only when both run it (after the board as after the model).
          std::vector<std::string>{"--ndisp", "12", "--window", "5", "--speckle-size", "100000",
                                   "--png16"}}) {
        std::vector<std::string> board_args{"board",          path("left.png"), path("right.png"),
                                            "--port",         device.path(),    "-o",
                                            path("board.png")};
        // The board's core has the AD cost; stereo match's default is census.
        std::vector<std::string> match_args{
            "match", path("left.png"), path("right.png"), "-o", path("match.png"), "--cost", "ad"};
        board_args.insert(board_args.end(), options.begin(), options.end());
        match_args.insert(match_args.end(), options.begin(), options.end());
        const Outcome board = run_stereo(board_args);
        ASSERT_EQ(board.exit_code, 0) << board.err;
        const Outcome match = run_stereo(match_args);
        ASSERT_EQ(match.exit_code, 0) << match.err;
        const std::string bytes = file_bytes(path("board.png"));
        EXPECT_FALSE(bytes.empty());
        EXPECT_EQ(bytes, file_bytes(path("match.png"))) << options.back();
        if (options.back() == "--png16") {
            const cv::Mat codes = cv::imread(path("match.png"), cv::IMREAD_UNCHANGED);
            negative += cv::countNonZero((codes > 0) & (codes < 32768));
        }
    }
    EXPECT_GT(negative, 0);
    EXPECT_EQ(device.frames(), 3);
}

TEST_F(BoardCli, JsonSummaryAndTheBoardsWindowByDefault) {
    const EmulatedBoard device(small_board());
    const Outcome outcome = run_stereo({"board", path("left.png"), path("right.png"), "--port",
                                        device.path(), "--ndisp", "12", "--json"});
    ASSERT_EQ(outcome.exit_code, 0) << outcome.err;
    const nlohmann::json summary = nlohmann::json::parse(outcome.out);
    EXPECT_EQ(summary["window"], 5);  // the board's, not the CLI default
    EXPECT_EQ(summary["width"], 32);
    EXPECT_EQ(summary["board"]["ndisp"], 12);
    EXPECT_EQ(summary["bytes_sent"], 2 + 14 + 2 + 6 * 32 * 24 + 2);
    // Disparity 4 is found; the bottom quarter's -2 lies outside 0 .. 11.
    EXPECT_GT(summary["valid_fraction"].get<double>(), 0.4);
}

// An earlier run stopped half way through a frame: the board answers only the clear command,
// which `stereo board` sends when the identify command gets no answer.
TEST_F(BoardCli, BoardLeftInsideAFrameIsClearedFirst) {
    const EmulatedBoard device(small_board(), false, true);
    const Outcome board =
        run_stereo({"board", path("left.png"), path("right.png"), "--port", device.path(),
                    "--ndisp", "12", "--timeout", "300", "-o", path("board.png")});
    ASSERT_EQ(board.exit_code, 0) << board.err;
    const Outcome match = run_stereo({"match", path("left.png"), path("right.png"), "--ndisp", "12",
                                      "--window", "5", "--cost", "ad", "-o", path("match.png")});
    ASSERT_EQ(match.exit_code, 0) << match.err;
    EXPECT_EQ(file_bytes(path("board.png")), file_bytes(path("match.png")));
    EXPECT_EQ(device.frames(), 1);
}

TEST_F(BoardCli, ErrorsExitNonZeroWithOneLine) {
    const EmulatedBoard device(small_board());
    const EmulatedBoard silent(small_board(), true);
    struct Case {
        std::vector<std::string> args;
        int exit_code;
        std::string message;
    };
    const std::vector<Case> cases = {
        {{"board", path("left.png"), path("right.png"), "--port", "/nonexistent/ttyUSB9"},
         1,
         "cannot open serial port"},
        {{"board", path("left.png"), path("right.png"), "--port", silent.path(), "--timeout",
          "200"},
         1,
         "did not answer"},
        {{"board", path("big.png"), path("big.png"), "--port", device.path()}, 2, "at most 32x24"},
        {{"board", path("left.png"), path("narrow.png"), "--port", device.path()}, 2, ""},
        {{"board", path("left.png"), path("right.png"), "--port", device.path(), "--ndisp", "13"},
         2,
         "12 labels"},
        {{"board", path("left.png"), path("right.png"), "--port", device.path(), "--baud", "7"},
         2,
         "--baud"},
    };
    for (const Case& c : cases) {
        const Outcome outcome = run_stereo(c.args);
        EXPECT_EQ(outcome.exit_code, c.exit_code) << c.args[4] << ": " << outcome.err;
        EXPECT_EQ(outcome.err.rfind("stereo: error: ", 0), 0U) << outcome.err;
        EXPECT_NE(outcome.err.find(c.message), std::string::npos) << outcome.err;
        EXPECT_EQ(std::count(outcome.err.begin(), outcome.err.end(), '\n'), 1) << outcome.err;
    }
    EXPECT_EQ(device.frames(), 0);
}

}  // namespace
}  // namespace stereo
