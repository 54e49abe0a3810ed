// The messages between `stereo cosim` and a co-simulation runner built on demand
// (sim/on_demand.cpp builds it; sim/cosim_runner_main.cpp is its main): one binary request on
// the runner's standard input, one reply on its standard output, until the input ends. Both ends
// are built from this header on the same machine, so integers travel in the host's byte order;
// the cache key (on_demand.cpp) includes this file, so a changed protocol is a new runner.
//
// Requests (tag byte, then fields):
//   'P' PortValues                         set the cfg_* ports      -> 'K'
//   'R'                                    two reset cycles          -> 'K'
//   'S' beats, expected, traffic, limit    stream                    -> 'K' StreamResult
//   'T' path                               FST trace from now on     -> 'K'
//   'W' pixels                             watch these pixels' stage outputs in the next
//                                          streams (probe runners only) -> 'K'
//   'G'                                    what the watched pixels got -> 'K' StageProbes
// A reply 'E' carries an error message instead.
#pragma once

#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "stereo_top_sim.hpp"

namespace stereo::sim::protocol {

inline constexpr int kVersion = 1;

enum Tag : char {
    kParams = 'P',
    kReset = 'R',
    kStream = 'S',
    kTrace = 'T',
    kWatch = 'W',
    kGetProbes = 'G',
    kOk = 'K',
    kError = 'E',
};

using stereo::sim::PortValues;

// Whole-message I/O on a file descriptor; throws std::runtime_error when the other end is gone.
class Channel {
  public:
    Channel(int read_fd, int write_fd) : read_fd_(read_fd), write_fd_(write_fd) {}

    template <typename T>
    requires std::is_trivially_copyable_v<T>
    void put(const T& value) {
        const auto* bytes = reinterpret_cast<const char*>(&value);
        out_.insert(out_.end(), bytes, bytes + sizeof value);
    }
    void put_string(const std::string& text) {
        put(static_cast<std::uint32_t>(text.size()));
        out_.insert(out_.end(), text.begin(), text.end());
    }
    // Sends what put() gathered.
    void flush() {
        std::size_t done = 0;
        while (done < out_.size()) {
            const ssize_t n = ::write(write_fd_, out_.data() + done, out_.size() - done);
            if (n < 0 && errno == EINTR) {
                continue;
            }
            if (n <= 0) {
                out_.clear();
                throw std::runtime_error(std::string("co-simulation runner: write failed (") +
                                         std::strerror(errno) + ")");
            }
            done += static_cast<std::size_t>(n);
        }
        out_.clear();
    }

    // False at a clean end of input before the first byte; throws on a partial value.
    bool read_bytes(void* data, std::size_t size, bool end_allowed = false) {
        auto* bytes = static_cast<char*>(data);
        std::size_t done = 0;
        while (done < size) {
            const ssize_t n = ::read(read_fd_, bytes + done, size - done);
            if (n < 0 && errno == EINTR) {
                continue;
            }
            if (n == 0 && done == 0 && end_allowed) {
                return false;
            }
            if (n <= 0) {
                throw std::runtime_error(
                    "co-simulation runner: the other end closed the channel mid-message");
            }
            done += static_cast<std::size_t>(n);
        }
        return true;
    }
    template <typename T>
    requires std::is_trivially_copyable_v<T> T get() {
        T value;
        read_bytes(&value, sizeof value);
        return value;
    }
    std::string get_string(std::uint32_t limit = 1U << 20) {
        const auto size = get<std::uint32_t>();
        if (size > limit) {
            throw std::runtime_error("co-simulation runner: message of " + std::to_string(size) +
                                     " bytes is over the limit");
        }
        std::string text(size, '\0');
        read_bytes(text.data(), size);
        return text;
    }

