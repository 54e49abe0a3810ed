#include "stereo/hierarchical.hpp"

#include <algorithm>
#include <cstdlib>
#include <stdexcept>
#include <string>

#include "plane_kernels.hpp"
#include "stereo/pipeline.hpp"

namespace stereo::hierarchical {
namespace {

using Value = Dsi::Value;

constexpr std::array<const char*, kLevels> kLevelName = {"quarter", "half", "full"};

// Lexicographic tie key (|v - pv|, |d - pd|, v, d) packed into one integer: among equal costs
// the candidate closest to the preferred displacement wins, vertically first.
std::int64_t tie_key(int d, int v, int prefer_d, int prefer_v) {
    return ((static_cast<std::int64_t>(std::abs(v - prefer_v)) * 512 + std::abs(d - prefer_d)) *
                256 +
            (v + 128)) *
               512 +
           d;
}

// Stage 1 for candidate (i, j): every pixel against its own displacement (base + (i, j)).
void cost_plane(const detail::PlanarImage& left, const detail::PlanarImage& right,
                const CandidateGrid& grid, int i, int j, Value* out) {
    const int width = left.width;
    const int height = left.height;
    const int weight = 3 / left.channels;  // a grey pixel counts as (g, g, g)
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const std::size_t p = static_cast<std::size_t>(y) * width + x;
            const int xr = x - (grid.base_d[p] + i);
            const int yr = y + grid.base_v[p] + j;
            if (xr < 0 || xr >= width || yr < 0 || yr >= height) {
                out[p] = static_cast<Value>(fx::kCostOutside);
                continue;
            }
            int sum = 0;
            for (int c = 0; c < left.channels; ++c) {
                const int diff = left.row(c, y)[x] - right.row(c, yr)[xr];
                sum += diff < 0 ? -diff : diff;
            }
            out[p] = static_cast<Value>(weight * sum);
        }
    }
}

std::string level_message(int level, int width, int height, const std::string& what) {
    return std::string(kLevelName[static_cast<std::size_t>(level)]) + " level (" +
           std::to_string(width) + "x" + std::to_string(height) + "): " + what;
}

}  // namespace

SearchRange level_range(const Params& params, int factor) {
    const int horizontal = params.ndisp / factor;
    const int vertical = params.vertical_range() / factor;
    const int v_min = -(vertical / 2);
    return {0, horizontal - 1, v_min, v_min + vertical - 1};
}

CandidateGrid full_grid(int width, int height, const SearchRange& range) {
    const std::size_t size = static_cast<std::size_t>(width) * height;
    const auto fill = [size](int value) {
        return std::vector<std::int16_t>(size, static_cast<std::int16_t>(value));
    };
    return {width,
            height,
            range.d_max - range.d_min + 1,
            range.v_max - range.v_min + 1,
            fill(range.d_min),
            fill(range.v_min),
            fill(std::clamp(0, range.d_min, range.d_max)),
            fill(std::clamp(0, range.v_min, range.v_max))};
}

CandidateGrid refine_grid(const LevelMap& coarse, int width, int height, const SearchRange& range) {
    const std::size_t size = static_cast<std::size_t>(width) * height;
    CandidateGrid grid{width, height, 3, 3, {}, {}, {}, {}};
    grid.base_d.resize(size);
    grid.base_v.resize(size);
    grid.prefer_d.resize(size);
    grid.prefer_v.resize(size);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const std::size_t parent =
                coarse.index(std::min(x / 2, coarse.width - 1), std::min(y / 2, coarse.height - 1));
            // Up-scaled x2, then clamped so that the whole 3x3 stays inside the level's range.
            const int d =
                std::clamp(2 * coarse.disparity[parent], range.d_min + 1, range.d_max - 1);
            const int v = std::clamp(2 * coarse.vertical[parent], range.v_min + 1, range.v_max - 1);
            const std::size_t p = static_cast<std::size_t>(y) * width + x;
            grid.base_d[p] = static_cast<std::int16_t>(d - 1);
            grid.base_v[p] = static_cast<std::int16_t>(v - 1);
            grid.prefer_d[p] = static_cast<std::int16_t>(d);
            grid.prefer_v[p] = static_cast<std::int16_t>(v);
        }
    }
    return grid;
}

bool level_valid(int x, int y, int d, int v, int width, int height, int reach) {
    return x >= reach && x < width - reach && y >= reach && y < height - reach && x - d >= reach &&
           y + v >= reach && y + v < height - reach;
}

