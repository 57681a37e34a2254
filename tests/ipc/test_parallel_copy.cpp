// SPDX-License-Identifier: MIT
// The ring's parallel copy: every byte of every job lands where it belongs, batch after batch.
#include "skyservice/ipc/parallel_copy.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <numeric>
#include <vector>

namespace
{

std::vector<uint8_t> pattern(size_t bytes, uint8_t seed)
{
    std::vector<uint8_t> v(bytes);
    for (size_t i = 0; i < bytes; ++i)
        v[i] = uint8_t(i * 131u + seed + (i >> 12));
    return v;
}

}  // namespace

// Jobs smaller than a slice, spanning several slices with a remainder, and empty; the same copier reused
// for a second batch (its workers wait between batches), and with no helper thread at all.
TEST(ParallelCopy, CopiesEveryJobExactly)
{
    for (unsigned threads : {0u, 1u, 3u})
    {
        sky::ParallelCopy copier(threads);
        for (int batch = 0; batch < 2; ++batch)
        {
            const size_t sizes[] = {1000, sky::ParallelCopy::kMinSliceBytes * 5 + 12345, 0, 3 << 20};
            std::vector<std::vector<uint8_t>> sources, targets;
            std::vector<sky::CopyJob> jobs;
            for (size_t k = 0; k < 4; ++k)
            {
                sources.push_back(pattern(sizes[k], uint8_t(k * 7 + batch)));
                targets.emplace_back(sizes[k] + 16, uint8_t(0xEE));
            }
            for (size_t k = 0; k < 4; ++k)
                jobs.push_back(sky::CopyJob{targets[k].data() + 8, sources[k].data(), sizes[k]});
            copier.run(jobs);
            for (size_t k = 0; k < 4; ++k)
            {
                ASSERT_TRUE(std::equal(sources[k].begin(), sources[k].end(), targets[k].begin() + 8))
                    << "job " << k << ", " << threads << " helper threads, batch " << batch;
                for (size_t i = 0; i < 8; ++i)  // nothing written outside the job
                {
                    EXPECT_EQ(targets[k][i], 0xEE);
                    EXPECT_EQ(targets[k][sizes[k] + 8 + i], 0xEE);
                }
            }
        }
    }
}
