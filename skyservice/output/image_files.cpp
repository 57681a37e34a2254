// SPDX-License-Identifier: MIT
#include "skyservice/output/image_files.h"

#include "skyservice/output/atomic_file.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <png.h>
#include <Imath/half.h>

#include <exception>
#include <set>

namespace sky
{

bool writePng(const std::string& path, const ImageRgba8& image, std::string& error)
{
    if (image.width == 0 || image.height == 0 || image.pixels.size() != size_t(image.width) * image.height * 4)
    {
        error = "cannot write '" + path + "': image size " + std::to_string(image.width) + "x" +
                std::to_string(image.height) + " does not match its " + std::to_string(image.pixels.size()) +
                " bytes of RGBA pixels";
        return false;
    }
    png_image info{};
    info.version = PNG_IMAGE_VERSION;
    info.width = image.width;
    info.height = image.height;
    info.format = PNG_FORMAT_RGBA;
    png_alloc_size_t bytes = 0;
    if (!png_image_write_get_memory_size(info, bytes, 0, image.pixels.data(), 0, nullptr))
    {
        error = "cannot write '" + path + "': libpng: " + info.message;
        png_image_free(&info);
        return false;
    }
    std::vector<uint8_t> encoded(bytes);
    if (!png_image_write_to_memory(&info, encoded.data(), &bytes, 0, image.pixels.data(), 0, nullptr))
    {
        error = "cannot write '" + path + "': libpng: " + info.message;
        png_image_free(&info);
        return false;
    }
    encoded.resize(bytes);
    return writeFileAtomic(path, encoded.data(), encoded.size(), error);
}

bool readPng(const std::string& path, ImageRgba8& image, std::string& error)
{
    png_image info{};
    info.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_file(&info, path.c_str()))
    {
        error = "cannot read '" + path + "': libpng: " + info.message;
        png_image_free(&info);
        return false;
    }
    info.format = PNG_FORMAT_RGBA;
    image.width = info.width;
    image.height = info.height;
    image.pixels.assign(PNG_IMAGE_SIZE(info), 0);
    if (!png_image_finish_read(&info, nullptr, image.pixels.data(), 0, nullptr))
    {
        error = "cannot read '" + path + "': libpng: " + info.message;
        png_image_free(&info);
        image = {};
        return false;
    }
    return true;
}

bool writeExr(const std::string& path, uint32_t width, uint32_t height, const std::vector<ExrChannel>& channels,
              std::string& error, const std::vector<std::pair<std::string, std::string>>& stringAttributes)
{
    if (width == 0 || height == 0 || width > uint32_t(INT32_MAX) || height > uint32_t(INT32_MAX))
    {
        error = "cannot write '" + path + "': bad image size " + std::to_string(width) + "x" + std::to_string(height);
        return false;
    }
    std::set<std::string> names;
    for (const ExrChannel& channel : channels)
    {
        if (channel.name.empty() || channel.data == nullptr || channel.pixelStrideFloats == 0 ||
            !names.insert(channel.name).second)
        {
            error = "cannot write '" + path + "': channel '" + channel.name +
                    "' is unnamed, duplicated, has no data or a zero stride";
            return false;
        }
    }
    const FileWriter writer = [&](const std::string& tempPath, std::string& writerError) {
        try
        {
            Imf::Header header(static_cast<int>(width), static_cast<int>(height));
            header.compression() = Imf::ZIP_COMPRESSION;
            for (const auto& [name, value] : stringAttributes)
                header.insert(name, Imf::StringAttribute(value));
            Imf::FrameBuffer frameBuffer;
            // OpenEXR converts pixel types when reading but not when writing: half channels are
            // converted here, float channels are passed in place with their stride.
            std::vector<std::vector<half>> halves;
            halves.reserve(channels.size());
            const size_t pixels = size_t(width) * height;
            for (const ExrChannel& channel : channels)
            {
                if (channel.type == ExrPixelType::Half)
                {
                    header.channels().insert(channel.name, Imf::Channel(Imf::HALF));
                    std::vector<half>& converted = halves.emplace_back(pixels);
                    for (size_t p = 0; p < pixels; ++p)
                        converted[p] = half(channel.data[p * channel.pixelStrideFloats]);
                    frameBuffer.insert(channel.name, Imf::Slice(Imf::HALF, reinterpret_cast<char*>(converted.data()),
                                                                sizeof(half), sizeof(half) * width));
                }
                else
                {
                    header.channels().insert(channel.name, Imf::Channel(Imf::FLOAT));
                    const size_t xStride = channel.pixelStrideFloats * sizeof(float);
                    frameBuffer.insert(channel.name,
                                       Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(const_cast<float*>(channel.data)),
                                                  xStride, xStride * width));
                }
            }
            Imf::OutputFile file(tempPath.c_str(), header);
            file.setFrameBuffer(frameBuffer);
            file.writePixels(int(height));
            return true;
        }
        catch (const std::exception& e)
        {
            writerError = std::string("OpenEXR: ") + e.what();
            return false;
        }
    };
    return writeFileAtomicWith(path, writer, error);
}

bool readExr(const std::string& path, ExrImage& image, std::string& error)
{
    image = {};
    try
    {
        Imf::InputFile file(path.c_str());
        const Imf::Header& header = file.header();
        const Imath::Box2i window = header.dataWindow();
        const int64_t width = int64_t(window.max.x) - window.min.x + 1;
        const int64_t height = int64_t(window.max.y) - window.min.y + 1;
        image.width = uint32_t(width);
        image.height = uint32_t(height);
        Imf::FrameBuffer frameBuffer;
        for (auto it = header.channels().begin(); it != header.channels().end(); ++it)
        {
            ExrChannelData& data = image.channels[it.name()];
            data.type = it.channel().type == Imf::HALF ? ExrPixelType::Half : ExrPixelType::Float;
            data.values.assign(size_t(width * height), 0.0f);
            frameBuffer.insert(it.name(), Imf::Slice::Make(Imf::FLOAT, data.values.data(), window.min, width, height));
        }
        for (auto it = header.begin(); it != header.end(); ++it)
            if (const auto* text = dynamic_cast<const Imf::StringAttribute*>(&it.attribute()))
                image.stringAttributes[it.name()] = text->value();
        file.setFrameBuffer(frameBuffer);
        file.readPixels(window.min.y, window.max.y);
        return true;
    }
    catch (const std::exception& e)
    {
        error = "cannot read '" + path + "': OpenEXR: " + e.what();
        image = {};
        return false;
    }
}

bool writeJsonAtomic(const std::string& path, const nlohmann::json& document, std::string& error)
{
    // Replace invalid UTF-8 rather than throw: a sidecar with one odd character beats no sidecar.
    const std::string text = document.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
    return writeFileAtomic(path, text.data(), text.size(), error);
}

}  // namespace sky
