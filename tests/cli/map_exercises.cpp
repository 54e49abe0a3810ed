// map_exercises MAP [requirements]: checks that a disparity map written by an equality test's
// engine exercises the path the test claims (issue 52): enough valid pixels, fractional and
// negative disparities, several distinct disparities, and stage 6's reason codes. Prints what it
// measured; exits 1 naming the first requirement the map misses, 2 on a usage error.
//
//   map_exercises OUT.pfm --min-valid 0.3 --fractional --negative --distinct 4
//       --reasons OUT.reasons.png --reason-codes 1,3,4 [--print]
#include <cmath>
#include <cstdlib>
#include <exception>
#include <iostream>
#include <set>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <opencv2/core.hpp>

#include "stereo_io/disparity_files.hpp"
#include "stereo_io/io.hpp"

namespace {

namespace io = stereo::io;

struct Requirements {
    std::string map;
    double min_valid = 0.0;
    bool fractional = false;
    bool negative = false;
    int distinct = 0;
    std::string reasons;
    std::vector<int> reason_codes;
    bool print = false;
};

// One character per pixel: '.' invalid, '-' negative, else the rounded disparity (0-9, '+').
void print_map(const cv::Mat& map) {
    for (int y = 0; y < map.rows; ++y) {
        std::string row;
        for (int x = 0; x < map.cols; ++x) {
            const float d = map.at<float>(y, x);
            if (std::isnan(d)) {
                row += '.';
            } else if (d < 0) {
                row += '-';
            } else {
                const long rounded = std::lround(d);
                row += rounded > 9 ? '+' : static_cast<char>('0' + rounded);
            }
        }
        std::cout << row << '\n';
    }
}

// The first requirement `map` misses, or "" when it meets them all.
std::string check(const Requirements& wanted) {
    const cv::Mat map = io::load_disparity_file(
        wanted.map, io::encoding_of(wanted.map, io::DisparityEncoding::offset16), 1.0);
    int valid = 0;
    int fractional = 0;
    int negative = 0;
    std::set<long> sixteenths;
    for (int y = 0; y < map.rows; ++y) {
        for (int x = 0; x < map.cols; ++x) {
            const float d = map.at<float>(y, x);
            if (std::isnan(d)) {
                continue;
            }
            ++valid;
            fractional += d != std::floor(d) ? 1 : 0;
            negative += d < 0 ? 1 : 0;
            sixteenths.insert(std::lround(d * 16));
        }
    }
    const double fraction = static_cast<double>(valid) / map.total();
    std::cout << wanted.map << ": " << map.cols << "x" << map.rows << ", valid " << fraction
              << ", fractional " << fractional << ", negative " << negative << ", distinct "
              << sixteenths.size();
    std::vector<int> reason_counts;
    if (!wanted.reasons.empty()) {
        const cv::Mat reasons = io::load_grey(wanted.reasons);
        if (reasons.size() != map.size()) {
            throw std::runtime_error(wanted.reasons + ": not the size of the disparity map");
        }
        reason_counts.assign(256, 0);
        for (auto it = reasons.begin<uchar>(); it != reasons.end<uchar>(); ++it) {
            reason_counts[*it] += 1;
        }
        std::cout << ", reasons";
        for (int code = 0; code < 8; ++code) {
            std::cout << ' ' << code << ':' << reason_counts[code];
        }
    }
    std::cout << '\n';
    if (wanted.print) {
        print_map(map);
    }
    if (fraction < wanted.min_valid) {
        return "valid fraction " + std::to_string(fraction) + " below " +
               std::to_string(wanted.min_valid);
    }
    if (wanted.fractional && fractional == 0) {
        return "no fractional disparity";
    }
    if (wanted.negative && negative == 0) {
        return "no negative disparity";
    }
    if (static_cast<int>(sixteenths.size()) < wanted.distinct) {
        return std::to_string(sixteenths.size()) + " distinct disparities, fewer than " +
               std::to_string(wanted.distinct);
    }
    for (const int code : wanted.reason_codes) {
        if (reason_counts.empty() || code < 0 || code > 255 || reason_counts[code] == 0) {
            return "no pixel with reason code " + std::to_string(code);
        }
    }
    return "";
}

}  // namespace

int main(int argc, char** argv) {
    Requirements wanted;
    CLI::App app{"Checks that a disparity map exercises what an equality test claims"};
    app.add_option("MAP", wanted.map, "PFM or offset16 PNG disparity map")->required();
    app.add_option("--min-valid", wanted.min_valid, "Smallest valid fraction")
        ->check(CLI::Range(0.0, 1.0));
    app.add_flag("--fractional", wanted.fractional, "Require a fractional disparity");
    app.add_flag("--negative", wanted.negative, "Require a negative disparity");
    app.add_option("--distinct", wanted.distinct, "Require this many distinct disparities");
    app.add_option("--reasons", wanted.reasons, "Stage 6's reason PNG (stereo match --reasons)");
    app.add_option("--reason-codes", wanted.reason_codes, "Reason codes that must occur")
        ->delimiter(',')
        ->needs("--reasons");
    app.add_flag("--print", wanted.print, "Print the map as characters");
    CLI11_PARSE(app, argc, argv);
    try {
        const std::string missed = check(wanted);
        if (!missed.empty()) {
            std::cerr << "map_exercises: " << wanted.map
                      << " does not exercise the path: " << missed << '\n';
            return 1;
        }
        return EXIT_SUCCESS;
    } catch (const std::exception& error) {
        std::cerr << "map_exercises: error: " << error.what() << '\n';
        return 2;
    }
}
