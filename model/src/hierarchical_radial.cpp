// The radial model of the vertical field (stereo/hierarchical.hpp, docs/hierarchical.md "Lens
// distortion"): a plane plus the first-order row change of a radial lens distortion shared by
// both images, fitted robustly to the full level's votes.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <utility>

#include "stereo/hierarchical.hpp"
#include "stereo/hierarchical_plane.hpp"

namespace stereo::hierarchical {
namespace {

// One vote: a valid winner (d, v) seen from the right image's column xr of its row y.
struct Vote {
    int xr, y, d, v;
};

std::vector<Vote> votes_of(const LevelMap& level) {
    std::vector<Vote> votes;
    for (int y = 0; y < level.height; ++y) {
        for (int x = 0; x < level.width; ++x) {
            const std::size_t p = level.index(x, y);
            const int column = right_column(level, x, y);
            if (level.valid[p] != 0 && column >= 0 && column < level.width) {
                votes.push_back({column, y, level.disparity[p], level.vertical[p]});
            }
        }
    }
    return votes;
}

// The least-squares coefficients (a, b, c, k) over the inliers; std::nullopt when the normal
// equations are singular. The lens term is scaled by 1 / (cx cy D) while solving, so that the
// four columns have comparable sizes.
std::optional<RadialModel> solve_radial(const std::vector<Vote>& votes,
                                        const std::vector<std::uint8_t>& inliers,
                                        const RadialModel& frame) {
    int d_max = 1;
    for (const Vote& vote : votes) {
        d_max = std::max(d_max, vote.d);
    }
    const double scale = 1.0 / (std::max(frame.cx, 1.0) * std::max(frame.cy, 1.0) * d_max);
    std::array<std::array<double, 5>, 4> m{};  // [normal matrix | right-hand side]
    std::size_t count = 0;
    for (std::size_t i = 0; i < votes.size(); ++i) {
        if (inliers[i] == 0) {
            continue;
        }
        ++count;
        const Vote& vote = votes[i];
        const double x = vote.xr - frame.cx;
        const double y = vote.y - frame.cy;
        const std::array<double, 4> row = {1.0, x, y, scale * y * vote.d * (2 * x + vote.d)};
        for (std::size_t r = 0; r < 4; ++r) {
            for (std::size_t c = 0; c < 4; ++c) {
                m[r][c] += row[r] * row[c];
            }
            m[r][4] += row[r] * vote.v;
        }
    }
    if (count < 4) {
        return std::nullopt;
    }
    // Gaussian elimination with partial pivoting.
    for (std::size_t col = 0; col < 4; ++col) {
        std::size_t pivot = col;
        for (std::size_t r = col + 1; r < 4; ++r) {
            if (std::abs(m[r][col]) > std::abs(m[pivot][col])) {
                pivot = r;
            }
        }
        if (std::abs(m[pivot][col]) <= 1e-9 * std::max(1.0, std::abs(m[col][col])) ||
            m[pivot][col] == 0.0) {
            return std::nullopt;
        }
        std::swap(m[col], m[pivot]);
        for (std::size_t r = col + 1; r < 4; ++r) {
            const double f = m[r][col] / m[col][col];
            for (std::size_t c = col; c < 5; ++c) {
                m[r][c] -= f * m[col][c];
            }
        }
    }
    std::array<double, 4> solution{};
    for (std::size_t r = 4; r-- > 0;) {
        double sum = m[r][4];
        for (std::size_t c = r + 1; c < 4; ++c) {
            sum -= m[r][c] * solution[c];
        }
        solution[r] = sum / m[r][r];
    }
    RadialModel model = frame;
    model.a = solution[0];
    model.b = solution[1];
    model.c = solution[2];
    model.k = solution[3] * scale;
    return model;
}

// round(plane(x, y)), halves up, as plane_field (without its clamp).
std::int64_t plane_offset(const Plane& plane, int x, int y) {
    const std::int64_t value = plane.a + plane.b * x + plane.c * y + kPlaneOne / 2;
    return value >= 0 ? value / kPlaneOne : -((-value + kPlaneOne - 1) / kPlaneOne);
}

std::vector<std::uint8_t> inliers_of(const std::vector<Vote>& votes, const RadialModel& model,
                                     double tolerance) {
    std::vector<std::uint8_t> inliers(votes.size(), 0);
    for (std::size_t i = 0; i < votes.size(); ++i) {
        const Vote& vote = votes[i];
        inliers[i] = std::abs(vote.v - model(vote.xr, vote.y, vote.d)) <= tolerance ? 1 : 0;
    }
    return inliers;
}

}  // namespace

std::optional<RadialModel> vertical_radial(const LevelMap& level, const Plane& plane,
                                           double min_gain, double tolerance, int max_iterations) {
    // The plane, in the centred coordinates, starts the radial fits.
    const double one = static_cast<double>(kPlaneOne);
    RadialModel model;
    model.cx = (level.width - 1) / 2.0;
    model.cy = (level.height - 1) / 2.0;
    model.b = static_cast<double>(plane.b) / one;
    model.c = static_cast<double>(plane.c) / one;
    model.a = static_cast<double>(plane.a) / one + model.b * model.cx + model.c * model.cy;
    const std::vector<Vote> votes = votes_of(level);
    double current_tolerance = static_cast<double>(kFirstFitTolerance) / one;
    std::vector<std::uint8_t> previous;
    for (int iteration = 0; iteration < max_iterations; ++iteration) {
        std::vector<std::uint8_t> inliers = inliers_of(votes, model, current_tolerance);
        if (inliers == previous) {
            break;  // the same inliers as the last fit: the same model
        }
        const std::optional<RadialModel> solved = solve_radial(votes, inliers, model);
        if (!solved) {
            break;  // too few or degenerate inliers: keep the last model
        }
        previous = std::move(inliers);
        model = *solved;
        current_tolerance = tolerance;
    }
    // Kept only if it explains clearly more votes than the plane: rounded as each field rounds
    // (halves up), the offset of a vote is its own.
    std::int64_t plane_exact = 0;
    std::int64_t radial_exact = 0;
    for (const Vote& vote : votes) {
        plane_exact += plane_offset(plane, vote.xr, vote.y) == vote.v ? 1 : 0;
        radial_exact += std::floor(model(vote.xr, vote.y, vote.d) + 0.5) == vote.v ? 1 : 0;
    }
    if (static_cast<double>(radial_exact) < min_gain * static_cast<double>(plane_exact) ||
        radial_exact == 0) {
        return std::nullopt;
    }
    return model;
}

std::vector<std::int16_t> right_disparities(const LevelMap& level) {
    const int width = level.width;
    std::vector<std::int16_t> disparity(static_cast<std::size_t>(width) * level.height, -1);
    for (int y = 0; y < level.height; ++y) {
        for (int x = 0; x < width; ++x) {
            const std::size_t p = level.index(x, y);
            const int column = right_column(level, x, y);
            if (level.valid[p] != 0 && column >= 0 && column < width) {
                std::int16_t& d = disparity[static_cast<std::size_t>(y) * width + column];
                d = std::max(d, level.disparity[p]);
            }
        }
    }
    std::vector<int> before(static_cast<std::size_t>(width));
    for (int y = 0; y < level.height; ++y) {
        std::int16_t* row = disparity.data() + static_cast<std::size_t>(y) * width;
        int last = -1;
        for (int x = 0; x < width; ++x) {
            last = row[x] >= 0 ? x : last;
            before[static_cast<std::size_t>(x)] = last;
        }
        if (last < 0) {
            std::fill(row, row + width, std::int16_t{0});
            continue;
        }
        // From the right, so that every value read is still a vote's.
        int next = -1;
        for (int x = width - 1; x >= 0; --x) {
            const int b = before[static_cast<std::size_t>(x)];
            next = b == x ? x : next;
            if (b == x) {
                continue;
            }
            const int nearest = b < 0 ? next : next < 0 ? b : (x - b <= next - x ? b : next);
            row[x] = row[nearest];
        }
    }
    return disparity;
}

std::vector<std::int8_t> radial_field(const RadialModel& model, const LevelMap& level, int v_min,
                                      int v_max) {
    const std::vector<std::int16_t> disparity = right_disparities(level);
    std::vector<std::int8_t> field(disparity.size());
    for (int y = 0; y < level.height; ++y) {
        for (int x = 0; x < level.width; ++x) {
            const std::size_t p = static_cast<std::size_t>(y) * level.width + x;
            const double v = std::floor(model(x, y, disparity[p]) + 0.5);
            field[p] = static_cast<std::int8_t>(
                std::clamp(v, static_cast<double>(v_min), static_cast<double>(v_max)));
        }
    }
    return field;
}

}  // namespace stereo::hierarchical
