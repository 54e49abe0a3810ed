// The speckle filter (stereo/speckle.hpp): one flood fill over the valid pixels, each region
// labelled once, so the cost is linear in the pixel count whatever the regions look like.
#include "stereo/speckle.hpp"

#include <cstddef>
#include <cstdint>
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
    const std::size_t pixels = map.fixed.size();
    const int max_step = params.range * fx::kSubpixelScale;
    const auto max_size = static_cast<std::size_t>(params.max_size);
    // Reused by the calling thread from one frame to the next (no allocation in a sequence).
    thread_local std::vector<std::uint8_t> visited;
    thread_local std::vector<std::size_t> members;  // the current region's first max_size + 1
    struct Pixel {
        std::size_t index;
        int x;
    };
    thread_local std::vector<Pixel> stack;
    visited.assign(pixels, 0);
    int removed = 0;
    for (std::size_t seed = 0; seed < pixels; ++seed) {
        if (visited[seed] != 0 || !map.valid(seed)) {
            continue;
        }
        members.clear();
        stack.assign(1, {seed, static_cast<int>(seed % static_cast<std::size_t>(width))});
        visited[seed] = 1;
        std::size_t size = 0;
        while (!stack.empty()) {
            const Pixel p = stack.back();
            stack.pop_back();
            if (size++ <= max_size) {  // a larger region is kept whole: no need to list it
                members.push_back(p.index);
            }
            const int disparity = map.fixed[p.index];
            const auto visit = [&](std::size_t q, int x) {
                if (visited[q] == 0 && map.valid(q) &&
                    std::abs(map.fixed[q] - disparity) <= max_step) {
                    visited[q] = 1;
                    stack.push_back({q, x});
                }
            };
            if (p.x + 1 < width) {
                visit(p.index + 1, p.x + 1);
            }
            if (p.x > 0) {
                visit(p.index - 1, p.x - 1);
            }
            if (p.index + width < pixels) {
                visit(p.index + width, p.x);
            }
            if (p.index >= static_cast<std::size_t>(width)) {
                visit(p.index - width, p.x);
            }
        }
        if (size <= max_size) {
            for (const std::size_t p : members) {
                map.reason[p] = fx::kReasonSpeckle;
                map.fixed[p] = 0;
            }
            removed += static_cast<int>(size);
        }
    }
    return removed;
}

}  // namespace stereo::speckle