  private:
    int read_fd_;
    int write_fd_;
    std::vector<char> out_;
};

inline void put_ports(Channel& channel, const PortValues& p) {
    channel.put(p.width);
    channel.put(p.height);
    channel.put(p.ndisp);
    channel.put(p.min_disp);
    for (const std::uint8_t byte : {p.use_ca, p.uniqueness_en, p.uniqueness, p.lr_en,
                                    p.lr_tolerance, p.subpixel_en, p.radius}) {
        channel.put(byte);
    }
    channel.put(static_cast<std::uint32_t>(p.kernel.size()));
    for (const std::int32_t tap : p.kernel) {
        channel.put(tap);
    }
}

inline PortValues get_ports(Channel& channel) {
    PortValues p;
    p.width = channel.get<std::uint16_t>();
    p.height = channel.get<std::uint16_t>();
    p.ndisp = channel.get<std::uint16_t>();
    p.min_disp = channel.get<std::uint16_t>();
    for (std::uint8_t* byte : {&p.use_ca, &p.uniqueness_en, &p.uniqueness, &p.lr_en,
                               &p.lr_tolerance, &p.subpixel_en, &p.radius}) {
        *byte = channel.get<std::uint8_t>();
    }
    const auto taps = channel.get<std::uint32_t>();
    if (taps > 64) {
        throw std::runtime_error("co-simulation runner: " + std::to_string(taps) +
                                 " kernel taps is over the limit");
    }
    p.kernel.resize(taps);
    for (std::int32_t& tap : p.kernel) {
        tap = channel.get<std::int32_t>();
    }
    return p;
}

inline void put_beats(Channel& channel, const std::vector<InputBeat>& beats) {
    channel.put(static_cast<std::uint64_t>(beats.size()));
    for (const InputBeat& beat : beats) {
        channel.put(beat.data);
        channel.put(static_cast<std::uint8_t>((beat.last ? 1 : 0) | (beat.user ? 2 : 0)));
    }
}

inline std::vector<InputBeat> get_beats(Channel& channel, std::uint64_t limit) {
    const auto count = channel.get<std::uint64_t>();
    if (count > limit) {
        throw std::runtime_error("co-simulation runner: " + std::to_string(count) +
                                 " beats is over the limit");
    }
    std::vector<InputBeat> beats(count);
    for (InputBeat& beat : beats) {
        beat.data = channel.get<std::uint64_t>();
        const auto flags = channel.get<std::uint8_t>();
        beat.last = (flags & 1) != 0;
        beat.user = (flags & 2) != 0;
    }
    return beats;
}

inline void put_result(Channel& channel, const StreamResult& result) {
    channel.put(static_cast<std::uint64_t>(result.outputs.size()));
    for (const OutputBeat& beat : result.outputs) {
        channel.put(beat.data);
        channel.put(static_cast<std::uint8_t>((beat.last ? 1 : 0) | (beat.user ? 2 : 0)));
    }
    channel.put(result.cycles);
    channel.put(result.input_beats);
    channel.put(static_cast<std::uint32_t>(result.status));
    channel.put(static_cast<std::uint8_t>(result.completed ? 1 : 0));
    channel.put_string(result.protocol_error);
}

inline StreamResult get_result(Channel& channel, std::uint64_t limit) {
    StreamResult result;
    const auto count = channel.get<std::uint64_t>();
    if (count > limit) {
        throw std::runtime_error("co-simulation runner: " + std::to_string(count) +
                                 " output beats, more than were asked for");
    }
    result.outputs.resize(count);
    for (OutputBeat& beat : result.outputs) {
        beat.data = channel.get<std::uint64_t>();
        const auto flags = channel.get<std::uint8_t>();
        beat.last = (flags & 1) != 0;
        beat.user = (flags & 2) != 0;
    }
    result.cycles = channel.get<std::uint64_t>();
    result.input_beats = channel.get<std::uint64_t>();
    result.status = channel.get<std::uint32_t>();
    result.completed = channel.get<std::uint8_t>() != 0;
    result.protocol_error = channel.get_string();
    return result;
}

// The stages a probe runner watches, in pipeline order (stereo_top's signals agg_*, rule1_* and
// wta_in_* / rule2_data: each label's value at the stage's output for the pixel).
inline constexpr const char* kProbedStages[] = {"aggregate", "ca_rule1", "ca_rule2"};
inline constexpr int kProbedStageCount = 3;

// What one watched pixel got from each probed stage: `seen` false when the stage's output never
// showed the pixel; values per label otherwise.
struct PixelProbe {
    int x = 0;
    int y = 0;
    std::array<bool, kProbedStageCount> seen{};
    std::array<std::vector<std::uint16_t>, kProbedStageCount> values;
};

inline void put_probes(Channel& channel, const std::vector<PixelProbe>& probes) {
    channel.put(static_cast<std::uint32_t>(probes.size()));
    for (const PixelProbe& probe : probes) {
        channel.put(static_cast<std::int32_t>(probe.x));
        channel.put(static_cast<std::int32_t>(probe.y));
        for (int stage = 0; stage < kProbedStageCount; ++stage) {
            channel.put(static_cast<std::uint8_t>(probe.seen[stage] ? 1 : 0));
            channel.put(static_cast<std::uint32_t>(probe.values[stage].size()));
            for (const std::uint16_t value : probe.values[stage]) {
                channel.put(value);
            }
        }
    }
}

inline std::vector<PixelProbe> get_probes(Channel& channel) {
    const auto count = channel.get<std::uint32_t>();
    if (count > 4096) {
        throw std::runtime_error("co-simulation runner: too many probed pixels");
    }
    std::vector<PixelProbe> probes(count);
    for (PixelProbe& probe : probes) {
        probe.x = channel.get<std::int32_t>();
        probe.y = channel.get<std::int32_t>();
        for (int stage = 0; stage < kProbedStageCount; ++stage) {
            probe.seen[stage] = channel.get<std::uint8_t>() != 0;
            const auto labels = channel.get<std::uint32_t>();
            if (labels > 4096) {
                throw std::runtime_error("co-simulation runner: too many probed labels");
            }
            probe.values[stage].resize(labels);
            for (std::uint16_t& value : probe.values[stage]) {
                value = channel.get<std::uint16_t>();
            }
        }
    }
    return probes;
}

}  // namespace stereo::sim::protocol
