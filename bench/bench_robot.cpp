// bench_robot: frames per second of the robot layers' front ends on a full-size KITTI frame
// (issue 20), single-threaded and in row bands, with OpenCV StereoSGBM on the same frame in the
// same run as the baseline (time ratios printed at the end). Also the whole avoidance decision
// (front end + ground fit + both methods) and one SLAM step. Skips (exit 0) without the data.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "stereo/edge_frontend.hpp"
#include "stereo_io/data_dir.hpp"
#include "stereo_io/io.hpp"
#include "stereo_robot/bands.hpp"
#include "stereo_robot/calibration.hpp"
#include "stereo_robot/decision.hpp"
#include "stereo_robot/ground.hpp"
#include "stereo_robot/slam/dataset.hpp"
#include "stereo_robot/slam/pipeline.hpp"

namespace {

namespace fs = std::filesystem;
using namespace stereo;

constexpr int kDisparities = 64;

struct Frames {
    fs::path dir;
    io::ImagePair pair;     // frame 10, grey
    io::ImagePair next;     // frame 11
    io::ImagePair half;     // frame 10 at half size (area averaging), as --downscale 2
    cv::Mat left, right;    // frame 10 for OpenCV
    cv::Mat left2, right2;  // frame 11
    robot::StereoGeometry geometry;
};

const Frames* frames() {
    static const std::optional<Frames> loaded = []() -> std::optional<Frames> {
        const fs::path dir = io::data_dir() / "sequence" / "kitti_sequence_1";
        if (!fs::is_directory(dir)) {
            return std::nullopt;
        }
        Frames f;
        f.dir = dir;
        const auto name = [&](const char* side, const char* frame) { return dir / side / frame; };
        f.pair = io::load_pair(name("image_l", "000010.png"), name("image_r", "000010.png"));
        f.next = io::load_pair(name("image_l", "000011.png"), name("image_r", "000011.png"));
        f.half = io::load_pair(name("image_l", "000010.png"), name("image_r", "000010.png"), 2);
        f.left = cv::imread(name("image_l", "000010.png").string(), cv::IMREAD_GRAYSCALE);
        f.right = cv::imread(name("image_r", "000010.png").string(), cv::IMREAD_GRAYSCALE);
        f.left2 = cv::imread(name("image_l", "000011.png").string(), cv::IMREAD_GRAYSCALE);
        f.right2 = cv::imread(name("image_r", "000011.png").string(), cv::IMREAD_GRAYSCALE);
        f.geometry = robot::load_calibration(dir / "calib.txt");
        return f;
    }();
    return loaded ? &*loaded : nullptr;
}

bool skip_without_data(benchmark::State& state) {
    if (frames() == nullptr) {
        state.SkipWithError("no KITTI data");
        return true;
    }
    return false;
}

void set_fps(benchmark::State& state) {
    state.counters["frames/s"] =
        benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

// The baseline: OpenCV StereoSGBM, 64 disparities, 5x5 blocks, one thread.
void BM_OpenCvStereoSGBM(benchmark::State& state) {
    if (skip_without_data(state)) {
        return;
    }
    cv::setNumThreads(1);
    const auto sgbm = cv::StereoSGBM::create(0, kDisparities, 5, 8 * 25, 32 * 25);
    cv::Mat disparity;
    for (auto _ : state) {
        sgbm->compute(frames()->left, frames()->right, disparity);
        benchmark::DoNotOptimize(disparity.data);
    }
    set_fps(state);
}

// One front end on frame 10, range(0) = threads (row bands).
template <typename Match>
void frontend_benchmark(benchmark::State& state, Match match) {
    if (skip_without_data(state)) {
        return;
    }
    const int threads = static_cast<int>(state.range(0));
    for (auto _ : state) {
        benchmark::DoNotOptimize(match(frames()->pair.left, frames()->pair.right, threads));
    }
    set_fps(state);
}

void BM_EdgeFrontend(benchmark::State& state) {
    MatchParams params;
    params.use_ca = false;
    frontend_benchmark(state, [&](const Image& l, const Image& r, int threads) {
        return robot::edge_match_bands(l, r, params, {}, threads);
    });
}

void BM_SparseFrontend(benchmark::State& state) {
    const robot::slam::FrontendParams params;
    frontend_benchmark(state, [&](const Image& l, const Image& r, int threads) {
        return robot::sparse_disparity_bands(l, r, params, threads);
    });
}

// stereo avoid's work per frame after loading: front end, ground fit, both decisions. Arguments:
// threads, and the downscale (1: full size, 64 labels; 2: half size, 32 labels, as
// `stereo avoid --downscale 2 --ndisp 32`).
void BM_AvoidDecision(benchmark::State& state) {
    if (skip_without_data(state)) {
        return;
    }
    const int threads = static_cast<int>(state.range(0));
    const int downscale = static_cast<int>(state.range(1));
    const io::ImagePair& pair = downscale == 1 ? frames()->pair : frames()->half;
    MatchParams params;
    params.use_ca = false;
    params.ndisp = 64 / downscale;
    const double t = robot::disparity_threshold(frames()->geometry, 10.0, downscale);
    for (auto _ : state) {
        const DisparityMap map =
            robot::edge_match_bands(pair.left, pair.right, params, {}, threads);
        const auto ground = robot::fit_ground(
            map, params.ndisp,
            robot::avoidance_camera(frames()->geometry, downscale, map.width, map.height), {});
        const robot::GroundModel* g = ground ? &*ground : nullptr;
        benchmark::DoNotOptimize(robot::decide_threshold(map, t, params.ndisp, {}, g));
        benchmark::DoNotOptimize(robot::decide_fuzzy(map, t, {}, robot::kDefaultBorder, g));
    }
    set_fps(state);
}

// One SLAM step (front end, motion, local and global map) at full size, frames 10 and 11 in
// turn.
void BM_SlamStep(benchmark::State& state) {
    if (skip_without_data(state)) {
        return;
    }
    const auto sequence =
        robot::slam::open_sequence(frames()->dir, robot::slam::Layout::kitti, std::nullopt);
    robot::slam::SlamParams params;
    params.threads = static_cast<int>(state.range(0));
    robot::slam::Slam slam(sequence.camera, params);
    bool odd = false;
    for (auto _ : state) {
        benchmark::DoNotOptimize(odd ? slam.process(frames()->left2, frames()->right2)
                                     : slam.process(frames()->left, frames()->right));
        odd = !odd;
    }
    set_fps(state);
}

BENCHMARK(BM_OpenCvStereoSGBM)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_EdgeFrontend)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_SparseFrontend)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_AvoidDecision)
    ->Args({1, 1})
    ->Args({2, 1})
    ->Args({1, 2})
    ->Args({2, 2})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_SlamStep)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

