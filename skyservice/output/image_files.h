// SPDX-License-Identifier: MIT
// Image and sidecar files for the file output (skyservice/ipc/PROTOCOL.md): PNG (8-bit sRGB RGBA, libpng),
// OpenEXR (half and float channels, OpenEXR 3.1 C++ API) and JSON (nlohmann). Every writer is atomic
// (skyservice/output/atomic_file.h): a reader never sees a partial file. Readers are for tests and
// tools. No function throws; errors name the file.
#pragma once

#include <nlohmann/json.hpp>

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace sky
{

/// An 8-bit RGBA image, rows top to bottom, 4 bytes per pixel (R, G, B, A), sRGB-encoded colour,
/// straight (not premultiplied) alpha.
struct ImageRgba8
{
    uint32_t width = 0;
    uint32_t height = 0;
    std::vector<uint8_t> pixels;  ///< width * height * 4 bytes

    uint8_t* pixel(uint32_t x, uint32_t y) { return pixels.data() + (size_t(y) * width + x) * 4; }
    const uint8_t* pixel(uint32_t x, uint32_t y) const { return pixels.data() + (size_t(y) * width + x) * 4; }
};

/**
 * Write a PNG file atomically.
 *
 * @param[in] path destination (its folder must exist).
 * @param[in] image the image; pixels.size() must be width * height * 4 and both sizes > 0.
 * @param[out] error on failure, a message naming the path.
 * @return true on success.
 **********************************************************************/
bool writePng(const std::string& path, const ImageRgba8& image, std::string& error);

/**
 * Read a PNG file of any colour type and bit depth, converted to 8-bit RGBA.
 *
 * @param[in] path the file.
 * @param[out] image the pixels.
 * @param[out] error on failure, a message naming the path.
 * @return true on success.
 **********************************************************************/
bool readPng(const std::string& path, ImageRgba8& image, std::string& error);

/// Storage type of an EXR channel in the file.
enum class ExrPixelType
{
    Half,   ///< 16-bit float: colour and alpha
    Float,  ///< 32-bit float: depth (half cannot hold 700 km: its largest finite value is 65504)
};

/// One channel to write: values are read as float from memory and stored as `type` in the file.
struct ExrChannel
{
    std::string name;               ///< e.g. "R", "G", "B", "A", "Z", "sky.R"
    ExrPixelType type = ExrPixelType::Half;
    const float* data = nullptr;    ///< value of pixel (0, 0); rows top to bottom; must outlive the call
    size_t pixelStrideFloats = 1;   ///< floats between neighbouring pixels (4 for interleaved RGBA)
};

/**
 * Write a scanline OpenEXR file (ZIP compression) atomically.
 *
 * @param[in] path destination (its folder must exist).
 * @param[in] width, height image size in pixels (> 0).
 * @param[in] channels channels with distinct, non-empty names; row y, column x of a channel is
 *   data[(y * width + x) * pixelStrideFloats].
 * @param[out] error on failure, a message naming the path (and the channel, if one is bad).
 * @param[in] stringAttributes extra header attributes (name, value), e.g. the view as JSON text.
 * @return true on success.
 *
 * Usual channel set (skyservice/ipc/PROTOCOL.md): R, G, B (premultiplied cloud colour) and A (1 - transmittance) as
 * half; Z (transmittance-weighted cloud depth, meters) as float; sky.R, sky.G, sky.B (final linear
 * composite) as half.
 **********************************************************************/
bool writeExr(const std::string& path, uint32_t width, uint32_t height, const std::vector<ExrChannel>& channels,
              std::string& error, const std::vector<std::pair<std::string, std::string>>& stringAttributes = {});

/// A channel read back from an EXR file.
struct ExrChannelData
{
    ExrPixelType type = ExrPixelType::Half;
    std::vector<float> values;  ///< width * height, rows top to bottom
};

/// An EXR file read back (for tests and tools).
struct ExrImage
{
    uint32_t width = 0;
    uint32_t height = 0;
    std::map<std::string, ExrChannelData> channels;       ///< by channel name
    std::map<std::string, std::string> stringAttributes;  ///< string-typed header attributes
};

/**
 * Read every HALF or FLOAT channel of a scanline or tiled OpenEXR file as float.
 *
 * @param[in] path the file.
 * @param[out] image size, channels and string attributes.
 * @param[out] error on failure, a message naming the path.
 * @return true on success.
 **********************************************************************/
bool readExr(const std::string& path, ExrImage& image, std::string& error);

/**
 * Write a JSON document (2-space indented, newline-terminated) atomically.
 *
 * @param[in] path destination (its folder must exist).
 * @param[in] document the JSON value; NaN and infinities are written as null.
 * @param[out] error on failure, a message naming the path.
 * @return true on success.
 **********************************************************************/
bool writeJsonAtomic(const std::string& path, const nlohmann::json& document, std::string& error);

}  // namespace sky
