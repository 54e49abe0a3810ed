// The fast CPU engine (stereo/fast_engine.hpp) against the model engine: the same validated map,
// bit for bit, on every scene with ground truth, on random pairs for every option, and for every
// thread count 1..4; bad thread counts are refused in one line.
#include <gtest/gtest.h>

#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "stereo/catalogue.hpp"
#include "stereo/defaults.hpp"
#include "stereo/fast_engine.hpp"
#include "stereo/matcher.hpp"
#include "stereo/pipeline.hpp"
#include "stereo_io/data_dir.hpp"
#include "stereo_io/io.hpp"
#include "stereo_io/test_support.hpp"

namespace stereo {
namespace {

// The first pixel where two validated maps differ, for the failure message.
std::string first_difference(const ValidatedDisparity& a, const ValidatedDisparity& b) {
    if (a.width != b.width || a.height != b.height) {
        return "sizes differ";
    }
    for (std::size_t q = 0; q < a.fixed.size(); ++q) {
        if (a.fixed[q] != b.fixed[q] || a.reason[q] != b.reason[q] ||
            a.certainty[q] != b.certainty[q]) {
            return "pixel (" + std::to_string(q % a.width) + ", " + std::to_string(q / a.width) +
                   "): model " + std::to_string(a.fixed[q]) + "/" + std::to_string(a.reason[q]) +
                   "/" + std::to_string(a.certainty[q]) + ", fast " + std::to_string(b.fixed[q]) +
                   "/" + std::to_string(b.reason[q]) + "/" + std::to_string(b.certainty[q]);
        }
    }
    return "equal";
}

void expect_same(const Image& left, const Image& right, const MatchParams& params, int threads,
                 const std::string& what) {
    ValidatedDisparity model;
    try {
        model = match_validated(left, right, params);
    } catch (const std::invalid_argument&) {  // e.g. lcdm on grey images: both refuse
        EXPECT_THROW(fast::match_validated(left, right, params, threads), std::invalid_argument)
            << what;
        return;
    }
    const ValidatedDisparity fast = fast::match_validated(left, right, params, threads);
    EXPECT_TRUE(model == fast) << what << " threads " << threads << ": "
                               << first_difference(model, fast);
}

// A smooth random image (noise blurred by a running mean), so that the CA rules fire often.
Image smooth_random(int width, int height, int channels, std::mt19937& rng) {
    const Image noise = test::random_image(width, height, channels, rng);
    Image out(width, height, channels);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            for (int c = 0; c < channels; ++c) {
                int sum = 0;
                int count = 0;
                for (int dy = -2; dy <= 2; ++dy) {
                    for (int dx = -2; dx <= 2; ++dx) {
                        const int nx = x + dx;
                        const int ny = y + dy;
                        if (nx >= 0 && ny >= 0 && nx < width && ny < height) {
                            sum += noise.at(nx, ny, c);
                            ++count;
                        }
                    }
                }
                out.at(x, y, c) = static_cast<std::uint8_t>(sum / count);
            }
        }
    }
    return out;
}

struct Scene {
    const char* folder;
    const char* left;
    const char* right;
    int downscale;
};

// Every scene with ground truth under the data folder (README.md of the data set).
const Scene kScenes[] = {
    {"middlebury2003/tsukuba", "left.png", "right.png", 1},
    {"middlebury2003/venus", "left.png", "right.png", 1},
    {"middlebury2003/teddy", "left.png", "right.png", 1},
    {"middlebury2003/cones", "left.png", "right.png", 1},
    {"middlebury2005/Reindeer", "view1.png", "view5.png", 3},
    {"middlebury2006/Cloth3", "view1.png", "view5.png", 3},
    {"middlebury2006/Wood2", "view1.png", "view5.png", 3},
    {"middlebury2014_illum/Motorcycle", "im0.png", "im1.png", 4},
};

TEST(FastEngine, EveryScene_DefaultCensusAndAd_EveryThreadCount) {
    int found = 0;
    for (const Scene& scene : kScenes) {
        const auto dir = io::data_dir() / scene.folder;
        if (!std::filesystem::exists(dir / scene.left)) {
            continue;
        }
        ++found;
        const io::ImagePair pair =
            io::load_pair(dir / scene.left, dir / scene.right, scene.downscale);
        MatchParams params = defaults::match_config("pipeline", "model").pipeline;
        for (int threads = 1; threads <= 4; ++threads) {
            expect_same(pair.left, pair.right, params, threads, std::string(scene.folder));
        }
        params.cost = std::string(catalogue::cost(catalogue::kFallbackCost).name);
        expect_same(pair.left, pair.right, params, 2, std::string(scene.folder) + " ad");
        params.use_ca = false;
        expect_same(pair.left, pair.right, params, 3, std::string(scene.folder) + " ad no CA");
    }
    if (found == 0) {
        GTEST_SKIP() << "no scene under " << io::data_dir();
    }
}