LevelMap match_level(const Image& left, const Image& right, const CandidateGrid& grid,
                     const LevelParams& level, bool use_ca, CaNeighbours neighbours,
                     std::int64_t& count) {
    check_pair(left, right);
    if (grid.width != left.width || grid.height != left.height || grid.cols < 1 || grid.rows < 1) {
        throw std::invalid_argument("candidate grid does not fit the level image");
    }
    const int width = left.width;
    const int height = left.height;
    const std::size_t plane_size = static_cast<std::size_t>(width) * height;
    const int cols = grid.cols;
    const int rows = grid.rows;
    const bool vertical_rule = use_ca && neighbours == CaNeighbours::horizontal_and_vertical;

    const detail::PlanarImage left_planes(left);
    const detail::PlanarImage right_planes(right);
    detail::PlaneAggregator aggregator(gaussian_kernel(level.window, level.sigma), width, height);
    detail::PlaneRule1 rule1(width, height);

    // Aggregated planes of candidate rows j-1, j, j+1 in a ring (row j lives in slot j % 3): the
    // CA rules of row j need no other row, so a D x V search never holds the whole volume.
    std::array<std::vector<std::vector<Value>>, 3> ring;
    for (auto& slot : ring) {
        slot.assign(static_cast<std::size_t>(cols), std::vector<Value>(plane_size));
    }
    std::vector<Value> cost(plane_size);
    auto aggregate_row = [&](int j) {
        auto& slot = ring[static_cast<std::size_t>(j % 3)];
        for (int i = 0; i < cols; ++i) {
            cost_plane(left_planes, right_planes, grid, i, j, cost.data());
            aggregator.run(cost.data(), slot[static_cast<std::size_t>(i)].data());
            count += static_cast<std::int64_t>(plane_size);
        }
    };
    auto plane = [&](int i, int j) -> const Value* {
        if (i < 0 || i >= cols || j < 0 || j >= rows) {
            return nullptr;
        }
        return ring[static_cast<std::size_t>(j % 3)][static_cast<std::size_t>(i)].data();
    };

    std::vector<Value> rule1_plane(plane_size);
    std::vector<Value> rule1_vertical(plane_size);
    std::vector<Value> rule2_plane(plane_size);
    std::vector<Value> best(plane_size);
    std::vector<std::int64_t> best_key(plane_size);
    std::vector<std::int16_t> best_i(plane_size, 0);
    std::vector<std::int16_t> best_j(plane_size, 0);

    aggregate_row(0);
    for (int j = 0; j < rows; ++j) {
        if (vertical_rule && j + 1 < rows) {
            aggregate_row(j + 1);  // rule 1 of row j reads row j + 1
        } else if (!vertical_rule && j > 0) {
            aggregate_row(j);
        }
        for (int i = 0; i < cols; ++i) {
            const Value* final_plane = plane(i, j);
            if (use_ca) {
                rule1.run(plane(i - 1, j), plane(i, j), plane(i + 1, j), rule1_plane.data());
                if (vertical_rule) {
                    // Fired by either pair: the horizontal result where it changed the cell,
                    // else the vertical one (equal to the centre unless that pair fired; a fired
                    // cell whose mean equals the centre is the same either way).
                    rule1.run(plane(i, j - 1), plane(i, j), plane(i, j + 1), rule1_vertical.data());
                    const Value* centre = plane(i, j);
                    for (std::size_t p = 0; p < plane_size; ++p) {
                        if (rule1_plane[p] == centre[p]) {
                            rule1_plane[p] = rule1_vertical[p];
                        }
                    }
                }
                detail::ca_rule2_plane(rule1_plane.data(), width, height, rule2_plane.data());
                final_plane = rule2_plane.data();
            }
            for (std::size_t p = 0; p < plane_size; ++p) {
                const std::int64_t key = tie_key(grid.base_d[p] + i, grid.base_v[p] + j,
                                                 grid.prefer_d[p], grid.prefer_v[p]);
                if ((i == 0 && j == 0) || final_plane[p] < best[p] ||
                    (final_plane[p] == best[p] && key < best_key[p])) {
                    best[p] = final_plane[p];
                    best_key[p] = key;
                    best_i[p] = static_cast<std::int16_t>(i);
                    best_j[p] = static_cast<std::int16_t>(j);
                }
            }
        }
    }

    LevelMap map{width, height, std::vector<std::int16_t>(plane_size),
                 std::vector<std::int16_t>(plane_size), std::vector<std::uint8_t>(plane_size)};
    const int reach = level.window / 2 + (use_ca ? 1 : 0);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const std::size_t p = map.index(x, y);
            map.disparity[p] = static_cast<std::int16_t>(grid.base_d[p] + best_i[p]);
            map.vertical[p] = static_cast<std::int16_t>(grid.base_v[p] + best_j[p]);
            map.valid[p] =
                level_valid(x, y, map.disparity[p], map.vertical[p], width, height, reach) ? 1 : 0;
        }
    }
    return map;
}

