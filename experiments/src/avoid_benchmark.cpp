// `stereo_experiments avoid-benchmark DATA_DIR OUT.md`: the obstacle benchmark of
// docs/results-avoidance.md. Textured obstacles (position, share of the window, distance) are
// pasted into sampled frames of both KITTI clips; both methods decide with ground removal (and,
// for comparison, without it); every case has a known set of acceptable answers.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "cli_command.hpp"
#include "cli_matcher_options.hpp"
#include "experiments.hpp"
#include "stereo/edge_frontend.hpp"
#include "stereo_io/io.hpp"
#include "stereo_io/output.hpp"
#include "stereo_robot/bands.hpp"
#include "stereo_robot/calibration.hpp"
#include "stereo_robot/decision.hpp"
#include "stereo_robot/ground.hpp"
#include "stereo_robot/obstacles.hpp"

namespace stereo::experiments {
namespace {

namespace fs = std::filesystem;
using robot::Direction;

struct Options {
    std::string data;
    std::string out;
    int stride = 5;
    double safe_distance = 10.0;
    double near = 6.0;
    double far = 20.0;
    int downscale = 1;  // shrink both images (area averaging) before matching
    int ndisp = 64;
    int threads = 1;  // row bands (bit-exact with 1)
};

struct Case {
    std::string name;
    std::string position;  // "" = free road
    double coverage = 0.0;
    bool near = true;
};

// Acceptable answers: nothing nearer than Z_safe in the centre -> forward (a turn away from a
// side obstacle is also accepted); a near obstacle covering the centre -> a turn or back-off, a
// turn away from the side it also covers.
bool acceptable(const Case& c, Direction d) {
    if (c.position.empty() || !c.near) {
        return d == Direction::forward;
    }
    if (c.position == "left") {
        return d == Direction::forward || d == Direction::right;
    }
    if (c.position == "right") {
        return d == Direction::forward || d == Direction::left;
    }
    return d != Direction::forward;  // centre, wall
}

struct Tally {
    int frames = 0;
    int threshold_ok = 0;
    int fuzzy_ok = 0;
    int threshold_plain_ok = 0;  // without ground removal
    int fuzzy_plain_ok = 0;
    std::map<std::string, int> fuzzy_answers;
};

void run(const Options& o) {
    if (o.stride < 1 || o.downscale < 1 || o.threads < 1 || o.ndisp < 2) {
        throw std::invalid_argument(
            "--stride, --downscale and --threads must be >= 1, --ndisp >= 2");
    }
    const std::vector<Case> cases = {
        {"free road", "", 0.0, true},
        {"centre, 1/3 of the window, near", "centre", 0.34, true},
        {"centre, 80 %, near", "centre", 0.8, true},
        {"left, 80 %, near", "left", 0.8, true},
        {"right, 80 %, near", "right", 0.8, true},
        {"wall (all windows), 90 %, near", "wall", 0.9, true},
        {"centre, 80 %, far", "centre", 0.8, false},
        {"wall, 90 %, far", "wall", 0.9, false},
    };
    std::map<std::string, std::map<std::string, Tally>> tallies;  // clip -> case -> tally
    // Before the run (the table is written after it), and not into the data it reads.
    io::check_outputs({o.out}, {.folders = {o.data}});
    io::check_writable_location(o.out);
    std::ostringstream md;
    double match_ms = 0.0;
    int matches = 0;
    for (const std::string clip : {"kitti_sequence_1", "kitti_sequence_2"}) {
        const fs::path dir = fs::path(o.data) / "sequence" / clip;
        const auto geometry = robot::load_calibration(dir / "calib.txt");
        const auto pairs = robot::pairs_from_folders(dir / "image_l", dir / "image_r");
        for (std::size_t f = 0; f < pairs.size(); f += o.stride) {
            const io::ImagePair road = io::load_pair(pairs[f].first, pairs[f].second, o.downscale);
            for (std::size_t k = 0; k < cases.size(); ++k) {
                const Case& c = cases[k];
                io::ImagePair pair = road;
                if (!c.position.empty()) {
                    robot::paste_obstacle(
                        pair.left, pair.right,
                        robot::obstacle_in_window(pair.left.width, pair.left.height,
                                                  robot::kDefaultBorder, c.position, c.coverage,
                                                  c.near ? o.near : o.far, geometry, o.downscale,
                                                  static_cast<std::uint32_t>(f * 31 + k + 1)));
                }
                MatchParams params;  // 11 x 11, sigma 3: stereo avoid's defaults
                params.ndisp = o.ndisp;
                params.use_ca = false;
                const auto start = std::chrono::steady_clock::now();
                const DisparityMap map =
                    robot::edge_match_bands(pair.left, pair.right, params, {}, o.threads);
                match_ms += std::chrono::duration<double, std::milli>(
                                std::chrono::steady_clock::now() - start)
                                .count();
                ++matches;
                const auto ground = robot::fit_ground(
                    map, params.ndisp,
                    robot::avoidance_camera(geometry, o.downscale, map.width, map.height), {});
                const double t = robot::disparity_threshold(geometry, o.safe_distance, o.downscale);
                Tally& tally = tallies[clip][c.name];
                ++tally.frames;
                for (const bool remove : {true, false}) {
                    const robot::GroundModel* g = remove && ground ? &*ground : nullptr;
                    const auto th = robot::decide_threshold(map, t, params.ndisp, {}, g);
                    const auto fz = robot::decide_fuzzy(map, t, {}, robot::kDefaultBorder, g);
                    (remove ? tally.threshold_ok : tally.threshold_plain_ok) +=
                        acceptable(c, th.direction) ? 1 : 0;
                    (remove ? tally.fuzzy_ok : tally.fuzzy_plain_ok) +=
                        acceptable(c, fz.fis.decision) ? 1 : 0;
                    if (remove) {
                        ++tally.fuzzy_answers[robot::to_string(fz.fis.decision)];
                    }
                }
            }
            std::cerr << clip << " frame " << f << '\n';
        }
    }
    md << "| clip | case | frames | threshold | fuzzy | threshold, no ground removal | fuzzy, no "
          "ground removal | fuzzy answers |\n|---|---|---|---|---|---|---|---|\n";
    for (const auto& [clip, by_case] : tallies) {
        for (const Case& c : cases) {
            const Tally& t = by_case.at(c.name);
            std::string answers;
            for (const auto& [name, count] : t.fuzzy_answers) {
                answers += (answers.empty() ? "" : ", ") + name + " " + std::to_string(count);
            }
            char line[512];
            std::snprintf(line, sizeof line,
                          "| %s | %s | %d | %d/%d | %d/%d | %d/%d | %d/%d | %s |\n", clip.c_str(),
                          c.name.c_str(), t.frames, t.threshold_ok, t.frames, t.fuzzy_ok, t.frames,
                          t.threshold_plain_ok, t.frames, t.fuzzy_plain_ok, t.frames,
                          answers.c_str());
            md << line;
        }
    }
    char footer[300];
    std::snprintf(footer, sizeof footer,
                  "\nZ_safe = %.1f m, near = %.1f m, far = %.1f m, every %d-th frame, downscale "
                  "%d, %d labels, %d thread(s); edge front end %.0f ms per frame (mean of %d).\n",
                  o.safe_distance, o.near, o.far, o.stride, o.downscale, o.ndisp, o.threads,
                  match_ms / matches, matches);
    md << footer;
    io::write_file_atomic(o.out, md.str());
    std::cout << o.out << '\n';
}

}  // namespace

void add_avoid_benchmark_command(CLI::App& app) {
    const auto [command, o] = cli::add_command<Options>(
        app, "avoid-benchmark",
        "Pasted-obstacle benchmark of both avoidance methods on the KITTI clips (markdown table).",
        run);
    command->add_option("DATA_DIR", o->data, "The shared data folder (holds sequence/)")
        ->required();
    command->add_option("OUT", o->out, "Markdown table to write")->required();
    cli::add_number_options(*command,
                            {{"--stride", &o->stride, "Use every N-th frame"},
                             {"--safe-distance", &o->safe_distance, "Z_safe, metres"},
                             {"--near", &o->near, "Distance of near obstacles, metres"},
                             {"--far", &o->far, "Distance of far obstacles, metres"},
                             {"--downscale", &o->downscale, "Shrink both images by F first"},
                             {"--ndisp", &o->ndisp, "Disparity labels"},
                             {"--threads", &o->threads, "Row bands matched in parallel"}});
}

}  // namespace stereo::experiments
