// SPDX-License-Identifier: MIT
#include "skyservice/sky/blue_noise.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <utility>

namespace sky
{
namespace
{

// Gaussian energy filter width from Ulichney 1993 (sigma = 1.5 gives the best-looking masks there).
constexpr double kSigmaTexels = 1.5;
// Ulichney starts from a random pattern with about 10% of the texels set (the "minority pixels").
constexpr uint32_t kInitialFillDivisor = 10;

// SplitMix64 (Steele, Lea & Flood, OOPSLA 2014): a fully specified generator, so masks are identical
// on every platform (std::uniform_int_distribution is not).
struct SplitMix64
{
    uint64_t state;
    uint64_t next()
    {
        uint64_t z = (state += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
};

// Beyond 6 sigma the Gaussian weight is below 2e-8 of the centre's: the kernel is cut there.
constexpr int kKernelRadius = 9;

// Binary pattern plus the Gaussian energy of its set texels at every texel, on a torus. Toggling a
// texel updates the energy incrementally over the kernel's window, so a step costs O(size^2) only for
// the search.
class VoidAndCluster
{
public:
    explicit VoidAndCluster(uint32_t size) : size_(int(size)), energy_(size_t(size) * size), bits_(energy_.size())
    {
        // Every toroidal offset once: a window of +-kKernelRadius, or the whole torus when it is smaller.
        const bool window = size_ > 2 * kKernelRadius;
        const int lo = window ? -kKernelRadius : 0;
        const int hi = window ? kKernelRadius : size_ - 1;
        for (int dy = lo; dy <= hi; ++dy)
            for (int dx = lo; dx <= hi; ++dx)
            {
                const int tx = std::min(std::abs(dx), size_ - std::abs(dx));  // toroidal distance
                const int ty = std::min(std::abs(dy), size_ - std::abs(dy));
                const double r2 = double(tx * tx + ty * ty);
                kernel_.push_back({dx, dy, std::exp(-r2 / (2.0 * kSigmaTexels * kSigmaTexels))});
            }
    }

    void set(size_t index, bool value)
    {
        if (bool(bits_[index]) == value)
            return;
        bits_[index] = value ? 1 : 0;
        const double sign = value ? 1.0 : -1.0;
        const int qx = int(index % size_t(size_));
        const int qy = int(index / size_t(size_));
        for (const KernelTap& tap : kernel_)
        {
            const int x = (qx + tap.dx + size_) % size_;
            const int y = (qy + tap.dy + size_) % size_;
            energy_[size_t(y) * size_t(size_) + size_t(x)] += sign * tap.weight;
        }
    }

    /// Set texel with the highest energy (the tightest cluster); the lowest index wins ties.
    size_t tightestCluster() const
    {
        size_t best = 0;
        double bestEnergy = -std::numeric_limits<double>::infinity();
        for (size_t i = 0; i < energy_.size(); ++i)
            if (bits_[i] && energy_[i] > bestEnergy)
            {
                bestEnergy = energy_[i];
                best = i;
            }
        return best;
    }

    /// Unset texel with the lowest energy (the largest void); the lowest index wins ties.
    size_t largestVoid() const
    {
        size_t best = 0;
        double bestEnergy = std::numeric_limits<double>::infinity();
        for (size_t i = 0; i < energy_.size(); ++i)
            if (!bits_[i] && energy_[i] < bestEnergy)
            {
                bestEnergy = energy_[i];
                best = i;
            }
        return best;
    }

private:
    struct KernelTap
    {
        int dx;
        int dy;
        double weight;
    };
    int size_;
    std::vector<KernelTap> kernel_;
    std::vector<double> energy_;
    std::vector<uint8_t> bits_;
};

}  // namespace

std::vector<uint8_t> makeBlueNoise(uint32_t size, uint32_t seed)
{
    if (size < 4)
        throw std::invalid_argument("makeBlueNoise: size must be at least 4 texels");
    const size_t count = size_t(size) * size;
    const size_t initialOnes = std::max<size_t>(1, count / kInitialFillDivisor);

    // Random initial pattern: the first initialOnes texels of a seeded Fisher-Yates shuffle.
    SplitMix64 rng{uint64_t(seed) * 0x2545F4914F6CDD1Dull + 1};
    std::vector<size_t> order(count);
    for (size_t i = 0; i < count; ++i)
        order[i] = i;
    for (size_t i = count - 1; i > 0; --i)
        std::swap(order[i], order[size_t(rng.next() % (i + 1))]);
    VoidAndCluster prototype(size);
    for (size_t i = 0; i < initialOnes; ++i)
        prototype.set(order[i], true);

    // Relax into the initial binary pattern: move the tightest cluster into the largest void until the
    // move would put it back where it was (bounded, in case of a cycle between equal energies).
    for (size_t iteration = 0; iteration < count; ++iteration)
    {
        const size_t cluster = prototype.tightestCluster();
        prototype.set(cluster, false);
        const size_t hole = prototype.largestVoid();
        prototype.set(hole, true);
        if (hole == cluster)
            break;
    }

    std::vector<size_t> rank(count, 0);
    // Phase 1: remove the tightest clusters one by one, ranks initialOnes-1 down to 0.
    VoidAndCluster removing = prototype;
    for (size_t r = initialOnes; r-- > 0;)
    {
        const size_t cluster = removing.tightestCluster();
        removing.set(cluster, false);
        rank[cluster] = r;
    }
    // Phases 2 and 3: fill the largest voids, ranks initialOnes up to count-1. Past half full Ulichney
    // switches to the tightest cluster of the unset texels; with a linear filter that is the unset texel
    // of lowest energy, i.e. the same largest-void rule.
    VoidAndCluster filling = std::move(prototype);
    for (size_t r = initialOnes; r < count; ++r)
    {
        const size_t hole = filling.largestVoid();
        filling.set(hole, true);
        rank[hole] = r;
    }

    std::vector<uint8_t> mask(count);
    for (size_t i = 0; i < count; ++i)
        mask[i] = uint8_t(rank[i] * 256 / count);
    return mask;
}

}  // namespace sky
