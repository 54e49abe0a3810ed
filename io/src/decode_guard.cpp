#include "decode_guard.hpp"

#include <limits>
#include <mutex>

#include <opencv2/core.hpp>

namespace stereo::io::detail {
namespace {

// The budget of this thread (0: none) and the first matrix refused under it.
thread_local std::int64_t t_budget = 0;
thread_local std::optional<std::pair<std::int64_t, std::int64_t>> t_refused;

// OpenCV's default allocator with one check in front: with a budget open on the calling thread, a
// matrix of more elements is refused with cv::Error::StsNoMem before any memory is reserved.
// cv::Mat::create falls back to the default allocator when a matrix's own allocator throws, so
// the check has to be the default allocator itself (a per-matrix allocator would be bypassed).
// Everything else, including the release of what it allocated (UMatData::currAllocator is the
// inner allocator), is the inner allocator's.
class GuardedAllocator final : public cv::MatAllocator {
  public:
    explicit GuardedAllocator(cv::MatAllocator* inner) : inner_(inner) {}

    cv::UMatData* allocate(int dims, const int* sizes, int type, void* data, size_t* step,
                           cv::AccessFlag flags, cv::UMatUsageFlags usage) const override {
        if (t_budget > 0 && data == nullptr) {
            check(dims, sizes);
        }
        return inner_->allocate(dims, sizes, type, data, step, flags, usage);
    }
    bool allocate(cv::UMatData* data, cv::AccessFlag flags,
                  cv::UMatUsageFlags usage) const override {
        return inner_->allocate(data, flags, usage);
    }
    void deallocate(cv::UMatData* data) const override { inner_->deallocate(data); }
    void map(cv::UMatData* data, cv::AccessFlag flags) const override { inner_->map(data, flags); }
    void unmap(cv::UMatData* data) const override { inner_->unmap(data); }
    cv::BufferPoolController* getBufferPoolController(const char* id) const override {
        return inner_->getBufferPoolController(id);
    }

  private:
    static void check(int dims, const int* sizes) {
        constexpr std::int64_t kHuge = std::numeric_limits<std::int64_t>::max();
        std::int64_t elements = 1;
        for (int i = 0; i < dims; ++i) {
            const std::int64_t size = sizes[i];
            elements = size > 0 && elements > kHuge / size ? kHuge : elements * size;
        }
        if (elements <= t_budget) {
            return;
        }
        if (!t_refused) {
            t_refused = dims == 2 ? std::make_pair(std::int64_t{sizes[1]}, std::int64_t{sizes[0]})
                                  : std::make_pair(elements, std::int64_t{1});
        }
        CV_Error(cv::Error::StsNoMem, "image above the pixel limit");
    }

    cv::MatAllocator* inner_;
};

void install_guard() {
    static std::mutex mutex;
    static GuardedAllocator* installed = nullptr;
    const std::lock_guard<std::mutex> lock(mutex);
    if (installed != nullptr && cv::Mat::getDefaultAllocator() == installed) {
        return;
    }
    // Never freed: matrices allocated through it may outlive any scope.
    installed = new GuardedAllocator(cv::Mat::getDefaultAllocator());
    cv::Mat::setDefaultAllocator(installed);
}

// Installed while the program starts, before any thread could be allocating: a later install
// (only when something replaced the default allocator since) swaps a pointer others may read.
[[maybe_unused]] const bool g_installed_at_start = (install_guard(), true);

}  // namespace

PixelBudget::PixelBudget(std::int64_t pixels) : outer_pixels_(t_budget) {
    install_guard();
    t_budget = pixels < 1 ? 1 : pixels;
    if (outer_pixels_ == 0) {
        t_refused.reset();
    }
}

PixelBudget::~PixelBudget() {
    t_budget = outer_pixels_;
}

std::optional<std::pair<std::int64_t, std::int64_t>> PixelBudget::refused() const {
    return t_refused;
}

}  // namespace stereo::io::detail
