// `stereo board LEFT RIGHT --port /dev/ttyUSB1 [options]`: match a pair on the iCEBreaker build
// (rtl/stereo_board_top.sv, docs/board.md) over its serial port. The board is asked what it was
// built for, configured, sent the pair and its beats are read back; the outputs are written as
// `stereo match` writes them, and with the same parameters they are the same bytes.
#include <chrono>
#include <cstdio>
#include <iostream>
#include <stdexcept>
#include <string>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "cli.hpp"
#include "cli_command.hpp"
#include "cli_matcher_options.hpp"
#include "stereo_io/board_client.hpp"
#include "stereo_io/board_protocol.hpp"
#include "stereo_io/disparity_files.hpp"
#include "stereo_io/io.hpp"
#include "stereo_io/output.hpp"
#include "stereo_io/serial_port.hpp"
#include "stereo_io/versioned_json.hpp"

namespace stereo::board {

// The identity in the JSON output: a key per field, named as the field.
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(Identity, id, version, width, height, ndisp, window,
                                   max_min_disp, status)

}  // namespace stereo::board

namespace stereo::cli {
namespace {

struct BoardOptions {
    std::string left;
    std::string right;
    std::string port;
    int baud = 115200;
    int timeout_ms = 2000;
    std::string output;  // empty: no file
    MatcherOptions matcher;
    int downscale = 1;
    bool png16 = false;
    bool json = false;

