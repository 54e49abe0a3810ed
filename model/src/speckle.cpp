// The speckle filter (stereo/speckle.hpp): one flood fill over the valid pixels, each region
// labelled once, so the cost is linear in the pixel count whatever the regions look like.
#include "stereo/speckle.hpp"

#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

namespace stereo::speckle {

void validate(const Params& params) {
    if (params.max_size < 0 || params.max_size > kMaxSize) {
        throw std::invalid_argument("speckle size " + std::to_string(params.max_size) +
                                    " is outside 0.." + std::to_string(kMaxSize) + " pixels");
    }
    if (params.range < 0 || params.range > kMaxRange) {
        throw std::invalid_argument("speckle range " + std::to_string(params.range) +
                                    " is outside 0.." + std::to_string(kMaxRange) + " pixels");
    }
}

int filter(ValidatedDisparity& map, const Params& params) {
    validate(params);
    if (!params.enabled()) {
        return 0;
    }
    const int width = map.width;
    const int height = map.height;
    const int max_step = params.range * fx::kSubpixelScale;
    // 0: not visited yet; otherwise the region's number + 1.
    std::vector<int> region_of(map.fixed.size(), 0);
    std::vector<std::size_t> members;  // the current region, in fill order
    std::vector<std::size_t> stack;
    int removed = 0;
    int next_region = 1;
    for (std::size_t seed = 0; seed < map.fixed.size(); ++seed) {
        if (!map.valid(seed) || region_of[seed] != 0) {
            continue;
        }
        members.clear();
        stack.assign(1, seed);
        region_of[seed] = next_region;
        while (!stack.empty()) {
            const std::size_t p = stack.back();
            stack.pop_back();
            members.push_back(p);
            const int x = static_cast<int>(p % width);
            const int y = static_cast<int>(p / width);
            const auto visit = [&](int nx, int ny) {
                if (nx < 0 || nx >= width || ny < 0 || ny >= height) {
                    return;
                }
                const std::size_t q = map.index(nx, ny);
                if (region_of[q] == 0 && map.valid(q) &&
                    std::abs(map.fixed[q] - map.fixed[p]) <= max_step) {
                    region_of[q] = next_region;
                    stack.push_back(q);
                }
            };
            visit(x + 1, y);
            visit(x - 1, y);
            visit(x, y + 1);
            visit(x, y - 1);
        }
        ++next_region;
        if (static_cast<int>(members.size()) <= params.max_size) {
            for (const std::size_t p : members) {
                map.reason[p] = fx::kReasonSpeckle;
                map.fixed[p] = 0;
            }
            removed += static_cast<int>(members.size());
        }
    }
    return removed;
}

}  // namespace stereo::speckle
