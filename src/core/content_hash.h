// ContentHash: 64-bit FNV-1a, the one hash fovrt uses for keys and checksums (reference-cache
// keys, scene fingerprints, experiment fingerprints, the checksums that seal cache entries and
// shard rows). Stable across runs, machines and compilers (unlike std::hash). Not cryptographic:
// it detects accidental corruption and mixed-up files, not an adversary.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <type_traits>

#include <fmt/format.h>

namespace fovrt {

class ContentHash {
public:
    void Bytes(const void* data, size_t size) {
        const auto* p = static_cast<const unsigned char*>(data);
        for (size_t i = 0; i < size; ++i) {
            hash_ ^= p[i];
            hash_ *= 1099511628211ull;
        }
    }
    template <typename T>
    void Value(const T& v) {
        static_assert(std::is_trivially_copyable_v<T>);
        Bytes(&v, sizeof(T));
    }
    // Length-prefixed, so ("ab", "c") and ("a", "bc") differ.
    void String(std::string_view s) {
        Value(s.size());
        Bytes(s.data(), s.size());
    }
    uint64_t Digest() const { return hash_; }
    std::string Hex() const { return fmt::format("{:016x}", hash_); }

private:
    uint64_t hash_ = 1469598103934665603ull;
};

// The hash of `bytes` alone (no length prefix), as 16 hex digits.
inline std::string HashHex(std::string_view bytes) {
    ContentHash h;
    h.Bytes(bytes.data(), bytes.size());
    return h.Hex();
}

}  // namespace fovrt
