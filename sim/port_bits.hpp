// Bit fields of Verilated ports of any width: integers up to 64 bits, VlWide<N> beyond.
#pragma once

#include <concepts>
#include <cstddef>
#include <cstdint>

namespace stereo::sim {

// Verilator exposes vectors wider than 64 bits as VlWide<N>: N 32-bit words, bit 0 in word 0.
template <typename Port>
concept WidePort = requires(const Port& port) {
    port.at(0);
};

template <typename Port>
bool get_bit(const Port& port, int position) {
    if constexpr (WidePort<Port>) {
        return ((port.at(static_cast<std::size_t>(position / 32)) >> (position % 32)) & 1U) != 0;
    } else {
        return ((static_cast<std::uint64_t>(port) >> position) & 1U) != 0;
    }
}

template <typename Port>
void set_bit(Port& port, int position, bool bit) {
    if constexpr (WidePort<Port>) {
        auto& word = port.at(static_cast<std::size_t>(position / 32));
        const std::uint32_t mask = 1U << (position % 32);
        word = bit ? (word | mask) : (word & ~mask);
    } else {
        const auto mask = static_cast<Port>(std::uint64_t{1} << position);
        port = bit ? static_cast<Port>(port | mask) : static_cast<Port>(port & ~mask);
    }
}

// Writes `bits` bits of `value` at [offset +: bits].
template <typename Port>
void put_bits(Port& port, int offset, int bits, std::uint64_t value) {
    for (int b = 0; b < bits; ++b) {
        set_bit(port, offset + b, ((value >> b) & 1U) != 0);
    }
}

// Reads [offset +: bits].
template <typename Port>
std::uint64_t get_bits(const Port& port, int offset, int bits) {
    std::uint64_t value = 0;
    for (int b = 0; b < bits; ++b) {
        value |= static_cast<std::uint64_t>(get_bit(port, offset + b)) << b;
    }
    return value;
}

}  // namespace stereo::sim