    static constexpr std::string_view kName = "board";
    static constexpr std::string_view kDescription =
        "Match a pair on the iCEBreaker (stereo_board_top) over its serial port (docs/board.md).";
};

void check_options(const BoardOptions& options) {
    if (!io::supported_baud(options.baud)) {
        throw std::invalid_argument("--baud " + std::to_string(options.baud) +
                                    " is not a standard rate (e.g. 115200, 1000000, 3000000)");
    }
}

// The board's identity. A board left inside an abandoned frame (an earlier run stopped half way)
// answers only the clear command: clear it and ask again; a board that answers neither is not
// there.
board::Identity identify(board::Client& client) {
    try {
        return client.identify();
    } catch (const board::NoAnswer&) {
        (void)client.clear();
        return client.identify();
    }
}

// -o in the format of its extension, as stereo match writes it.
void write_output(const BoardOptions& options, io::DisparityEncoding output_encoding,
                  const ValidatedDisparity& validated, const DisparityMap& map, int ndisp) {
    if (options.output.empty()) {
        return;
    }
    std::string bytes;
    if (output_encoding == io::DisparityEncoding::pfm) {
        bytes = io::encode_pfm(io::to_float_disparity(validated));
    } else if (output_encoding == io::DisparityEncoding::offset16) {
        bytes =
            io::encode_disparity_png(io::to_offset16(validated),
                                     {.encoding = io::DisparityEncoding::offset16}, options.output);
    } else {
        bytes = io::encode_disparity_png(io::disparity_to_mat(map, ndisp, 1), {}, options.output);
    }
    io::write_file_atomic(options.output, bytes);
}

void run_board(const BoardOptions& options) {
    check_options(options);
    MatchConfig config = options.matcher.resolved();
    const auto output_encoding =
        options.output.empty()
            ? io::DisparityEncoding::scaled
            : io::output_encoding(options.output, options.png16 ? io::DisparityEncoding::offset16
                                                                : io::DisparityEncoding::scaled);
    if (!options.output.empty()) {
        io::check_outputs_distinct({options.output}, {options.left, options.right});
        io::check_writable_location(options.output);
    }
    const io::ImagePair pair = io::load_pair(options.left, options.right, options.downscale);
    const int width = pair.left.width;
    const int height = pair.left.height;

    io::SerialPort port(options.port, options.baud);
    board::Client client(port, std::chrono::milliseconds(options.timeout_ms));
    const board::Identity identity = identify(client);
    // The board's kernel is fixed: without --window the board's window is used; a --sigma other
    // than the default kernel's is refused.
    MatchParams& params = config.pipeline;
    if (!options.matcher.window_given()) {
        params.window = identity.window;
    }
    if (params.sigma != fx::kDefaultSigma) {
        throw std::invalid_argument("--sigma: the board's kernel is the default one (sigma " +
                                    std::to_string(fx::kDefaultSigma) + ")");
    }
    // The parameters as the model checks them (stereo match refuses the same ones).
    matchers().create("pipeline", "model", config)->validate(width, height);
    const board::Config registers = board::config_for(width, height, params);
    board::check_fits(identity, width, height, registers);
    std::uint8_t cleared = 0;
    if (identity.status != 0) {
        cleared = client.clear();  // a sticky bit from before this run
    }
    const std::uint8_t configured = client.configure(registers);
    const auto start = std::chrono::steady_clock::now();
    ValidatedDisparity validated = client.frame(pair.left, pair.right);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const std::uint8_t status = client.identify().status;
    if (configured != 0 || status != 0) {
        throw std::runtime_error("the board reports: " +
                                 board::describe_status(configured | status));
    }

    // The host-side speckle filter, as stereo match runs it after any engine.
    speckle::filter(validated, config.speckle);
    write_output(options, output_encoding, validated, to_label_map(validated), params.ndisp);
    std::size_t valid = 0;
    for (std::size_t i = 0; i < validated.reason.size(); ++i) {
        valid += validated.valid(i) ? 1 : 0;
    }
    const double valid_fraction = static_cast<double>(valid) / validated.reason.size();
    const ValidationParams& v = params.validation;
    if (options.json) {
        nlohmann::json summary = pipeline_json(width, height, params);
        summary.update({
            {"uniqueness", v.uniqueness ? nlohmann::json(v.uniqueness_ratio) : nullptr},
            {"lr_check", v.left_right ? nlohmann::json(v.lr_tolerance) : nullptr},
            {"valid_fraction", valid_fraction},
            {"port", options.port},
            {"baud", options.baud},
            {"frame_seconds", seconds},
            {"bytes_sent", client.bytes_sent()},
            {"bytes_received", client.bytes_received()},
            {"status_cleared", cleared},
            {"board", identity},
        });
        std::cout << io::versioned(summary).dump() << '\n';
        return;
    }
    std::printf(
        "%dx%d ndisp %d window %d ca %s on the board at %s (%d baud, built for %dx%d, %d labels): "
        "%.1f%% valid, frame %.3f s\n",
        width, height, params.ndisp, params.window, params.use_ca ? "on" : "off",
        options.port.c_str(), options.baud, identity.width, identity.height, identity.ndisp,
        100.0 * valid_fraction, seconds);
}

}  // namespace

void add_board_command(CLI::App& app) {
    const auto [command, options] = add_command<BoardOptions>(app, run_board);
    command->footer(
        "The board answers with what it was built for (largest frame, labels, window): without "
        "--window its window is used, and a larger frame, more labels, another window or a "
        "--sigma other than 3 are refused before any pixel is sent.");
    command->add_option("LEFT", options->left, "Left image")->required();
    command->add_option("RIGHT", options->right, "Right image, same size as LEFT")->required();
    command
        ->add_option("--port", options->port,
                     "Serial port of the board (the iCEBreaker's second FTDI port, e.g. "
                     "/dev/ttyUSB1)")
        ->required();
    add_number_options(*command,
                       {{"--baud", &options->baud, "Baud rate the bitstream was built for"},
                        {"--timeout", &options->timeout_ms,
                         "Milliseconds of silence after which the board counts as not answering",
                         checks::integer_in(1, 3'600'000)}});
    command->add_option("-o,--output", options->output,
                        "Disparity file as `stereo match -o` writes it (PNG, or .pfm)");
    // The defaults of `stereo match --cost ad` (the core's cost), so that the same options give
    // the same output; the ndisp default fits the smallest build.
    options->matcher.config.pipeline.ndisp = 1;
    add_matcher_options(*command, options->matcher, MatcherChoice::fixed,
                        {.validation = true, .speckle = true, .validation_on_by_default = true});
    command->add_flag("--png16", options->png16,
                      "Write a 16-bit PNG of 32768 + 16 d (signed, 1/16 pixel), 0 = invalid");
    add_downscale_option(*command, options->downscale);
    command->add_flag("--json", options->json, "Print the summary as one JSON object");
}

}  // namespace stereo::cli
