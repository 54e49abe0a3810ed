// The plane scheduler (stereo/search.hpp): the one loop every matcher of the model runs.
#include "stereo/search.hpp"

#include <algorithm>
#include <array>
#include <stdexcept>

#include "stereo/constants.hpp"

namespace stereo {

CandidateGrid CandidateGrid::horizontal(int width, int height, int ndisp, int min_disp) {
    const auto base = static_cast<std::int16_t>(min_disp);
    return {width, height, ndisp, 1, {base}, {0}, {base}, {0}};
}

bool window_valid(int x, int y, int d, int v, int width, int height, int reach) {
    return x >= reach && x < width - reach && y >= reach && y < height - reach && x - d >= reach &&
           y + v >= reach && y + v < height - reach;
}

void cost_plane(const CostFunction& cost, const PlanarImage& left, const PlanarImage& right,
                const CandidateGrid& grid, int i, int j, CostValue* out) {
    const int width = left.width;
    const int height = left.height;
    constexpr auto outside = static_cast<CostValue>(fx::kCostOutside);
    for (int y = 0; y < height; ++y) {
        CostValue* row = out + static_cast<std::size_t>(y) * width;
        // Runs of pixels that share a displacement are one call of the cost function (a uniform
        // grid makes each row one run).
        int x = 0;
        while (x < width) {
            const std::size_t g = grid.at(static_cast<std::size_t>(y) * width + x);
            const int d = grid.base_d[g] + i;
            const int v = grid.base_v[g] + j;
            int end = x + 1;
            if (grid.uniform()) {
                end = width;
            } else {
                while (end < width) {
                    const std::size_t h = static_cast<std::size_t>(y) * width + end;
                    if (grid.base_d[h] != grid.base_d[g] || grid.base_v[h] != grid.base_v[g]) {
                        break;
                    }
                    ++end;
                }
            }
            const int yr = y + v;
            // Left pixels x..end-1 see right pixels x - d ..; those inside are a contiguous run.
            const int first = std::clamp(d, x, end);
            const int last = std::clamp(width + d, x, end);  // exclusive: x - d < width
            if (yr < 0 || yr >= height || first >= last) {
                std::fill(row + x, row + end, outside);
            } else {
                std::fill(row + x, row + first, outside);
                cost.row(left, right, y, yr, first, last - first, d, row + first);
                std::fill(row + last, row + end, outside);
            }
            x = end;
        }
    }
}

Dsi cost_volume(const CostFunction& cost, const Image& left, const Image& right, int ndisp,
                int min_disp) {
    const PlanarImage left_planes = cost.prepare(left);
    const PlanarImage right_planes = cost.prepare(right);
    const auto grid = CandidateGrid::horizontal(left.width, left.height, ndisp, min_disp);
    Dsi dsi(left.width, left.height, ndisp);
    for (int d = 0; d < ndisp; ++d) {
        cost_plane(cost, left_planes, right_planes, grid, d, 0, dsi.plane(d).data());
    }
    return dsi;
}

std::int64_t search(const PlanarImage& left, const PlanarImage& right, const CandidateGrid& grid,
                    const SearchStages& stages) {
    if (grid.width != left.width || grid.height != left.height || grid.cols < 1 || grid.rows < 1) {
        throw std::invalid_argument("candidate grid does not fit the images");
    }
    for (std::size_t r = 1; r < stages.refiners.size(); ++r) {
        if (stages.refiners[r]->reads_neighbour_planes()) {
            throw std::invalid_argument("only the first refiner may read neighbouring planes");
        }
    }
    const std::size_t plane_size = static_cast<std::size_t>(grid.width) * grid.height;
    const int cols = grid.cols;
    const int total = cols * grid.rows;
    const bool neighbours =
        !stages.refiners.empty() && stages.refiners.front()->reads_neighbour_planes();
    const bool vertical = neighbours && stages.neighbours == CaNeighbours::horizontal_and_vertical;
    // Aggregated planes k - ahead .. k + ahead live in a ring: plane k in slot k % ring size.
    const int ahead = !neighbours ? 0 : (vertical ? cols : 1);
    std::vector<std::vector<CostValue>> ring(static_cast<std::size_t>(2 * ahead + 1),
                                             std::vector<CostValue>(plane_size));
    std::vector<CostValue> cost(plane_size);
    std::array<std::vector<CostValue>, 2> refined;  // ping-pong through the refiner chain
    for (auto& plane : refined) {
        plane.resize(stages.refiners.empty() ? 0 : plane_size);
    }
    const auto slot = [&](int k) { return ring[static_cast<std::size_t>(k) % ring.size()].data(); };
    const auto plane_at = [&](int i, int j) -> const CostValue* {
        return i < 0 || i >= cols || j < 0 || j >= grid.rows ? nullptr : slot(j * cols + i);
    };

    std::int64_t cells = 0;
    int computed = 0;
    for (int k = 0; k < total; ++k) {
        for (; computed <= std::min(total - 1, k + ahead); ++computed) {
            cost_plane(stages.cost, left, right, grid, computed % cols, computed / cols,
                       cost.data());
            stages.aggregator.plane(cost.data(), slot(computed));
            cells += static_cast<std::int64_t>(plane_size);
        }
        const int i = k % cols;
        const int j = k / cols;
        const CostValue* final_plane = slot(k);
        for (std::size_t r = 0; r < stages.refiners.size(); ++r) {
            std::array<NeighbourPlanes, 2> axes{};
            std::size_t count = 0;
            if (r == 0 && neighbours) {
                axes[count++] = {plane_at(i - 1, j), plane_at(i + 1, j)};
                if (vertical) {
                    axes[count++] = {plane_at(i, j - 1), plane_at(i, j + 1)};
                }
            }
            CostValue* out = refined[r % 2].data();
            stages.refiners[r]->plane(final_plane, std::span(axes.data(), count), out);
            final_plane = out;
        }
        stages.selector.update(final_plane, i, j);
    }
    return cells;
}

}  // namespace stereo
