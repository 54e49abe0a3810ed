#include "stereo/hls/hierarchical.hpp"

#include <functional>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include "stereo/catalogue.hpp"
#include "stereo/hls/hier_level.hpp"
#include "stereo/hls/host.hpp"
#include "stereo/hls/match.hpp"

namespace stereo::hls::hierarchical {
namespace {

namespace model = stereo::hierarchical;

// The quarter level of a search with ndisp D and vrange V: (D/4) x (V/4) candidates, offsets
// -(V/4)/2 .. (the model's level_range at factor 4).
template <int D, int V>
using quarter_level = hier_level<kHostMaxWidth / 4, D / 4, V / 4, -(V / 4 / 2),
                                 -(V / 4 / 2) + V / 4 - 1, kHostLevelWindow, false>;
// A refinement level whose range has the offsets -HALF .. HALF - 1: the half level of V = 4 HALF,
// the full level of V = 2 HALF.
template <int HALF>
using refine_level = hier_level<kHostMaxWidth, 3, 3, -HALF, HALF - 1, kHostLevelWindow, true>;

template <class... Levels>
struct level_list {};
// The compiled levels: the quarter levels of (D, V) = (8, 8), (16, 16), (32, 16), (64, 16) (the
// defaults) and (64, 64) (the thesis' V = D), and every refinement level they need.
using CompiledLevels =
    level_list<quarter_level<8, 8>, quarter_level<16, 16>, quarter_level<32, 16>,
               quarter_level<64, 16>, quarter_level<64, 64>, refine_level<2>, refine_level<4>,
               refine_level<8>, refine_level<16>, refine_level<32>>;

template <class Level>
constexpr LevelShape shape_of() {
    return {Level::kCols, Level::kRows, Level::kVMin, Level::kVMax, Level::kRefine};
}

template <class... Levels>
std::vector<LevelShape> shapes(level_list<Levels...>) {
    return {shape_of<Levels>()...};
}

// The cfg ports of a level: the model's kernel of the level's window centred in WINDOW taps.
template <int WINDOW>
LevelConfig<WINDOW> level_config(const LevelParams& level, bool use_ca, int width, int height) {
    const std::vector<std::int32_t> taps = gaussian_kernel(level.window, level.sigma);
    LevelConfig<WINDOW> cfg;
    cfg.width = width;
    cfg.height = height;
    cfg.radius = level.window / 2;
    cfg.use_ca = use_ca;
    const int first = (WINDOW - level.window) / 2;
    for (std::size_t i = 0; i < taps.size(); ++i) {
        cfg.kernel[first + static_cast<int>(i)] = static_cast<tap_t>(taps[i]);
    }
    return cfg;
}

// Streams the pair through a Level: W*H steps with the pixels, then flush steps with pixels below
// the frame until the last winner is out. The host plays the prediction ring: it reads the base
// of the pixel the level asks for, and of the pixel whose winner leaves, from the grid.
template <class Level>
LevelMap run_level(const Image& left, const Image& right, const CandidateGrid& grid,
                   const LevelParams& level, bool use_ca) {
    const int width = left.width;
    const int height = left.height;
    if (level.window > Level::kWindow) {
        throw std::invalid_argument("level window " + std::to_string(level.window) +
                                    " is larger than the synthesised " +
                                    std::to_string(Level::kWindow));
    }
    const auto state = std::make_unique<Level>();  // megabytes of line buffers: on the heap
    const LevelConfig<Level::kWindow> cfg =
        level_config<Level::kWindow>(level, use_ca, width, height);
    const auto base = [&](int x, int y) {
        if (!inside(x, y, width, height)) {
            return std::pair{0, 0};  // a pixel outside the frame: no real base needed
        }
        const std::size_t g = grid.at(static_cast<std::size_t>(y) * width + x);
        return std::pair{int{grid.base_d[g]}, int{grid.base_v[g]}};
    };
    const std::size_t size = static_cast<std::size_t>(width) * height;
    LevelMap map{width, height, std::vector<std::int16_t>(size), std::vector<std::int16_t>(size),
                 std::vector<std::uint8_t>(size, 0)};
    // Latency bound: census 2 rows, the vertical range below the pixel, the window, the CA rows.
    const long long max_steps =
        static_cast<long long>(size) +
        static_cast<long long>(Level::kVMax + Level::kWindow + 8) * (width + 1) + 64;
    state->reset();
    std::size_t collected = 0;
    int x = 0;
    int y = 0;  // raster position of this step's input; y >= height while flushing
    for (long long step = 0; collected < size; ++step) {
        if (step == max_steps) {
            throw std::logic_error("HLS level wrote " + std::to_string(collected) + " winners of " +
                                   std::to_string(size));
        }
        const bool pixel_step = y < height;
        const Rgb left_pixel = pixel_step ? rgb(left, x, y) : Rgb{};
        const Rgb right_pixel = pixel_step ? rgb(right, x, y) : Rgb{};
        const auto [in_base_d, in_base_v] = base(state->req_x(), state->req_y());
        state->step(to_coord(x), to_coord(y), left_pixel, right_pixel, cfg, in_base_d, in_base_v);
        const int out_x = state->out_x();
        const int out_y = state->out_y();
        if (inside(out_x, out_y, width, height)) {
            const std::size_t p = map.index(out_x, out_y);
            if (p != collected) {
                throw std::logic_error("HLS level output out of raster order");
            }
            const auto [out_base_d, out_base_v] = base(out_x, out_y);
            const LevelWinner winner = state->winner(cfg, out_base_d, out_base_v);
            map.disparity[p] = static_cast<std::int16_t>(winner.d);
            map.vertical[p] = static_cast<std::int16_t>(winner.v);
            map.valid[p] = winner.valid ? 1 : 0;
            ++collected;
        }
        if (++x == width) {
            x = 0;
            ++y;
        }
    }
    return map;
}

// The compiled level of `shape` on the pair, or nothing when none has that shape.
template <class... Levels>
std::optional<LevelMap> run_compiled(level_list<Levels...>, const LevelShape& shape,
                                     const Image& left, const Image& right,
                                     const CandidateGrid& grid, const LevelParams& level,
                                     bool use_ca) {
    std::optional<LevelMap> map;
    (void)((shape_of<Levels>() == shape
                ? (map = run_level<Levels>(left, right, grid, level, use_ca), true)
                : false) ||
           ...);
    return map;
}

// The grid's shape when it is one the levels compute: the quarter level's (every pixel's base
// (0, v_min), preferring (0, 0), the whole range) or a refinement level's (3x3 inside the range,
// preferring the centre; its preferred d is at least 1, so the two never meet).
LevelShape shape_of_grid(const CandidateGrid& grid, const SearchRange& range) {
    const auto quarter_pixel = [&](std::size_t g) {
        return grid.base_d[g] == 0 && grid.base_v[g] == range.v_min && grid.prefer_d[g] == 0 &&
               grid.prefer_v[g] == 0;
    };
    const auto refine_pixel = [&](std::size_t g) {
        return grid.prefer_d[g] == grid.base_d[g] + 1 && grid.prefer_v[g] == grid.base_v[g] + 1 &&
               grid.base_d[g] >= 0 && grid.base_v[g] >= range.v_min &&
               grid.base_v[g] + 2 <= range.v_max;
    };
    const bool refine = !quarter_pixel(0);
    const auto fits = refine ? std::function<bool(std::size_t)>(refine_pixel)
                             : std::function<bool(std::size_t)>(quarter_pixel);
    bool every_pixel =
        refine ? grid.cols == 3 && grid.rows == 3 : grid.rows == range.v_max - range.v_min + 1;
    for (std::size_t g = 0; g < grid.base_d.size() && every_pixel; ++g) {
        every_pixel = fits(g);
    }
    if (!every_pixel) {
        throw std::invalid_argument(
            "the HLS levels compute the quarter level's whole range (base (0, v_min), preferring "
            "(0, 0)) or a 3x3 refinement preferring its centre inside the range, not this grid");
    }
    return {grid.cols, grid.rows, range.v_min, range.v_max, refine};
}

}  // namespace

std::vector<LevelShape> compiled_levels() {
    return shapes(CompiledLevels{});
}

std::string compiled_ranges() {
    std::string text;
    for (const LevelShape& shape : compiled_levels()) {
        if (!shape.refine) {
            text += (text.empty() ? "" : ", ") + std::string("D ") +
                    std::to_string(4 * shape.cols) + " V " + std::to_string(4 * shape.rows);
        }
    }
    return text;
}

LevelMap match_level(const Image& left, const Image& right, const CandidateGrid& grid,
                     const SearchRange& range, const LevelParams& level, bool use_ca,
                     std::int64_t& count) {
    check_pair(left, right);
    if (grid.width != left.width || grid.height != left.height || grid.cols < 1 || grid.rows < 1) {
        throw std::invalid_argument("candidate grid does not fit the level image");
    }
    const LevelShape shape = shape_of_grid(grid, range);
    std::optional<LevelMap> map =
        run_compiled(CompiledLevels{}, shape, left, right, grid, level, use_ca);
    if (!map) {
        throw std::invalid_argument(
            "no compiled HLS level has " + std::to_string(shape.cols) + "x" +
            std::to_string(shape.rows) + " candidates with offsets " + std::to_string(shape.v_min) +
            " .. " + std::to_string(shape.v_max) + " (compiled: " + compiled_ranges() + ")");
    }
    count += static_cast<std::int64_t>(left.width) * left.height * grid.cols * grid.rows;
    return *std::move(map);
}

void check(const Params& params, int width, int height) {
    catalogue::require_cost(params.cost, catalogue::CostUse::hardware, "the HLS levels");
    if (catalogue::cost(params.cost).id != catalogue::Cost::census) {
        throw std::invalid_argument("the HLS levels compute the " +
                                    std::string(catalogue::cost(catalogue::Cost::census).name) +
                                    " cost only, as the RTL's (--cost " + params.cost + ")");
    }
    if (params.neighbours != CaNeighbours::horizontal) {
        throw std::invalid_argument(
            "the HLS levels' CA rule 1 reads the horizontal neighbours only");
    }
    if (width > kHostMaxWidth || height > kHostMaxHeight) {
        throw std::invalid_argument("image " + std::to_string(width) + "x" +
                                    std::to_string(height) + " is larger than the HLS levels' " +
                                    std::to_string(kHostMaxWidth) + "x" +
                                    std::to_string(kHostMaxHeight));
    }
    const SearchRange quarter = model::level_range(params, model::kLevelFactor[0]);
    const LevelShape wanted{quarter.d_max + 1, quarter.v_max - quarter.v_min + 1, quarter.v_min,
                            quarter.v_max, false};
    for (const LevelShape& shape : compiled_levels()) {
        if (shape == wanted) {
            return;  // its refinement levels are compiled with it
        }
    }
    throw std::invalid_argument("no compiled HLS levels for ndisp " + std::to_string(params.ndisp) +
                                " and vrange " + std::to_string(params.vertical_range()) +
                                " (compiled: " + compiled_ranges() + ")");
}

std::array<LevelMap, model::kLevels> match_levels(const Image& left, const Image& right,
                                                  const Params& params, CostCount& count) {
    check_pair(left, right);
    model::validate(params, left.width, left.height);
    check(params, left.width, left.height);
    std::array<LevelMap, model::kLevels> levels;
    for (int level = 0; level < model::kLevels; ++level) {
        const auto l = static_cast<std::size_t>(level);
        const int factor = model::kLevelFactor[l];
        const Image level_left = factor == 1 ? left : model::downscale_area(left, factor);
        const Image level_right = factor == 1 ? right : model::downscale_area(right, factor);
        const SearchRange range = model::level_range(params, factor);
        const CandidateGrid grid =
            level == 0
                ? model::full_grid(level_left.width, level_left.height, range)
                : model::refine_grid(levels[l - 1], level_left.width, level_left.height, range);
        levels[l] = match_level(level_left, level_right, grid, range, params.levels[l],
                                params.use_ca, count.level[l]);
    }
    return levels;
}

model::Result match(const Image& left, const Image& right, const Params& params) {
    return model::match(left, right, params, {&match_levels, &hls::match_validated});
}

void register_matchers(MatcherRegistry& registry) {
    registry.add({std::string(catalogue::method(catalogue::Method::hierarchical).name), "hls",
                  "Sec. 3.3 search, the levels and the 1-D pass as HLS kernels in C simulation "
                  "(census)",
                  hierarchical_factory(&match, &check)});
}

}  // namespace stereo::hls::hierarchical
