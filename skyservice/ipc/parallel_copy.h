// SPDX-License-Identifier: MIT
// Large memory copies spread over a few threads. The frame ring takes each frame's images from the
// renderer's readback buffer into shared memory: 8 MB a frame for the 1080p display image, 50 MB with the
// compositing layers, where one thread's memcpy (~6-8 GB/s) is most of a frame's time. The workers are
// made once and wait between copies; the calling thread copies a share too.
#pragma once

#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <mutex>
#include <thread>
#include <vector>

namespace sky
{

/// One copy of a batch.
struct CopyJob
{
    void* dst = nullptr;
    const void* src = nullptr;
    size_t bytes = 0;
};

class ParallelCopy
{
public:
    /// `threads` workers besides the caller (0: the caller copies everything).
    explicit ParallelCopy(unsigned threads);
    ~ParallelCopy();
    ParallelCopy(const ParallelCopy&) = delete;
    ParallelCopy& operator=(const ParallelCopy&) = delete;

    /// Copies every job (non-overlapping regions), in slices of at least kMinSliceBytes, and returns when
    /// all are done. Not reentrant: one caller at a time.
    void run(const std::vector<CopyJob>& jobs);

    static constexpr size_t kMinSliceBytes = size_t(1) << 20;

private:
    void work();
    bool takeSlice(CopyJob& slice);

    std::vector<std::thread> workers_;
    std::mutex mutex_;
    std::condition_variable wake_, done_;
    std::vector<CopyJob> slices_;  ///< what is left to copy
    size_t next_ = 0;              ///< first slice not taken
    size_t busy_ = 0;              ///< slices taken and not finished
    uint64_t generation_ = 0;      ///< +1 per run: wakes the workers
    bool stop_ = false;
};

}  // namespace sky
