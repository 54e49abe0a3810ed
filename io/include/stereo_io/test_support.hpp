// Helpers shared by tests/ and testbench/ (CMake target stereo_test_support, header-only):
// seeded random images and pairs, constant extreme pairs, counts of a map's valid pixels. The seed
// is printed and replayable with STEREO_SEED. The data folder is io::data_dir()
// (stereo_io/data_dir.hpp), not a helper of its own.
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "stereo/image.hpp"
#include "stereo_io/io.hpp"

namespace stereo::test {

// The seed comes from STEREO_SEED when set, so a failing random test can be replayed.
inline std::uint32_t test_seed() {
    static const std::uint32_t seed = [] {
        const char* text = std::getenv("STEREO_SEED");
        const std::uint32_t value =
            text != nullptr ? static_cast<std::uint32_t>(std::strtoul(text, nullptr, 10))
                            : std::random_device{}();
        std::cout << "[seed] STEREO_SEED=" << value << '\n';
        return value;
    }();
    return seed;
}

// A generator seeded with test_seed() + salt: one test's or one case's own replayable stream.
inline std::mt19937 seeded_rng(int salt = 0) {
    return std::mt19937(test_seed() + static_cast<std::uint32_t>(salt));
}

inline Image random_image(int width, int height, int channels, std::mt19937& rng) {
    Image image(width, height, channels);
    std::uniform_int_distribution<int> value(0, 255);
    for (auto& p : image.pixels) {
        p = static_cast<std::uint8_t>(value(rng));
    }
    return image;
}

// A right image with right(x) = left(x + shift) plus noise (true disparity `shift`), so that
// matching has a true answer and the CA rules see realistic, not only random, cost volumes.
inline Image shifted_copy(const Image& left, int shift, int noise, std::mt19937& rng) {
    Image right(left.width, left.height, left.channels);
    std::uniform_int_distribution<int> jitter(-noise, noise);
    for (int y = 0; y < left.height; ++y) {
        for (int x = 0; x < left.width; ++x) {
            const int source = std::clamp(x + shift, 0, left.width - 1);
            for (int c = 0; c < left.channels; ++c) {
                const int v = left.at(source, y, c) + jitter(rng);
                right.at(x, y, c) = static_cast<std::uint8_t>(std::clamp(v, 0, 255));
            }
        }
    }
    return right;
}

// A random left image and shifted_copy(left, shift, noise): a pair with true disparity `shift`.
// Draws from `rng` in that order, so it replaces the two calls one for one.
inline io::ImagePair shifted_pair(int width, int height, int channels, int shift, int noise,
                                  std::mt19937& rng) {
    Image left = random_image(width, height, channels, rng);
    Image right = shifted_copy(left, shift, noise, rng);
    return {std::move(left), std::move(right)};
}

// shifted_pair drawn from its own generator, seeded_rng(salt): for a test that draws nothing else.
inline io::ImagePair seeded_shifted_pair(int width, int height, int channels, int shift, int noise,
                                         int salt = 0) {
    auto rng = seeded_rng(salt);
    return shifted_pair(width, height, channels, shift, noise, rng);
}

// Constant images at the extremes of the pixel range: black and white against themselves and
// each other, so that every cost is 0 or its maximum.
struct ConstantPair {
    int left_value;
    int right_value;
    Image left;
    Image right;
};

// Colours of the six faces of the RGB cube in steps of 15 (every hue sector, every tie of the
// maximum, both sides of the lightness fold, greys), in raster order over a width x height RGB
// image, repeating; and the same image reversed, so that each pixel meets other colours.
inline std::pair<Image, Image> rgb_cube_pair(int width, int height) {
    Image left(width, height, 3);
    for (int k = 0; k < width * height; ++k) {
        const int u = 15 * (k % 18);
        const int v = 15 * ((k / 18) % 18);
        const int face = (k / (18 * 18)) % 6;
        const int rgb[6][3] = {{u, v, 0},   {u, 0, v},   {0, u, v},
                               {u, v, 255}, {u, 255, v}, {255, u, v}};
        for (int c = 0; c < 3; ++c) {
            left.pixels[static_cast<std::size_t>(k) * 3 + static_cast<std::size_t>(c)] =
                static_cast<std::uint8_t>(rgb[face][c]);
        }
    }
    Image right = left;
    std::reverse(right.pixels.begin(), right.pixels.end());
    return {std::move(left), std::move(right)};
}

inline std::vector<ConstantPair> constant_pairs(int width, int height, int channels) {
    std::vector<ConstantPair> pairs;
    for (const auto& [l, r] :
         {std::pair{0, 0}, std::pair{255, 255}, std::pair{0, 255}, std::pair{255, 0}}) {
        ConstantPair pair{l, r, Image(width, height, channels), Image(width, height, channels)};
        std::fill(pair.left.pixels.begin(), pair.left.pixels.end(), static_cast<std::uint8_t>(l));
        std::fill(pair.right.pixels.begin(), pair.right.pixels.end(), static_cast<std::uint8_t>(r));
        pairs.push_back(std::move(pair));
    }
    return pairs;
}

// A map's valid pixels and, of those, the ones whose `values` (its disparity or vertical plane)
// hold `value`: how much of the output found a known displacement.
struct ValidCount {
    int valid = 0;
    int at_value = 0;
};
template <class T>
ValidCount count_valid_at(const std::vector<std::uint8_t>& valid, const std::vector<T>& values,
                          int value) {
    ValidCount count;
    for (std::size_t i = 0; i < valid.size(); ++i) {
        if (valid[i] != 0) {
            ++count.valid;
            count.at_value += values[i] == value ? 1 : 0;
        }
    }
    return count;
}

}  // namespace stereo::test
