#include "cli_cosim_options.hpp"

#include <regex>
#include <stdexcept>

#include "cli_command.hpp"
#include "stereo/catalogue.hpp"

namespace stereo::cli {

void add_core_pair_options(CLI::App& command, CorePairOptions& options) {
    command.add_option("LEFT", options.left, "Left image")->required();
    command.add_option("RIGHT", options.right, "Right image, same size as LEFT")->required();
    // stereo match's defaults where the core has them (defaults::match_config: the census cost,
    // stage 6 with its ratio and tolerance, sub-pixel), but 16 labels and a 5x5 window, which the
    // built configurations cover (larger ones: --size), and no speckle filter (not in the core;
    // docs/cli.md).
    options.matcher.config.pipeline.ndisp = 16;
    options.matcher.config.pipeline.window = 5;
    add_matcher_options(
        command, options.matcher, MatcherChoice::fixed,
        {.validation = true, .validation_on_by_default = true, .default_cost = true});
    std::string cost_help = "Cost stage of the core:";
    for (const catalogue::CostRow& row : catalogue::kCosts) {
        if (catalogue::usable(row, catalogue::CostUse::hardware)) {
            cost_help += " " + std::string(row.name) +
                         " (COST = " + std::to_string(row.hardware_code) + ", " +
                         std::string(row.summary) + ")";
        }
    }
    command.add_option("--cost", options.matcher.given.cost, cost_help)
        ->check(CLI::IsMember(catalogue::cost_names(catalogue::CostUse::hardware)))
        ->default_str(options.matcher.config.pipeline.cost);
    add_downscale_option(command, options.downscale, "Shrink both images by integer F");
    command.add_option("--crop", options.crop, "Use the region WxH+X+Y (after --downscale)");
}

io::ImagePair load_core_pair(const CorePairOptions& options) {
    io::ImagePair pair = io::load_pair(options.left, options.right, options.downscale);
    if (options.crop.empty()) {
        return pair;
    }
    static const std::regex pattern(R"((\d+)x(\d+)\+(\d+)\+(\d+))");
    std::smatch parts;
    if (!std::regex_match(options.crop, parts, pattern)) {
        throw std::invalid_argument("--crop must be WxH+X+Y, got '" + options.crop + "'");
    }
    // Each number is at most 9 digits (the pattern's \d+ could hold any count): larger values
    // cannot fit any image and must not overflow an int.
    const auto number = [&options](const std::string& digits) {
        if (digits.size() > 9) {
            throw std::invalid_argument("--crop " + options.crop + ": " + digits + " is too large");
        }
        return std::stoi(digits);
    };
    const int width = number(parts[1]);
    const int height = number(parts[2]);
    const int x0 = number(parts[3]);
    const int y0 = number(parts[4]);
    return io::crop(pair, x0, y0, width, height);
}

void add_cosim_options(CLI::App& command, CosimOptions& options) {
    add_core_pair_options(command, options);
    command.add_option("--seed", options.seed, "Seed of the stall/gap generator")
        ->capture_default_str();
    // At most 0.95 (20 times the cycles of a frame): the old bound [0, 1) let 0.999999999 run
    // for days, a hang at a documented boundary (issue 51).
    const CLI::Validator probability = checks::real_in(0, 0.95);
    command.add_option("--stall", options.stall, "Probability of m_axis_tready low per cycle")
        ->capture_default_str()
        ->check(probability);
    command.add_option("--gap", options.gap, "Probability of s_axis_tvalid withheld per cycle")
        ->capture_default_str()
        ->check(probability);
    command
        .add_option("--method", options.method,
                    "pipeline: stereo_top; asw: stereo_top with adaptive support weights (ASW = "
                    "1: the separable variant, --window its diameter; census at 5 or AD at 31, "
                    "up to 64x48, 16 labels; docs/asw.md); hierarchical: the hierarchical "
                    "search's whole core (stereo_hier_top: census, up to 64x48, 16 labels, pass "
                    "window 5, levels 9 / 15 / 15, V = 16) with the host's plane tracker in the "
                    "loop (docs/hierarchical.md)")
        ->check(
            CLI::IsMember({std::string(catalogue::method(catalogue::Method::pipeline).name),
                           std::string(catalogue::method(catalogue::Method::asw).name),
                           std::string(catalogue::method(catalogue::Method::hierarchical).name)}))
        ->capture_default_str();
    command.add_option("-o,--output", options.output, "Write the RTL's disparity PNG");
    command
        .add_option("--frames", options.frames,
                    "Stream the pair this many times (traffic seed + frame), all compared; "
                    "hierarchical: a steady rig, the host writing each next plane [" +
                        std::to_string(kPipelineFrames) + "; hierarchical " +
                        std::to_string(kHierarchicalFrames) + "]")
        ->check(checks::integer_in(1, 1'000'000));
    command
        .add_option("--reset-at", options.reset_at,
                    "Before each frame, stream this many of its beats and reset mid-frame (the "
                    "part-frame is not counted; hierarchical: the host keeps its plane)")
        ->check(checks::integer_at_least(-1));  // -1: no reset
    command.add_option("--trace", options.trace,
                       "Write an FST waveform of the run (TRACE.fst; other "
                       "extensions, .vcd included, are refused)");
    command.add_option("--size", options.size,
                       "Co-simulate a core of WIDTHxHEIGHT (with NDISP --ndisp, WINDOW --window, "
                       "COST --cost) built on demand into the cache, instead of one of this "
                       "build's configurations");
    command.add_option("--lanes", options.lanes, "With --size: LANES, labels per clock (0: NDISP)")
        ->capture_default_str();
    command
        .add_option("--max-min-disp", options.max_min_disp,
                    "With --size: MAX_MIN_DISP (-1: 8, or |--min-disp| when larger)")
        ->capture_default_str();
    command.add_flag("--lean", options.lean,
                     "With --size: the lean memory architecture (RECOMPUTE_COSTS = 1; ad, census)");
    command.add_option("--cache", options.cache,
                       "With --size: the folder of the built cores (default $STEREO_COSIM_CACHE, "
                       "else ~/.cache/stereo/cosim)");
    command
        .add_option("--sim-threads", options.sim_threads,
                    "With --size: Verilator threads of the core (measured: 2 threads are slower "
                    "than 1 on the 640x480 / 64-label cores, docs/gtkwave.md)")
        ->check(CLI::Range(1, 16))
        ->capture_default_str();
    command
        .add_option("--diff", options.diff,
                    "Write a PNG of the first mismatching frame: 255 where the disparity "
                    "differs, 128 where only the reason or certainty does, 0 elsewhere")
        ->check(checks::png_output());
    command.add_flag("--json", options.json,
                     "Print one JSON object (mismatches, cycles, pixels, ...)");
}

}  // namespace stereo::cli
