#include "stereo_robot/bands.hpp"

#include <algorithm>
#include <exception>
#include <stdexcept>
#include <thread>
#include <vector>

namespace stereo::robot {
namespace {

struct Band {
    int first = 0;  // the band's own rows [first, last)
    int last = 0;
    int from = 0;  // rows matched, halo included: [from, to)
    int to = 0;
};

std::vector<Band> make_bands(int height, int threads, int halo) {
    std::vector<Band> bands;
    const int n = std::max(1, std::min(threads, height / std::max(1, 2 * halo)));
    for (int i = 0; i < n; ++i) {
        Band b;
        b.first = i * height / n;
        b.last = (i + 1) * height / n;
        b.from = std::max(0, b.first - halo);
        b.to = std::min(height, b.last + halo);
        bands.push_back(b);
    }
    return bands;
}

// Runs `match` on every band (one thread each, the first on the calling thread) and copies the
// band's own rows of each result with `copy(result, band)`.
template <typename Result, typename Match, typename Copy>
void run_bands(const Image& left, const Image& right, int threads, int halo, Match match,
               Copy copy) {
    if (left.width != right.width || left.height != right.height) {
        throw std::invalid_argument("band matching: the two images differ in size");
    }
    const auto bands = make_bands(left.height, threads, halo);
    std::vector<Result> results(bands.size());
    std::vector<std::exception_ptr> errors(bands.size());
    const auto work = [&](std::size_t i) {
        try {
            const Band& b = bands[i];
            results[i] = match(rows_of(left, b.from, b.to), rows_of(right, b.from, b.to));
        } catch (...) {
            errors[i] = std::current_exception();
        }
    };
    {
        std::vector<std::jthread> pool;
        for (std::size_t i = 1; i < bands.size(); ++i) {
            pool.emplace_back(work, i);
        }
        work(0);
    }  // joined here
    for (const auto& error : errors) {
        if (error) {
            std::rethrow_exception(error);
        }
    }
    for (std::size_t i = 0; i < bands.size(); ++i) {
        copy(results[i], bands[i]);
    }
}

}  // namespace

Image rows_of(const Image& image, int first, int last) {
    if (first < 0 || last > image.height || first >= last) {
        throw std::invalid_argument("rows_of: empty or out-of-range rows");
    }
    Image out(image.width, last - first, image.channels);
    const std::size_t row = static_cast<std::size_t>(image.width) * image.channels;
    std::copy(image.pixels.begin() + static_cast<std::ptrdiff_t>(first * row),
              image.pixels.begin() + static_cast<std::ptrdiff_t>(last * row), out.pixels.begin());
    return out;
}

int edge_frontend_reach(const MatchParams& params, const edge_frontend::EdgeParams& edges) {
    return edges.log_window / 2 + 2 + params.window / 2;
}

int default_threads() {
    return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

DisparityMap edge_match_bands(const Image& left, const Image& right, const MatchParams& params,
                              const edge_frontend::EdgeParams& edges, int threads) {
    if (threads <= 1) {
        return edge_frontend::match(left, right, params, edges);
    }
    // Validate once on the whole image, so that the bands (shorter) never throw on their own.
    edge_frontend::validate(edges);
    DisparityMap out(left.width, left.height);
    const int halo = edge_frontend_reach(params, edges) + 2;  // +2: margin, costs two rows
    run_bands<DisparityMap>(
        left, right, threads, halo,
        [&](const Image& l, const Image& r) { return edge_frontend::match(l, r, params, edges); },
        [&](const DisparityMap& band, const Band& b) {
            for (int y = b.first; y < b.last; ++y) {
                const std::size_t src = band.index(0, y - b.from);
                const std::size_t dst = out.index(0, y);
                std::copy_n(band.disparity.begin() + static_cast<std::ptrdiff_t>(src), out.width,
                            out.disparity.begin() + static_cast<std::ptrdiff_t>(dst));
                std::copy_n(band.valid.begin() + static_cast<std::ptrdiff_t>(src), out.width,
                            out.valid.begin() + static_cast<std::ptrdiff_t>(dst));
            }
        });
    return out;
}

slam::SparseDisparity sparse_disparity_bands(const Image& left, const Image& right,
                                             const slam::FrontendParams& params, int threads) {
    // The fast engine under slam::sparse_disparity splits the rows itself (tiles with exact
    // seams, docs/cpu-engine.md) on its worker threads; no bands of whole images here.
    return slam::sparse_disparity(left, right, params, nullptr, std::max(threads, 1));
}

}  // namespace stereo::robot
