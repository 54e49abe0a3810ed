// The hierarchical levels as HLS kernels (hls/include/stereo/hls/hier_level.hpp, issue 45)
// against the model bit for bit: the tie ranks, each level (the quarter level's whole range, the
// refinement levels around random and chained predictions), the three levels chained, the whole
// search with the HLS 1-D pass, and the registry's engine; random pairs of several sizes moved
// both ways, CA on and off, and a Tsukuba crop.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <string>

#include "middlebury_crop.hpp"
#include "shifted_pairs.hpp"
#include "stereo/catalogue.hpp"
#include "stereo/defaults.hpp"
#include "stereo/hierarchical.hpp"
#include "stereo/hls/hier_level.hpp"
#include "stereo/hls/hierarchical.hpp"
#include "stereo/hls/match.hpp"
#include "stereo/matcher.hpp"
#include "stereo_io/io.hpp"
#include "stereo_io/test_support.hpp"

namespace stereo::hls {
namespace {

namespace model = stereo::hierarchical;
using test::same_level;
using test::shifted_2d;

const std::string kCensus(catalogue::cost(catalogue::Cost::census).name);

// The search's parameters on small random pairs: census, windows 5 / 7 / 9 (the thesis' are too
// large for 16-pixel quarter levels), the full level's winners.
model::Params small_params(int ndisp, int vrange, bool use_ca) {
    model::Params params;
    params.ndisp = ndisp;
    params.vrange = vrange;
    params.levels = {model::default_level(5), model::default_level(7), model::default_level(9)};
    params.use_ca = use_ca;
    params.cost = kCensus;
    params.output = model::Output::full_level;
    return params;
}

// A random pair whose right image is the left moved (dx, dy): winners off v = 0.
struct Case {
    int width;
    int height;
    int dx;
    int dy;
};

io::ImagePair moved_pair(const Case& c, int channels, std::mt19937& rng) {
    const Image left = test::random_image(c.width, c.height, channels, rng);
    return {left, shifted_2d(left, c.dx, c.dy, 4, rng)};
}

int off_zero(const model::LevelMap& map) {
    return static_cast<int>(std::count_if(map.vertical.begin(), map.vertical.end(),
                                          [](std::int16_t v) { return v != 0; }));
}

// ---- the tie order ---------------------------------------------------------------------------

// kTieRank sorts the labels as stereo::tie_key does, relative to the base, for every pixel.
template <int COLS, int ROWS, bool REFINE, int V_MIN>
void expect_ranks_follow_tie_key(int base_d, int base_v, int prefer_d, int prefer_v) {
    using Wta = level_wta<COLS, ROWS, REFINE, V_MIN>;
    for (int a = 0; a < COLS * ROWS; ++a) {
        for (int b = 0; b < COLS * ROWS; ++b) {
            const auto key = [&](int k) {
                return tie_key(base_d + k % COLS, base_v + k / COLS, prefer_d, prefer_v);
            };
            EXPECT_EQ(Wta::kTieRank[static_cast<std::size_t>(a)] <
                          Wta::kTieRank[static_cast<std::size_t>(b)],
                      key(a) < key(b))
                << a << " " << b;
        }
    }
}

TEST(HlsLevelWta, TieRanksFollowTheModelsTieKey) {
    expect_ranks_follow_tie_key<4, 4, false, -2>(0, -2, 0, 0);   // quarter, D = V = 16
    expect_ranks_follow_tie_key<16, 4, false, -2>(0, -2, 0, 0);  // quarter, the defaults
    expect_ranks_follow_tie_key<3, 3, true, -4>(7, -3, 8, -2);   // a refinement 3x3
    expect_ranks_follow_tie_key<3, 3, true, -4>(0, 1, 1, 2);     // at the range's corner
}

// ---- each level -------------------------------------------------------------------------------

TEST(HlsHierarchical, QuarterLevelEqualsModel) {
    std::mt19937 rng = test::seeded_rng(1);
    for (const Case& c : {Case{72, 56, 4, 4}, Case{61, 47, 3, -4}, Case{45, 53, 0, 0}}) {
        for (const auto& [ndisp, vrange] :
             {std::pair{16, 16}, std::pair{8, 8}, std::pair{32, 16}}) {
            for (const bool use_ca : {true, false}) {
                SCOPED_TRACE(std::to_string(c.width) + "x" + std::to_string(c.height) + " D " +
                             std::to_string(ndisp) + " V " + std::to_string(vrange) +
                             (use_ca ? " CA" : " no CA"));
                const io::ImagePair pair = moved_pair(c, 3, rng);
                const Image left = model::downscale_area(pair.left, 4);
                const Image right = model::downscale_area(pair.right, 4);
                const model::Params params = small_params(ndisp, vrange, use_ca);
                const model::SearchRange range = model::level_range(params, 4);
                const CandidateGrid grid = model::full_grid(left.width, left.height, range);
                std::int64_t model_count = 0;
                std::int64_t hls_count = 0;
                const model::LevelMap expected =
                    model::match_level(left, right, grid, params.levels[0], use_ca,
                                       CaNeighbours::horizontal, model_count, kCensus);
                const model::LevelMap actual = hierarchical::match_level(
                    left, right, grid, range, params.levels[0], use_ca, hls_count);
                EXPECT_TRUE(same_level(expected, actual));
                EXPECT_EQ(hls_count, model_count);
            }
        }
    }
}

// Refinement levels around random predictions (every base of the range, clamped at its ends) and
// around the level below's winners.
TEST(HlsHierarchical, RefinementLevelsEqualModel) {
    std::mt19937 rng = test::seeded_rng(2);
    for (const Case& c : {Case{64, 48, 3, 3}, Case{59, 41, 5, -3}}) {
        for (const int factor : {2, 1}) {
            for (const bool use_ca : {true, false}) {
                SCOPED_TRACE(std::to_string(c.width) + "x" + std::to_string(c.height) + " factor " +
                             std::to_string(factor) + (use_ca ? " CA" : " no CA"));
                const io::ImagePair pair = moved_pair(c, 1, rng);
                const Image left = model::downscale_area(pair.left, factor);
                const Image right = model::downscale_area(pair.right, factor);
                const model::Params params = small_params(16, 16, use_ca);
                const model::SearchRange range = model::level_range(params, factor);
                const model::SearchRange coarse_range = model::level_range(params, 2 * factor);
                // A random coarse map of the next coarser size, every winner in its range.
                model::LevelMap coarse{left.width / 2, left.height / 2, {}, {}, {}};
                std::uniform_int_distribution<int> d(coarse_range.d_min, coarse_range.d_max);
                std::uniform_int_distribution<int> v(coarse_range.v_min, coarse_range.v_max);
                for (int p = 0; p < coarse.width * coarse.height; ++p) {
                    coarse.disparity.push_back(static_cast<std::int16_t>(d(rng)));
                    coarse.vertical.push_back(static_cast<std::int16_t>(v(rng)));
                    coarse.valid.push_back(1);
                }
                const CandidateGrid grid =
                    model::refine_grid(coarse, left.width, left.height, range);
                const model::LevelParams level = params.levels[factor == 2 ? 1 : 2];
                std::int64_t model_count = 0;
                std::int64_t hls_count = 0;
                const model::LevelMap expected =
                    model::match_level(left, right, grid, level, use_ca, CaNeighbours::horizontal,
                                       model_count, kCensus);
                const model::LevelMap actual =
                    hierarchical::match_level(left, right, grid, range, level, use_ca, hls_count);
                EXPECT_TRUE(same_level(expected, actual));
                EXPECT_EQ(hls_count, model_count);
            }
        }
    }
}

// ---- the three levels chained -------------------------------------------------------------------

void expect_levels_equal(const Image& left, const Image& right, const model::Params& params) {
    model::CostCount model_count;
    model::CostCount hls_count;
    const auto expected = model::match_levels(left, right, params, model_count);
    const auto actual = hierarchical::match_levels(left, right, params, hls_count);
    for (std::size_t l = 0; l < expected.size(); ++l) {
        EXPECT_TRUE(same_level(expected[l], actual[l])) << model::kLevelNames[l];
    }
    EXPECT_EQ(hls_count.level, model_count.level);
    // The pairs are moved: the full level's winners leave v = 0 (else the test proves less).
    EXPECT_GT(off_zero(expected[2]), 0);
}

TEST(HlsHierarchical, ThreeLevelsEqualModel) {
    std::mt19937 rng = test::seeded_rng(3);
    for (const Case& c : {Case{96, 72, 4, 3}, Case{83, 69, 2, -5}, Case{64, 52, 6, 2}}) {
        for (const auto& [ndisp, vrange] : {std::pair{16, 16}, std::pair{8, 8}}) {
            for (const bool use_ca : {true, false}) {
                SCOPED_TRACE(std::to_string(c.width) + "x" + std::to_string(c.height) + " D " +
                             std::to_string(ndisp) + " V " + std::to_string(vrange) +
                             (use_ca ? " CA" : " no CA"));
                const Case moved{c.width, c.height, std::min(c.dx, ndisp / 2),
                                 std::clamp(c.dy, -vrange / 2 + 1, vrange / 2 - 1)};
                const io::ImagePair pair = moved_pair(moved, 3, rng);
                expect_levels_equal(pair.left, pair.right, small_params(ndisp, vrange, use_ca));
            }
        }
    }
}

// ---- a real crop: the levels, the whole search with the field and the HLS pass, the registry ----

TEST(HlsHierarchical, RealCropEqualsModel) {
    // Tsukuba, the right crop 3 rows lower: the scene moves up by 3 rows in the right image.
    const auto left_crop = test::middlebury_crop("tsukuba", 120, 100, 128, 96);
    const auto right_crop = test::middlebury_crop("tsukuba", 120, 103, 128, 96);
    if (!left_crop || !right_crop) {
        GTEST_SKIP() << "Middlebury 2003 tsukuba not under the data directory";
    }
    const Image& left = left_crop->left;
    const Image& right = right_crop->right;
    {
        SCOPED_TRACE("the defaults' levels, D 16, V 16");
        model::Params params;
        params.ndisp = 16;
        params.cost = kCensus;
        expect_levels_equal(left, right, params);
    }
    {
        SCOPED_TRACE("the thesis' levels 9 / 15 / 23, no CA");
        model::Params params = model::Params::thesis();
        params.ndisp = 16;
        params.vrange = 16;
        params.cost = kCensus;
        params.use_ca = false;
        expect_levels_equal(left, right, params);
    }
    // The registry's default run (the field with its plane prior, the pass with stage 6): the
    // engine's result equals the model engine's.
    MatcherRegistry registry;
    register_model_matchers(registry);
    register_matchers(registry);
    const std::string method(catalogue::method(catalogue::Method::hierarchical).name);
    MatchConfig config = defaults::match_config(method, "hls");
    config.pipeline.ndisp = 16;
    const MatchResult expected = registry.create(method, "model", config)->compute(left, right);
    const MatchResult actual = registry.create(method, "hls", config)->compute(left, right);
    EXPECT_EQ(actual.validated, expected.validated);
    EXPECT_EQ(actual.disparity, expected.disparity);
    EXPECT_EQ(actual.vertical, expected.vertical);
    ASSERT_EQ(actual.levels.size(), expected.levels.size());
    for (std::size_t l = 0; l < expected.levels.size(); ++l) {
        EXPECT_TRUE(same_level(expected.levels[l], actual.levels[l])) << l;
    }
    EXPECT_EQ(actual.counts, expected.counts);
}

// ---- what the levels refuse
// ------------------------------------------------------------------------

TEST(HlsHierarchical, RefusesWhatTheLevelsDoNotCompute) {
    std::mt19937 rng = test::seeded_rng(4);
    const io::ImagePair pair = moved_pair({64, 48, 2, 1}, 3, rng);
    model::CostCount count;
    const auto run = [&](const model::Params& params) {
        return hierarchical::match_levels(pair.left, pair.right, params, count);
    };
    model::Params ad = small_params(16, 16, true);
    ad.cost = catalogue::cost(catalogue::Cost::ad).name;
    EXPECT_THROW(run(ad), std::invalid_argument);
    model::Params vertical_neighbours = small_params(16, 16, true);
    vertical_neighbours.neighbours = CaNeighbours::horizontal_and_vertical;
    EXPECT_THROW(run(vertical_neighbours), std::invalid_argument);
    EXPECT_THROW(run(small_params(24, 16, true)), std::invalid_argument);  // not compiled
    EXPECT_NO_THROW(run(small_params(16, 16, true)));
}

}  // namespace
}  // namespace stereo::hls
