// SPDX-License-Identifier: MIT
// client_demo_png_check FILE [--sky-bluish | --darker-than OTHER X0 Y0 X1 Y1 RATIO] : the end-to-end tests'
// picture checks, in one small tool so that the shell scripts need no image library.
//   always:        the PNG reads, and its pixels are not uniform (standard deviation of the luma > 4 of 255)
//                  and not black (mean luma > 10 of 255)
//   --sky-bluish:  the upper third of the right half (sky: right of the text overlay, above the horizon of
//                  a level view) has more blue than red on average
//   --darker-than: the box of columns X0..X1, rows Y0..Y1 (inclusive) has a mean luma below RATIO times the
//                  same box's in the PNG OTHER (something dark drawn where OTHER shows sky)
// Exit code 0 when every check holds, 1 otherwise (the failing check on stderr).
#include "skyservice/output/image_files.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <cstring>
#include <string>

namespace
{

double lumaOf(const uint8_t* p) { return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]; }

// Mean luma of columns x0..x1, rows y0..y1 (clipped to the image); -1 when the box is empty.
double boxLuma(const sky::ImageRgba8& image, long x0, long y0, long x1, long y1)
{
    double sum = 0.0;
    long count = 0;
    for (long y = std::max(y0, 0L); y <= std::min(y1, long(image.height) - 1); ++y)
        for (long x = std::max(x0, 0L); x <= std::min(x1, long(image.width) - 1); ++x, ++count)
            sum += lumaOf(image.pixel(uint32_t(x), uint32_t(y)));
    return count > 0 ? sum / double(count) : -1.0;
}

}  // namespace

int main(int argc, char** argv)
{
    const bool skyBluish = argc == 3 && std::strcmp(argv[2], "--sky-bluish") == 0;
    const bool darkerThan = argc == 9 && std::strcmp(argv[2], "--darker-than") == 0;
    if (argc < 2 || (argc > 2 && !skyBluish && !darkerThan))
    {
        std::fprintf(stderr,
                     "usage: client_demo_png_check FILE [--sky-bluish | --darker-than OTHER X0 Y0 X1 Y1 RATIO]\n");
        return 2;
    }
    sky::ImageRgba8 image;
    std::string error;
    if (!sky::readPng(argv[1], image, error))
    {
        std::fprintf(stderr, "%s\n", error.c_str());
        return 1;
    }
    double sum = 0.0;
    double sum2 = 0.0;
    const double n = double(image.width) * image.height;
    for (uint32_t y = 0; y < image.height; ++y)
        for (uint32_t x = 0; x < image.width; ++x)
        {
            const uint8_t* p = image.pixel(x, y);
            const double luma = lumaOf(p);
            sum += luma;
            sum2 += luma * luma;
        }
    const double mean = sum / n;
    const double deviation = std::sqrt(std::max(0.0, sum2 / n - mean * mean));
    std::printf("%s: %ux%u, mean luma %.1f, deviation %.1f\n", argv[1], image.width, image.height, mean, deviation);
    if (mean <= 10.0)
    {
        std::fprintf(stderr, "%s is black (mean luma %.1f)\n", argv[1], mean);
        return 1;
    }
    if (deviation <= 4.0)
    {
        std::fprintf(stderr, "%s is uniform (luma deviation %.1f)\n", argv[1], deviation);
        return 1;
    }
    if (skyBluish)
    {
        double red = 0.0;
        double blue = 0.0;
        for (uint32_t y = 0; y < image.height / 3; ++y)
            for (uint32_t x = image.width / 2; x < image.width; ++x)
            {
                red += image.pixel(x, y)[0];
                blue += image.pixel(x, y)[2];
            }
        std::printf("sky: red %.0f, blue %.0f (sums)\n", red, blue);
        if (!(blue > red))
        {
            std::fprintf(stderr, "%s: the sky is not bluish (red %.0f >= blue %.0f)\n", argv[1], red, blue);
            return 1;
        }
    }
    if (darkerThan)
    {
        sky::ImageRgba8 other;
        if (!sky::readPng(argv[3], other, error))
        {
            std::fprintf(stderr, "%s\n", error.c_str());
            return 1;
        }
        const long x0 = std::atol(argv[4]);
        const long y0 = std::atol(argv[5]);
        const long x1 = std::atol(argv[6]);
        const long y1 = std::atol(argv[7]);
        const double ratio = std::atof(argv[8]);
        const double here = boxLuma(image, x0, y0, x1, y1);
        const double there = boxLuma(other, x0, y0, x1, y1);
        std::printf("box %ld,%ld..%ld,%ld: mean luma %.1f here, %.1f in %s\n", x0, y0, x1, y1, here, there, argv[3]);
        if (here < 0.0 || there < 0.0 || !(here < ratio * there))
        {
            std::fprintf(stderr, "%s: the box %ld,%ld..%ld,%ld is not darker than %.2f x %s's (%.1f vs %.1f)\n",
                         argv[1], x0, y0, x1, y1, ratio, argv[3], here, there);
            return 1;
        }
    }
    return 0;
}
