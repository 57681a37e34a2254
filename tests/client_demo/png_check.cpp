// SPDX-License-Identifier: MIT
// client_demo_png_check FILE [--sky-bluish] : the end-to-end tests' picture checks, in one small tool so
// that the shell scripts need no image library.
//   always:        the PNG reads, and its pixels are not uniform (standard deviation of the luma > 4 of 255)
//                  and not black (mean luma > 10 of 255)
//   --sky-bluish:  the upper third of the right half (sky: right of the text overlay, above the horizon of
//                  a level view) has more blue than red on average
// Exit code 0 when every check holds, 1 otherwise (the failing check on stderr).
#include "skyservice/output/image_files.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>

int main(int argc, char** argv)
{
    if (argc < 2)
    {
        std::fprintf(stderr, "usage: client_demo_png_check FILE [--sky-bluish]\n");
        return 2;
    }
    const bool skyBluish = argc > 2 && std::strcmp(argv[2], "--sky-bluish") == 0;
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
            const double luma = 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
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
    return 0;
}