TEST(FastEngine, RandomPairs_EveryOption_EveryThreadCount) {
    auto rng = test::seeded_rng(49);
    const ValidationParams validations[] = {{},
                                            ValidationParams::all_on(),
                                            {true, 0, false, 0, false},
                                            {false, 20, true, 2, false},
                                            {false, 20, false, 0, true}};
    for (const std::string& cost : catalogue::cost_names()) {
        for (const int channels : {1, 3}) {
            const Image left = smooth_random(53, 37, channels, rng);
            const Image right = test::shifted_copy(left, 4, 6, rng);
            for (const bool ca : {true, false}) {
                for (const auto& validation : validations) {
                    for (const int min_disp : {0, -5, 3}) {
                        for (const int window : {1, 3, 11}) {
                            for (const int ndisp : {1, 2, 9}) {
                                MatchParams params;
                                params.cost = cost;
                                params.use_ca = ca;
                                params.validation = validation;
                                params.min_disp = min_disp;
                                params.window = window;
                                params.ndisp = ndisp;
                                const int threads = 1 + (window + ndisp + min_disp + 8) % 4;
                                expect_same(left, right, params, threads,
                                            cost + " ch " + std::to_string(channels) + " ca " +
                                                std::to_string(ca) + " min " +
                                                std::to_string(min_disp) + " w " +
                                                std::to_string(window) + " n " +
                                                std::to_string(ndisp));
                            }
                        }
                    }
                }
            }
        }
    }
}

TEST(FastEngine, EveryWindowRadius) {
    // The aggregation has one-pass kernels for radii 1 .. 7 and the tap-by-tap loop for the
    // others (radius 0, 8, 9 here); rows outside the image must add nothing in both.
    auto rng = test::seeded_rng(52);
    const Image left = smooth_random(45, 41, 3, rng);
    const Image right = test::shifted_copy(left, 3, 5, rng);
    MatchParams params = defaults::match_config("pipeline", "model").pipeline;
    params.ndisp = 6;
    for (int window = 1; window <= 19; window += 2) {
        params.window = window;
        expect_same(left, right, params, 1 + window % 3, "w " + std::to_string(window));
    }
}

TEST(FastEngine, TallAndTinyImages_TileSeams) {
    auto rng = test::seeded_rng(50);
    for (const auto& [width, height] : std::vector<std::pair<int, int>>{
             {40, 97}, {33, 16}, {33, 17}, {30, 15}, {24, 31}, {9, 9}}) {
        const Image left = smooth_random(width, height, 3, rng);
        const Image right = test::shifted_copy(left, 2, 4, rng);
        MatchParams params = defaults::match_config("pipeline", "model").pipeline;
        params.ndisp = 5;
        params.window = height > 12 ? 7 : 3;
        for (int threads = 1; threads <= 4; ++threads) {
            expect_same(left, right, params, threads,
                        std::to_string(width) + "x" + std::to_string(height));
        }
    }
}

TEST(FastEngine, OneEngine_ASequenceOfPairs) {
    auto rng = test::seeded_rng(51);
    const MatchParams params = defaults::match_config("pipeline", "model").pipeline;
    fast::Engine engine(params, 2);
    ValidatedDisparity out;
    for (const auto& [width, height] :
         std::vector<std::pair<int, int>>{{90, 60}, {90, 60}, {70, 50}}) {
        const Image left = smooth_random(width, height, 3, rng);
        const Image right = test::shifted_copy(left, 5, 8, rng);
        engine.match(left, right, out);
        EXPECT_TRUE(out == match_validated(left, right, params))
            << first_difference(match_validated(left, right, params), out);
    }
}

TEST(FastEngine, BadThreadCounts_OneLine) {
    const MatchParams params;
    for (const int threads : {0, -1, -100, fast::kMaxThreads + 1, 100000}) {
        try {
            fast::Engine engine(params, threads);
            ADD_FAILURE() << "threads " << threads << " accepted";
        } catch (const std::invalid_argument& error) {
            const std::string message = error.what();
            EXPECT_NE(message.find("threads"), std::string::npos) << message;
            EXPECT_EQ(message.find('\n'), std::string::npos) << message;
        }
    }
    EXPECT_NO_THROW(fast::Engine(params, fast::kMaxThreads));
}

TEST(FastEngine, TooSmallImage_OneLine) {
    const MatchParams params = defaults::match_config("pipeline", "model").pipeline;
    fast::Engine engine(params, 2);
    auto rng = test::seeded_rng(52);
    const Image small = test::random_image(100, 8, 3, rng);
    EXPECT_THROW(engine.match(small, small), std::invalid_argument);
}

}  // namespace
}  // namespace stereo
