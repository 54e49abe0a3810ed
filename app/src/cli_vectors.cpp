// `stereo vectors LEFT RIGHT -o DIR [options]`: the test vectors of the SystemVerilog testbench
// (testbench/sv/README.md): the pair's input beats, the golden model's output beats and the
// configuration, as $readmemh files (stereo_io/test_vectors.hpp).
#include <cstdio>
#include <string>

#include <CLI/CLI.hpp>

#include "cli.hpp"
#include "cli_command.hpp"
#include "cli_cosim_options.hpp"
#include "cli_matcher_options.hpp"
#include "stereo/catalogue.hpp"
#include "stereo_io/test_vectors.hpp"

namespace stereo::cli {
namespace {

struct VectorsOptions : CorePairOptions {
    std::string folder;
    int frames = 1;

    static constexpr std::string_view kName = "vectors";
    static constexpr std::string_view kDescription =
        "Write $readmemh test vectors (configuration, input beats, the golden model's output "
        "beats) for the SystemVerilog testbench (testbench/sv/README.md).";
};

void run_vectors(const VectorsOptions& options) {
    const MatchConfig config = options.matcher.resolved();
    const MatchParams& params = config.pipeline;
    // The golden model, made (and its parameters checked) before any file is read or written.
    const auto model = matchers().create("pipeline", "model", config);
    const io::ImagePair pair = load_core_pair(options);
    model->validate(pair.left.width, pair.left.height);
    const ValidatedDisparity expected = model->compute(pair.left, pair.right).validated;
    io::write_vectors(options.folder,
                      io::make_vectors(pair.left, pair.right, params, expected, options.frames));
    const int k = params.min_disp < 0 ? -params.min_disp : 0;
    std::printf(
        "%s: %d x %d x %d frame(s); the core needs WIDTH >= %d, HEIGHT >= %d, NDISP >= %d, "
        "WINDOW >= %d, MAX_MIN_DISP >= %d, COST = %d (%s)\n",
        options.folder.c_str(), pair.left.width, pair.left.height, options.frames, pair.left.width,
        pair.left.height, params.ndisp, params.window, k,
        catalogue::cost(params.cost).hardware_code, params.cost.c_str());
}

}  // namespace

void add_vectors_command(CLI::App& app) {
    const auto [command, options] = add_command<VectorsOptions>(app, run_vectors);
    add_core_pair_options(*command, *options);
    command
        ->add_option("-o,--out", options->folder, "Folder for config.hex, input.hex, expected.hex")
        ->required();
    command->add_option("--frames", options->frames, "Frames streamed back to back (the same pair)")
        ->check(checks::integer_in(1, 64))
        ->capture_default_str();
}

}  // namespace stereo::cli