// Keeps each run's real time per iteration for the ratio summary.
class Collecting final : public benchmark::ConsoleReporter {
  public:
    void ReportRuns(const std::vector<Run>& runs) override {
        for (const Run& run : runs) {
            if (!run.error_occurred && run.run_type == Run::RT_Iteration) {
                seconds[run.benchmark_name()] =
                    run.GetAdjustedRealTime() / benchmark::GetTimeUnitMultiplier(run.time_unit);
            }
        }
        ConsoleReporter::ReportRuns(runs);
    }
    std::map<std::string, double> seconds;
};

}  // namespace

int main(int argc, char** argv) {
    benchmark::Initialize(&argc, argv);
    Collecting reporter;
    benchmark::RunSpecifiedBenchmarks(&reporter);
    benchmark::Shutdown();
    const auto base = reporter.seconds.find("BM_OpenCvStereoSGBM/real_time");
    if (base == reporter.seconds.end()) {
        std::cout << "no StereoSGBM baseline measured (filtered out, or no data): no ratios\n";
        return 0;
    }
    std::printf("\n%-36s %10s %10s %14s\n", "benchmark", "ms/frame", "frames/s", "x SGBM time");
    for (const auto& [name, s] : reporter.seconds) {
        std::printf("%-36s %10.1f %10.2f %14.2f\n", name.c_str(), 1000.0 * s, 1.0 / s,
                    s / base->second);
    }
    return 0;
}