Image downscale_area(const Image& image, int factor) {
    if (factor < 1 || image.width / factor < 1 || image.height / factor < 1) {
        throw std::invalid_argument("cannot downscale a " + std::to_string(image.width) + "x" +
                                    std::to_string(image.height) + " image by " +
                                    std::to_string(factor));
    }
    Image out(image.width / factor, image.height / factor, image.channels);
    const int area = factor * factor;
    std::vector<int> row_sum(static_cast<std::size_t>(out.width) * out.channels);
    for (int y = 0; y < out.height; ++y) {
        std::fill(row_sum.begin(), row_sum.end(), 0);
        for (int dy = 0; dy < factor; ++dy) {
            for (int x = 0; x < out.width * factor; ++x) {
                for (int c = 0; c < image.channels; ++c) {
                    row_sum[static_cast<std::size_t>(x / factor) * image.channels + c] +=
                        image.at(x, y * factor + dy, c);
                }
            }
        }
        for (int x = 0; x < out.width; ++x) {
            for (int c = 0; c < image.channels; ++c) {
                const int sum = row_sum[static_cast<std::size_t>(x) * image.channels + c];
                out.at(x, y, c) = static_cast<std::uint8_t>((sum + area / 2) / area);
            }
        }
    }
    return out;
}

void validate(const Params& params, int width, int height) {
    const auto check_range = [](const char* name, int value, int max) {
        if (value % 4 != 0 || value < 8 || value > max) {
            throw std::invalid_argument(std::string(name) + " must be a multiple of 4 in [8, " +
                                        std::to_string(max) + "] for three levels, got " +
                                        std::to_string(value));
        }
    };
    check_range("ndisp", params.ndisp, fx::kMaxDisparities);
    if (params.vrange < 0) {
        throw std::invalid_argument("vrange must be >= 0 (0 = same as ndisp), got " +
                                    std::to_string(params.vrange));
    }
    check_range("vrange", params.vertical_range(), kMaxVerticalRange);
    for (int level = 0; level < kLevels; ++level) {
        const int factor = kLevelFactor[static_cast<std::size_t>(level)];
        const LevelParams& lp = params.levels[static_cast<std::size_t>(level)];
        const int level_width = width / factor;
        const int level_height = height / factor;
        try {
            stereo::validate(MatchParams{params.ndisp / factor, lp.window, lp.sigma, params.use_ca},
                             level_width, level_height);
        } catch (const std::invalid_argument& error) {
            throw std::invalid_argument(
                level_message(level, level_width, level_height, error.what()));
        }
    }
}

namespace {

Result finish(std::array<LevelMap, kLevels> levels, const CostCount& count) {
    Result result{{}, {}, std::move(levels), count};
    const LevelMap& full = result.levels[kLevels - 1];
    result.disparity = DisparityMap(full.width, full.height);
    result.vertical.assign(full.valid.size(), 0);
    for (std::size_t p = 0; p < full.valid.size(); ++p) {
        if (full.valid[p] != 0) {
            result.disparity.disparity[p] = static_cast<std::uint8_t>(full.disparity[p]);
            result.disparity.valid[p] = 1;
            result.vertical[p] = static_cast<std::int8_t>(full.vertical[p]);
        }
    }
    return result;
}

}  // namespace

Result match(const Image& left, const Image& right, const Params& params) {
    check_pair(left, right);
    validate(params, left.width, left.height);
    CostCount count;
    std::array<LevelMap, kLevels> levels;
    for (int level = 0; level < kLevels; ++level) {
        const auto l = static_cast<std::size_t>(level);
        const int factor = kLevelFactor[l];
        const Image level_left = factor == 1 ? left : downscale_area(left, factor);
        const Image level_right = factor == 1 ? right : downscale_area(right, factor);
        const SearchRange range = level_range(params, factor);
        const CandidateGrid grid =
            level == 0 ? full_grid(level_left.width, level_left.height, range)
                       : refine_grid(levels[l - 1], level_left.width, level_left.height, range);
        levels[l] = match_level(level_left, level_right, grid, params.levels[l], params.use_ca,
                                params.neighbours, count.level[l]);
    }
    return finish(std::move(levels), count);
}

Result full_search(const Image& left, const Image& right, const Params& params) {
    check_pair(left, right);
    validate(params, left.width, left.height);
    CostCount count;
    std::array<LevelMap, kLevels> levels;
    const CandidateGrid grid = full_grid(left.width, left.height, level_range(params, 1));
    levels[kLevels - 1] = match_level(left, right, grid, params.levels[kLevels - 1], params.use_ca,
                                      params.neighbours, count.level[kLevels - 1]);
    return finish(std::move(levels), count);
}

}  // namespace stereo::hierarchical
