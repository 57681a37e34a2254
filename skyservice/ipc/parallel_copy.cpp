// SPDX-License-Identifier: MIT
#include "skyservice/ipc/parallel_copy.h"

#include <algorithm>
#include <cstring>

namespace sky
{

ParallelCopy::ParallelCopy(unsigned threads)
{
    for (unsigned i = 0; i < threads; ++i)
        workers_.emplace_back([this] { work(); });
}

ParallelCopy::~ParallelCopy()
{
    {
        std::lock_guard<std::mutex> lock(mutex_);
        stop_ = true;
    }
    wake_.notify_all();
    for (std::thread& t : workers_)
        t.join();
}

bool ParallelCopy::takeSlice(CopyJob& slice)
{
    if (next_ >= slices_.size())
        return false;
    slice = slices_[next_++];
    ++busy_;
    return true;
}

void ParallelCopy::run(const std::vector<CopyJob>& jobs)
{
    const size_t parts = workers_.size() + 1;
    std::unique_lock<std::mutex> lock(mutex_);
    slices_.clear();  // keeps its capacity: no allocation once the largest batch has been seen
    for (const CopyJob& job : jobs)
    {
        const size_t slice = std::max(kMinSliceBytes, (job.bytes + parts - 1) / parts);
        for (size_t offset = 0; offset < job.bytes; offset += slice)
            slices_.push_back(CopyJob{static_cast<uint8_t*>(job.dst) + offset,
                                      static_cast<const uint8_t*>(job.src) + offset,
                                      std::min(slice, job.bytes - offset)});
    }
    next_ = 0;
    busy_ = 0;
    ++generation_;
    if (slices_.size() > 1)
        wake_.notify_all();
    CopyJob slice;
    while (takeSlice(slice))
    {
        lock.unlock();
        std::memcpy(slice.dst, slice.src, slice.bytes);
        lock.lock();
        --busy_;
    }
    done_.wait(lock, [this] { return busy_ == 0; });
}

void ParallelCopy::work()
{
    uint64_t seen = 0;
    std::unique_lock<std::mutex> lock(mutex_);
    for (;;)
    {
        wake_.wait(lock, [&] { return stop_ || generation_ != seen; });
        if (stop_)
            return;
        seen = generation_;
        CopyJob slice;
        while (takeSlice(slice))
        {
            lock.unlock();
            std::memcpy(slice.dst, slice.src, slice.bytes);
            lock.lock();
            if (--busy_ == 0 && next_ >= slices_.size())
                done_.notify_all();
        }
    }
}

}  // namespace sky
