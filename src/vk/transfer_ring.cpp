#include "vk/transfer_ring.h"

#include <algorithm>
#include <cstring>

#include "core/check.h"
#include "vk/allocator.h"
#include "vk/recorder.h"

namespace fovrt {

TransferRing::TransferRing(CommandRecorder& recorder, Buffer& ring) : recorder_(recorder), ring_(ring) {
    FOVRT_CHECK(ring_.mapped() != nullptr && ring_.size() > 0);
}

size_t TransferRing::Room() {
    if (offset_ >= ring_.size()) Flush();
    return ring_.size() - offset_;
}

void TransferRing::Upload(const void* data, size_t bytes, Buffer& dst) {
    const char* from = static_cast<const char*>(data);
    for (size_t done = 0; done < bytes;) {
        const size_t piece = std::min(bytes - done, Room());
        offset_ = recorder_.Upload(from + done, piece, ring_, offset_, dst, done);
        done += piece;
    }
}

void TransferRing::Download(const Buffer& src, size_t bytes, void* out, size_t srcOffset) {
    char* to = static_cast<char*>(out);
    for (size_t done = 0; done < bytes;) {
        const size_t piece = std::min(bytes - done, Room());
        landings_.push_back({offset_, piece, to + done});
        offset_ = recorder_.Download(src, piece, ring_, offset_, srcOffset + done);
        done += piece;
    }
}

void TransferRing::Flush() {
    if (!landings_.empty()) recorder_.Barrier();  // the copies' writes visible to the host
    recorder_.Flush();
    ++flushes_;
    Land();
    offset_ = 0;
}

void TransferRing::Submit() {
    if (!landings_.empty()) recorder_.Barrier();
    recorder_.Submit();
    Land();
    offset_ = 0;
}

void TransferRing::Land() {
    const char* mapped = static_cast<const char*>(ring_.mapped());
    for (const Landing& l : landings_) std::memcpy(l.out, mapped + l.offset, l.bytes);
    landings_.clear();
}

}  // namespace fovrt
