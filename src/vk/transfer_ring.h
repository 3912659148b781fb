// TransferRing: a piece of work's host data streamed to device buffers and back through one
// host-visible buffer of fixed size (an upload heap, as in Falcor's and NRD's integrations), so
// that staging costs the ring's size, not a frame's bytes. Transfers fill the ring in recording
// order; when the next one does not fit, the work recorded so far is flushed (submitted and
// waited on: CommandRecorder::Flush) and the ring starts over. A transfer larger than the ring
// goes in pieces. When everything fits, the work is one submit, as without a ring.
//
// Ordering is the caller's: the recorder's barriers order a download behind the commands that
// wrote its source, as they would with one submit (a flush only adds waits).
#pragma once

#include <cstddef>
#include <vector>

namespace fovrt {

class Buffer;
class CommandRecorder;

class TransferRing {
public:
    // `ring`: host-visible (MemoryUsage::Staging), used from offset 0 to its size.
    TransferRing(CommandRecorder& recorder, Buffer& ring);
    TransferRing(const TransferRing&) = delete;
    TransferRing& operator=(const TransferRing&) = delete;

    // Copies `bytes` of host memory into `dst` (from offset 0).
    void Upload(const void* data, size_t bytes, Buffer& dst);
    // Copies `bytes` of `src` from `srcOffset` into host memory at `out`, which holds them once
    // Submit() has returned.
    void Download(const Buffer& src, size_t bytes, void* out, size_t srcOffset = 0);
    // Submits the rest and waits; every download has landed. Call instead of the recorder's Submit().
    void Submit();

    // Times the work was submitted before Submit(): 0 when everything fit the ring at once.
    int flushes() const { return flushes_; }

private:
    // The room left from the current offset (offsets are 16-byte aligned); flushes when it is
    // none, so the result is never 0.
    size_t Room();
    void Flush();
    void Land();  // copies the downloads recorded since the last submit out of the ring

    struct Landing {
        size_t offset, bytes;
        void* out;
    };
    CommandRecorder& recorder_;
    Buffer& ring_;
    size_t offset_ = 0;
    int flushes_ = 0;
    std::vector<Landing> landings_;
};

}  // namespace fovrt
